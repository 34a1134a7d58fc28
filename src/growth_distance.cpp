#include "growth_distance.hpp"

#include "minkowski.hpp"

#include <cmath>

namespace gdc::detail {
namespace {

SimplexClosest vertexResult(const Vec3& p, int index) {
    SimplexClosest r;
    r.closest = p;
    r.count = 1;
    r.used[0] = index;
    r.weights[0] = 1;
    return r;
}

SimplexClosest segmentResult(const Vec3& a, const Vec3& b, int ia, int ib) {
    Vec3 ab = b - a;
    double length2 = ab.squaredNorm();
    double t = length2 > 0 ? -a.dot(ab) / length2 : 0;
    if (t <= 0) return vertexResult(a, ia);
    if (t >= 1) return vertexResult(b, ib);
    SimplexClosest r;
    r.closest = a + t * ab;
    r.count = 2;
    r.used = {ia, ib, 0, 0};
    r.weights = {1 - t, t, 0, 0};
    return r;
}

// Closest point of a triangle to the origin by Voronoi regions (Ericson, Real-Time Collision
// Detection, §5.1.5), keeping only the vertices of the region it falls in.
SimplexClosest triangleResult(const Vec3& a, const Vec3& b, const Vec3& c, int ia, int ib, int ic) {
    Vec3 ab = b - a, ac = c - a;
    double d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0 && d2 <= 0) return vertexResult(a, ia);
    double d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0 && d4 <= d3) return vertexResult(b, ib);
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return segmentResult(a, b, ia, ib);
    double d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0 && d5 <= d6) return vertexResult(c, ic);
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return segmentResult(a, c, ia, ic);
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return segmentResult(b, c, ib, ic);
    double sum = va + vb + vc;
    if (!(sum > 0)) return segmentResult(a, b, ia, ib);  // degenerate (collinear) triangle
    double v = vb / sum, w = vc / sum;
    SimplexClosest r;
    r.closest = a + v * ab + w * ac;
    r.count = 3;
    r.used = {ia, ib, ic, 0};
    r.weights = {1 - v - w, v, w, 0};
    return r;
}

SimplexClosest tetrahedronResult(const std::array<Vec3, 4>& p) {
    static constexpr int faces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
    SimplexClosest best;
    double bestDistance = INFINITY;
    bool outsideAny = false;
    const double volume = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]));
    for (const auto& f : faces) {
        Vec3 normal = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]);
        double originSide = -normal.dot(p[f[0]]);
        double oppositeSide = normal.dot(p[f[3]] - p[f[0]]);
        // The origin is outside this face when it lies on the other side from the fourth vertex;
        // a flat tetrahedron (volume ≈ 0) has every face tested.
        bool outside = originSide * oppositeSide < 0 || std::abs(volume) < 1e-14 * normal.squaredNorm();
        if (!outside) continue;
        outsideAny = true;
        SimplexClosest r = triangleResult(p[f[0]], p[f[1]], p[f[2]], f[0], f[1], f[2]);
        double distance = r.closest.squaredNorm();
        if (distance < bestDistance) bestDistance = distance, best = r;
    }
    if (outsideAny) return best;
    // The origin is inside: barycentric coordinates from signed volumes.
    SimplexClosest r;
    r.count = 4;
    r.used = {0, 1, 2, 3};
    for (int i = 0; i < 4; ++i) {
        std::array<Vec3, 4> q = p;
        q[i] = Vec3::Zero();
        r.weights[i] = (q[1] - q[0]).dot((q[2] - q[0]).cross(q[3] - q[0])) / volume;
    }
    return r;
}

}  // namespace

SimplexClosest closestPointToOrigin(const std::array<Vec3, 4>& points, int count) {
    switch (count) {
        case 1: return vertexResult(points[0], 0);
        case 2: return segmentResult(points[0], points[1], 0, 1);
        case 3: return triangleResult(points[0], points[1], points[2], 0, 1, 2);
        default: return tetrahedronResult(points);
    }
}

GrowthDistance growthDistance(const Polytope& a, const Polytope& b, const Pose& bInA, const Settings& settings) {
    GrowthDistance result;
    const MinkowskiDifference difference(a, b, bInA, settings.bruteForceSupportLimit);
    const Vec3 centreOffset = difference.centreB - difference.centreA;  // p_B − p_A
    const double size = a.radius() + b.radius();
    const double separation = centreOffset.norm();
    if (!(separation > 1e-12 * size)) return result;  // coincident contraction points: no ray direction

    // C = (A − p_A) − (B − p_B) contains the origin; its exit point along w is the growth touch.
    const Vec3 w = centreOffset / separation;
    auto support = [&](const Vec3& direction) { return difference.centred(direction); };
    // Start outside C on the ray's line: beyond C's support plane in direction w.
    const double start = w.dot(support(w).point) + 0.5 * size;
    const Vec3 origin = start * w;
    RayCastResult cast = gjkRayCast(support, origin, -w, settings.rayCastTolerance * size,
                                    settings.maxRayCastIterations);
    result.iterations = cast.iterations;
    if (!cast.hit || !(cast.normal.squaredNorm() > 0) || !cast.normal.allFinite()) return result;
    const double exitDistance = start - cast.lambda;  // h
    if (!(exitDistance > 0)) return result;
    result.valid = true;
    result.normal = cast.normal.normalized();
    result.growth = separation / exitDistance;
    result.witnessA.setZero();
    result.witnessB.setZero();
    for (int i = 0; i < cast.simplexCount; ++i) {
        result.witnessA += cast.weights[i] * a.vertices()[cast.simplex[i].vertexA];
        result.witnessB += cast.weights[i] * difference.vertexB(cast.simplex[i].vertexB);
    }
    return result;
}

}  // namespace gdc::detail
