#include "geometry/growth_distance.hpp"

#include "geometry/minkowski.hpp"

#include <algorithm>
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
// Detection, §5.1.5), keeping only the vertices of the region it falls in; inside, the projection
// along the triangle's normal.
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
    // Inside the triangle the closest point is the origin's projection on its plane, computed from
    // the plane's normal rather than as a + v·ab + w·ac. The weights come from differences of
    // products of dot products (va, vb, vc) that cancel on a long thin triangle — the facets and
    // chords of A − B a needle makes, 700 long and 1e-3 from the origin — and their rounding times
    // the edge length turned v up to 7e-5 rad away from perpendicular to the triangle. The cast then
    // found a support point of its own simplex behind v (v·w ≤ 0 with |v| still 2·10^4 tolerances),
    // stalled 1.5e-6 of the size short of the exit, restarted into the same triangle, and returned
    // the normal of an earlier advance 0.05 rad from the exit facet: collide(A, B) and
    // collide(B, A) chose a face in one order and an edge in the other (issue 21, oracle seeds
    // 30651115 and 30662339). The cross product's rounding is relative to the triangle's area,
    // whatever its length, so v stays perpendicular to the plane (tests/growth_distance_test.cpp:
    // within 1e-11 of the extent, the barycentric form up to 3e-9 off). The weights stay
    // barycentric: they only place the witnesses.
    const Vec3 normal = ab.cross(ac);
    const double normalSquared = normal.squaredNorm();
    r.closest = normalSquared > 0 ? Vec3(normal * (normal.dot(a) / normalSquared)) : Vec3(a + v * ab + w * ac);
    r.count = 3;
    r.used = {ia, ib, ic, 0};
    r.weights = {1 - v - w, v, w, 0};
    return r;
}

SimplexClosest tetrahedronResult(const std::array<Vec3, 4>& p) {
    static constexpr int faces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
    const double volume = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]));
    // Flat when a vertex's height over the opposite face is below 1e-14 of the tetrahedron's
    // extent (volume = height·|face normal|): relative to its own size, so a tetrahedron of a pair
    // 1e-3 in size is judged as one of size 1. (It compared volume, a length cubed, with the face
    // normal squared, a length to the fourth: below size 1 no tetrahedron was ever flat, issue 21.)
    // Squared on both sides (no square roots): volume² < (1e-14)²·|normal|²·extent².
    double extentSquared = 0;
    for (int i = 1; i < 4; ++i) extentSquared = std::max(extentSquared, (p[i] - p[0]).squaredNorm());
    const double flatScale = 1e-28 * extentSquared, volumeSquared = volume * volume;
    auto closestOnFaces = [&](bool everyFace) {
        SimplexClosest best;
        double bestDistance = INFINITY;
        bool outsideAny = false;
        for (const auto& f : faces) {
            Vec3 normal = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]);
            double originSide = -normal.dot(p[f[0]]);
            double oppositeSide = normal.dot(p[f[3]] - p[f[0]]);
            // The origin is outside this face when it lies on the other side from the fourth
            // vertex; a flat tetrahedron has every face tested.
            bool outside = everyFace || originSide * oppositeSide < 0 || volumeSquared < flatScale * normal.squaredNorm();
            if (!outside) continue;
            outsideAny = true;
            SimplexClosest r = triangleResult(p[f[0]], p[f[1]], p[f[2]], f[0], f[1], f[2]);
            double distance = r.closest.squaredNorm();
            if (distance < bestDistance) bestDistance = distance, best = r;
        }
        return std::make_pair(outsideAny, best);
    };
    if (auto [outsideAny, best] = closestOnFaces(false); outsideAny) return best;
    // The origin is inside: barycentric coordinates from signed volumes.
    SimplexClosest r;
    r.count = 4;
    r.used = {0, 1, 2, 3};
    bool weightsValid = true;
    for (int i = 0; i < 4; ++i) {
        std::array<Vec3, 4> q = p;
        q[i] = Vec3::Zero();
        r.weights[i] = (q[1] - q[0]).dot((q[2] - q[0]).cross(q[3] - q[0])) / volume;
        weightsValid &= r.weights[i] >= -1e-9 && r.weights[i] <= 1 + 1e-9;
    }
    // Inside means convex weights. A nearly flat tetrahedron that passed the test above can still
    // give weights of ±1600 (a parallelogram facet of A − B, from two parallel edges: a needle's):
    // they put the cast's witness points far outside both bodies (issue 21, the contact 0.9 of a
    // needle's length away). Then the origin is on the flat tetrahedron's boundary, within rounding:
    // the closest point of its faces, with convex weights.
    if (weightsValid) return r;
    return closestOnFaces(true).second;
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

namespace {

// Where the ray from the origin along the unit `direction` leaves the convex set of `support`
// (which contains the origin): a GJK ray cast fired back from beyond the set's support plane in
// that direction, so the cast always starts outside. `exitDistance` = start − lambda.
template <class Support>
RayCastResult castExitAlong(const Support& support, const Vec3& direction, double size, const Settings& settings,
                            double& exitDistance) {
    const double start = direction.dot(support(direction).point) + 0.5 * size;
    RayCastResult cast = gjkRayCast(support, start * direction, -direction, settings.rayCastTolerance * size,
                                    settings.maxRayCastIterations);
    exitDistance = start - cast.lambda;
    return cast;
}

// The points of A and B (A's frame) whose difference is the cast's hit, from its final simplex.
void castWitnesses(const RayCastResult& cast, const MinkowskiDifference& difference, Vec3& onA, Vec3& onB) {
    onA.setZero();
    onB.setZero();
    for (int i = 0; i < cast.simplexCount; ++i) {
        onA += cast.weights[i] * difference.a.vertices()[cast.simplex[i].vertexA];
        onB += cast.weights[i] * difference.vertexB(cast.simplex[i].vertexB);
    }
}

}  // namespace

// Two boxes: C = A − B is a zonotope generated by the six half-edges of the boxes, so it is the
// intersection of the slabs |n·x| ≤ h_C(n) over its facet normals — the 3 + 3 face normals and the
// 9 edge–edge cross products. The ray along w leaves C through the slab it crosses first: the exact
// exit, without iterating (the same quantity the ray cast converges to). h_C(n) = halfA·|n| +
// halfB·|Rᵀn|, and Rᵀ of each axis is known without the product: Rᵀe_i is row i of R, Rᵀ(column
// j) = e_j, and Rᵀ(e_i × column j) = (row i) × e_j (up to a sign, which the absolute value drops).
// The facet normals e_i × (column j of R) and (row i of R) × e_j each have one zero component, so
// their cross products, norms and dot products are written out on the other two. A ray through an
// edge or corner of C leaves several slabs at once; any normal of that cone is valid, and the sum
// of the tied facet normals is the one in its middle (what the ray cast converges to for a
// symmetric pose, and the one that finds edge–edge contacts). Along a face axis n the boxes overlap
// by h_C(n) − |n·(p_B − p_A)| in the nearer direction and by more in the other: the least of these
// over the six face axes bounds every face normal's overlap from below. tests/box_box_test.cpp
// checks both against the 15 axes evaluated directly.
BoxGrowth boxGrowth(const Vec3& halfA, const Vec3& halfB, const Mat3& rotationB, const Vec3& centreOffset,
                    double separation, double size) {
    BoxGrowth result;
    if (!(separation > 1e-12 * size)) return result;  // coincident contraction points
    const Vec3 w = centreOffset / separation;
    const Mat3 absoluteR = rotationB.cwiseAbs();
    // The gauge: the ray leaves through the facet of least h_C(m)/|m·w|, and that ratio does not
    // depend on the length of m, so an edge axis is compared unnormalised — no square root, no
    // division — and ratios are compared by cross-multiplication: the exit so far is the fraction
    // exitSupport/exitAlong (1/0: none yet, an infinite distance), and distance s/a lies below
    // D·(1 − ε) exactly when s·exitAlong < exitSupport·a·(1 − ε) (a, exitAlong ≥ 0). Only a facet
    // that becomes, or ties, the exit has its unit normal made (`normal()`).
    double exitSupport = 1, exitAlong = 0;
    Vec3 tiedNormals = Vec3::Zero();
    // `along` = m·w, `supportValue` = h_C(m), `lengthSquared()` = |m|² (1 for a face axis).
    // A facet beyond the exit so far by more than the tie band is neither a new exit nor a tie,
    // whatever its guards (a parallel edge pair, a ray along the slab) would say — they only ever
    // drop a facet, and exit·(1 + 1e-12) ≥ exit·(1 − 1e-12) as exit ≥ 0 — so that test comes first
    // and most facets pay neither |m|² nor the guards (a NaN fails it and takes the guards' path,
    // as the guards decide).
    auto consider = [&](double along, double supportValue, auto&& lengthSquared, auto&& normal) {
        const double a = std::abs(along);
        const double distance = supportValue * exitAlong, exit = exitSupport * a;  // both scaled by a·exitAlong
        if (distance > exit * (1 + 1e-12)) return;
        const double squared = lengthSquared();
        if (!(squared > 1e-18)) return;  // parallel edges (|m| ≤ 1e-9): covered by the face normals
        if (a * a < 1e-24 * squared) return;  // |m̂·w| < 1e-12: the ray runs along the slab
        if (distance < exit * (1 - 1e-12)) {
            const Vec3 n = normal(squared);
            const Vec3 outward = along > 0 ? n : -n;
            if (distance > exit * (1 - 2e-12)) tiedNormals += outward;
            else tiedNormals = outward;
            exitSupport = supportValue, exitAlong = a;
        } else {  // distance ≤ exit·(1 + 1e-12), the first test
            const Vec3 n = normal(squared);
            tiedNormals += along > 0 ? n : -n;
        }
    };
    const auto unitLength = [] { return 1.0; };
    double faceOverlap = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const double supportValue = halfA[i] + halfB.dot(absoluteR.row(i).transpose());
        faceOverlap = std::min(faceOverlap, supportValue - std::abs(centreOffset[i]));
        consider(w[i], supportValue, unitLength, [&](double) { return Vec3(Vec3::Unit(i)); });
    }
    for (int j = 0; j < 3; ++j) {
        const Vec3 n = rotationB.col(j);
        const double supportValue = halfA.dot(absoluteR.col(j)) + halfB[j];
        faceOverlap = std::min(faceOverlap, supportValue - std::abs(n.dot(centreOffset)));
        consider(n.dot(w), supportValue, unitLength, [&](double) { return n; });
    }
    // The nine edge facets m = e_i × (column j of R): m[i1] = n1 = −R(i2, j), m[i2] = n2 = R(i1, j)
    // ((i, i1, i2) cyclic), with h_C(m) = (halfA[i1]·|n1| + halfA[i2]·|n2|) + (halfB[j1]·|R(i, j2)| +
    // halfB[j2]·|R(i, j1)|) (Rᵀm = (row i) × e_j has components R(i, j2) at j1 and −R(i, j1) at j2)
    // and m·w = n1·w[i1] + n2·w[i2]. Rows i = 0 and 1 of a column are made two at a time, packed
    // (their R and |R| entries are neighbours in the column), row 2 on its own: each number the same
    // products summed in the same order as one at a time, so the same double; then considered in
    // the order of the loop this replaced (i, then j).
    using Pair = Eigen::Array2d;
    const Pair halfANext(halfA[1], halfA[2]), halfAPrevious(halfA[2], halfA[0]);  // halfA[i1], halfA[i2]
    const Pair wNext(w[1], w[2]), wPrevious(w[2], w[0]);                          // w[i1], w[i2]
    double first[3][3], second[3][3], support[3][3], along[3][3];                 // n1, n2, h_C(m), m·w
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) {
        const int j1 = j == 2 ? 0 : j + 1, j2 = j == 0 ? 2 : j - 1;
        const Pair n1 = -Pair(rotationB(2, j), rotationB(0, j));
        const Pair n2 = rotationB.col(j).segment<2>(1).array();
        const Pair s = (halfANext * n1.abs() + halfAPrevious * n2.abs()) +
                       (halfB[j1] * absoluteR.col(j2).head<2>().array() + halfB[j2] * absoluteR.col(j1).head<2>().array());
        const Pair a = n1 * wNext + n2 * wPrevious;
        first[0][j] = n1[0], first[1][j] = n1[1], second[0][j] = n2[0], second[1][j] = n2[1];
        support[0][j] = s[0], support[1][j] = s[1], along[0][j] = a[0], along[1][j] = a[1];
        // Row 2: i1 = 0, i2 = 1.
        const double m1 = -rotationB(1, j), m2 = rotationB(0, j);
        first[2][j] = m1, second[2][j] = m2;
        support[2][j] = halfA[0] * std::abs(m1) + halfA[1] * std::abs(m2) +
                        (halfB[j1] * absoluteR(2, j2) + halfB[j2] * absoluteR(2, j1));
        along[2][j] = m1 * w[0] + m2 * w[1];
    }
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
        const int i1 = i == 2 ? 0 : i + 1, i2 = i == 0 ? 2 : i - 1;
#pragma GCC unroll 3
        for (int j = 0; j < 3; ++j) {
            const double n1 = first[i][j], n2 = second[i][j];
            consider(
                along[i][j], support[i][j], [&] { return n1 * n1 + n2 * n2; },
                [&](double lengthSquared) {
                    const double length = std::sqrt(lengthSquared);
                    Vec3 n = Vec3::Zero();
                    n[i1] = n1 / length, n[i2] = n2 / length;
                    return n;
                });
        }
    }
    const double exitDistance = exitSupport / exitAlong;
    // |tiedNormals| once, for the test and the normalisation (what normalized() computes).
    const double tiedSquared = tiedNormals.squaredNorm();
    const double tiedLength = std::sqrt(tiedSquared);
    result.valid = std::isfinite(exitDistance) && exitDistance > 0 && tiedLength > 1e-6;
    result.normal = tiedSquared > 0 ? Vec3(tiedNormals / tiedLength) : tiedNormals;
    result.faceOverlapLowerBound = faceOverlap;
    result.exitDistance = exitDistance;
    return result;
}

GrowthDistance growthDistance(const Polytope& a, const Polytope& b, const Pose& bInA, const Settings& settings,
                              bool needWitnesses) {
    return growthDistance(MinkowskiDifference(a, b, bInA, settings.bruteForceSupportLimit), settings, needWitnesses);
}

GrowthDistance growthDistance(const MinkowskiDifference& difference, const Settings& settings, bool needWitnesses) {
    GrowthDistance result;
    const Polytope& a = difference.a;
    const Polytope& b = difference.b;
    const Pose& bInA = difference.bInA;
    const Vec3 centreOffset = difference.centreB - difference.centreA;  // p_B − p_A
    const double size = a.radius() + b.radius();
    const double separation = centreOffset.norm();
    if (!(separation > 1e-12 * size)) return result;  // coincident contraction points: no ray direction

    // C = (A − p_A) − (B − p_B) contains the origin; its exit point along w is the growth touch.
    const Vec3 w = centreOffset / separation;
    if (a.isBox() && b.isBox() && !needWitnesses)
    {
        const BoxGrowth box =
            boxGrowth(a.boxHalfExtents(), b.boxHalfExtents(), bInA.rotation, centreOffset, separation, size);
        result.valid = box.valid;
        result.normal = box.normal;
        result.growth = separation / box.exitDistance;
        result.faceOverlapLowerBound = box.faceOverlapLowerBound;
        return result;
    }
    auto support = [&](const Vec3& direction) { return difference.centred(direction); };
    double exitDistance = 0;  // h
    RayCastResult cast = castExitAlong(support, w, size, settings, exitDistance);
    result.iterations = cast.iterations;
    if (!cast.hit || !(cast.normal.squaredNorm() > 0) || !cast.normal.allFinite()) return result;
    if (!(exitDistance > 0)) return result;
    result.valid = true;
    result.normal = cast.normal.normalized();
    result.growth = separation / exitDistance;
    if (!needWitnesses) return result;  // collide() needs only the normal
    result.hasWitnesses = true;
    castWitnesses(cast, difference, result.witnessA, result.witnessB);
    return result;
}

SeparationAlong separationAlong(const Polytope& a, const Polytope& b, const Pose& bInA, const Vec3& normal,
                                const Settings& settings) {
    return separationAlong(MinkowskiDifference(a, b, bInA, settings.bruteForceSupportLimit), normal, settings);
}

SeparationAlong separationAlong(const MinkowskiDifference& difference, const Vec3& normal, const Settings& settings) {
    // A − B contains the origin when the pair overlaps; B moved by t·normal still overlaps A while
    // t·normal ∈ A − B, so the separating translation is where that ray leaves A − B. Cast
    // back from beyond A − B's support plane (castExitAlong), as for the growth distance.
    SeparationAlong result;
    const Polytope& a = difference.a;
    auto support = [&](const Vec3& direction) {
        const int ia = difference.supportA(direction), ib = difference.supportB(-direction);
        return SupportPoint{a.vertices()[ia] - difference.vertexB(ib), ia, ib};
    };
    double distance = 0;
    RayCastResult cast = castExitAlong(support, normal, a.radius() + difference.b.radius(), settings, distance);
    if (!cast.hit || cast.simplexCount == 0) return result;
    result.valid = true;
    result.distance = distance;
    castWitnesses(cast, difference, result.witnessA, result.witnessB);
    return result;
}

}  // namespace gdc::detail
