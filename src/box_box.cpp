// Two boxes through the general pipeline's steps (collide.cpp, collideGeneral), each step in the
// box's closed form where the general one searches: the Gauss-map feature from the signs and
// sizes of the direction's components, faces straight from the box's numbering, and the exit of
// the ray along n through A − B from the 15 slabs of that zonotope instead of a GJK ray cast.
// Every decision is made on the same numbers the general pipeline compares (the same expressions
// on the same inputs), so both return the same manifold; where the general pipeline takes a rare
// branch (no growth-distance normal, the overhang check, an empty intersection, a depth
// confirmation that may add a point) the pair goes to it whole.
#include "box_box.hpp"

#include "collide_general.hpp"
#include "feature_intersection.hpp"
#include "gauss_map.hpp"
#include "growth_distance.hpp"
#include "minkowski.hpp"
#include "reduction.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

// Largest angular tolerance served (rad): below π/4 a box face's neighbours on the Gauss map (90°
// away) are more than twice the tolerance away, so no face has a cap (faceCap) and no direction
// is within the tolerance of two faces' normals on opposite sides of the box.
constexpr double kMaxAngularTolerance = 0.7;

// collide.cpp's kClearlySmallerOverlap: the overhang check runs only where a face could need less
// than this fraction of the normal's overlap (the box pair's lower bound settles it otherwise).
constexpr double kClearlySmallerOverlap = 0.5;

// collide.cpp's depth confirmation: a point is added where the exit along n is deeper than the
// deepest lifted point by more than this fraction of it.
constexpr double kDepthSlack = 0.01;

// Polytope::box numbers vertex v with the signs of its bits (x: 1, y: 2, z: 4), the faces
// −x, +x, −y, +y, −z, +z, and Polytope::buildTopology the edges in the order of their (tail, head)
// vertex pairs, tail < head: (0,1) (0,2) (0,4) (1,3) (1,5) (2,3) (2,6) (3,7) (4,5) (4,6) (5,7) (6,7).
// kBoxEdge[v][axis] is the edge from v along `axis` (box_box_test checks both against Polytope::box).
constexpr int kBoxEdge[8][3] = {{0, 1, 2}, {0, 3, 4}, {5, 1, 6}, {5, 3, 7},
                                {8, 9, 2}, {8, 10, 4}, {11, 9, 6}, {11, 10, 7}};
int boxFace(int axis, bool positive) { return 2 * axis + (positive ? 1 : 0); }

}  // namespace

// gauss_map.cpp's selectFeature for a box, on the same numbers. A box's face normals are exactly
// ±e_i and its edge directions exactly ±e_i (box_box_test checks it), so every dot product
// selectFeature takes is a component of `direction` up to sign, exactly:
// - faces: the support vertex s (bit i set where direction_i > 0) has the faces ±e_i whose sign is
//   that of direction_i (the others around the candidate vertices have cosine −|direction_i|,
//   below the tolerance's positive cosine): cosine |direction_i|, largest wins, ties to the lowest
//   index, a face at exactly the tolerance's cosine taken;
// - edges: the three edges of s lie between their faces' normals and have sine |direction_i|; a
//   neighbour of s across axis m joins the candidates (selectFeature's `around`) where its edge is
//   within the tolerance of ⟂ direction, and its other two edges lie between their normals only
//   where direction_m is exactly 0. Least sine wins, ties to the lowest index, one at exactly the
//   tolerance's sine taken.
Feature selectBoxFeature(const Vec3& d, const AngularTolerance& tolerance) {
    const int s = (d.x() > 0 ? 1 : 0) | (d.y() > 0 ? 2 : 0) | (d.z() > 0 ? 4 : 0);
    Feature best{FeatureType::Vertex, s};
    double bestCos = tolerance.cosine;
    for (int i = 0; i < 3; ++i) {
        const double c = std::abs(d[i]);
        const int face = boxFace(i, d[i] > 0);
        if (c > bestCos || (c == bestCos && (best.type != FeatureType::Face || face < best.index)))
            bestCos = c, best = {FeatureType::Face, face};
    }
    if (best.type == FeatureType::Face) return best;
    double bestSin = tolerance.sine;
    auto consider = [&](int edge, double sine) {
        if (sine > bestSin || (sine == bestSin && best.type == FeatureType::Edge && edge > best.index)) return;
        bestSin = sine, best = {FeatureType::Edge, edge};
    };
    for (int i = 0; i < 3; ++i) consider(kBoxEdge[s][i], std::abs(d[i]));
    for (int m = 0; m < 3; ++m) {
        if (d[m] != 0) continue;
        const int neighbour = s ^ (1 << m);
        for (int i = 0; i < 3; ++i)
            if (i != m) consider(kBoxEdge[neighbour][i], std::abs(d[i]));
    }
    return best;
}

namespace {

// collide.cpp's faceGeometry / featureGeometry for a box feature (a box face has no cap below
// kMaxAngularTolerance), with the same arithmetic: the same Pose::apply of the same vertices.
FeatureGeometry boxFeatureGeometry(const Polytope& box, const Feature& feature, const Pose* toCommon) {
    FeatureGeometry geometry;
    geometry.type = feature.type;
    int storage[2];
    const int* indices = nullptr;
    const int count = featureVertices(box, feature, &indices, storage);
    for (int i = 0; i < count; ++i)
        geometry.points.push_back(toCommon ? toCommon->apply(box.vertices()[indices[i]]) : box.vertices()[indices[i]]);
    if (feature.type == FeatureType::Face) {
        const Polytope::Face& face = box.faces()[feature.index];
        if (toCommon) {
            geometry.planeNormal = toCommon->rotation * face.normal;
            geometry.planeOffset = face.offset + geometry.planeNormal.dot(toCommon->position);
        } else {
            geometry.planeNormal = face.normal;
            geometry.planeOffset = face.offset;
        }
    }
    return geometry;
}

// collide.cpp's refineNormal, on the same numbers: the least overlap among the picked faces'
// normals (a box face's cap is the face alone); edge–edge, the edges' common perpendicular.
void refineNormal(Vec3& normal, double& normalOverlap, const FeatureGeometry& a, const FeatureGeometry& b,
                  const MinkowskiDifference& pair) {
    Vec3 best = normal;
    double bestOverlap = INFINITY, bestCos = -2;
    auto consider = [&](const Vec3& candidate) {
        const double overlap = candidate == normal ? normalOverlap : pair.overlapAlong(candidate);
        const double cosine = candidate.dot(normal);
        if (overlap < bestOverlap || (overlap == bestOverlap && cosine > bestCos))
            bestOverlap = overlap, bestCos = cosine, best = candidate;
    };
    if (a.type == FeatureType::Face) consider(a.planeNormal);
    if (b.type == FeatureType::Face) consider(-b.planeNormal);
    if (bestCos > -2) {
        normal = best, normalOverlap = bestOverlap;
        return;
    }
    if (a.type == FeatureType::Edge && b.type == FeatureType::Edge) {
        Vec3 perpendicular = (a.points[1] - a.points[0]).cross(b.points[1] - b.points[0]);
        double scale = (a.points[1] - a.points[0]).norm() * (b.points[1] - b.points[0]).norm();
        if (perpendicular.norm() > 1e-6 * scale) {
            perpendicular.normalize();
            normal = perpendicular.dot(normal) < 0 ? -perpendicular : perpendicular;
            normalOverlap = pair.overlapAlong(normal);
        }
    }
}

// The line {t·n} through A − B (B at `bInA`, all in A's frame). A − B is the zonotope spanned by
// the boxes' half-edges, the intersection of the slabs |m·x + m·p| ≤ r(m) over its facet normals
// m — the 3 + 3 face normals and the 9 edge cross products (unnormalised: each slab's bounds on t
// are ratios) — with r(m) = halfA·|m| + halfB·|Rᵀm| and p B's centre. The line leaves A − B at the
// least upper bound on t: the exit the general pipeline's ray cast (separationAlong) converges to.
struct LineThroughDifference {
    double exit = INFINITY;    // largest t with t·n in A − B
    double entry = -INFINITY;  // smallest
    bool missesSlab = false;   // a slab parallel to n misses the line
};

LineThroughDifference lineThroughDifference(const Vec3& halfA, const Vec3& halfB, const Pose& bInA, const Vec3& n,
                                            double slack) {
    const Mat3& r = bInA.rotation;
    const Vec3& p = bInA.position;
    LineThroughDifference line;
    auto slab = [&](double radius, double mp, double mn) {
        if (mn == 0) {
            line.missesSlab |= std::abs(mp) > radius + slack;
            return;
        }
        double low = (-radius - mp) / mn, high = (radius - mp) / mn;
        if (mn < 0) std::swap(low, high);
        line.entry = std::max(line.entry, low), line.exit = std::min(line.exit, high);
    };
    const Mat3 absR = r.cwiseAbs();
    const Vec3 nInB = r.transpose() * n, pInB = r.transpose() * p;
    for (int i = 0; i < 3; ++i) slab(halfA[i] + halfB.dot(absR.row(i).transpose()), p[i], n[i]);
    for (int j = 0; j < 3; ++j) slab(halfA.dot(absR.col(j)) + halfB[j], pInB[j], nInB[j]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const Vec3 m = Vec3::Unit(i).cross(r.col(j));
            const Vec3 mInB = r.row(i).transpose().cross(Vec3::Unit(j));
            slab(halfA.dot(m.cwiseAbs()) + halfB.dot(mInB.cwiseAbs()), m.dot(p), m.dot(n));
        }
    return line;
}

// collide.cpp's emit: the chosen points to the manifold, mapped from A's frame to the world.
void emit(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
          Manifold& manifold) {
    int chosen[kMaxManifoldPoints];
    const int maxCount = std::max(1, std::min(settings.maxContacts, kMaxManifoldPoints));
    const int total = static_cast<int>(points.size());
    const int count = total <= maxCount ? total : reduceContacts(points, maxCount, chosen);
    manifold.normal = commonToWorld.rotation * normal;
    manifold.pointCount = count;
    double nonFinite = 0;
    for (int i = 0; i < count; ++i) {
        const LiftedPoint& point = points[total <= maxCount ? i : chosen[i]];
        manifold.points[i] = {commonToWorld.apply(point.position), point.depth};
        nonFinite += (manifold.points[i].position * 0.0).sum() + point.depth * 0.0;
    }
    if (!(nonFinite == 0))
        throw InvalidInput("the contact overflows double precision (coordinates or offsets near 1e308)");
}

}  // namespace

bool boxBoxApplies(const Polytope& a, const Polytope& b, const Settings& settings) {
    return a.isBox() && b.isBox() && settings.normalMethod == NormalMethod::GrowthDistance &&
           settings.angularTolerance >= 0 && settings.angularTolerance <= kMaxAngularTolerance;
}

Manifold collideBoxBox(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings) {
    auto general = [&] { return collideGeneral(a, poseA, b, poseB, settings); };
    if (!poseA.isFinite() || !poseB.isFinite()) return general();  // it says what is wrong
    Manifold manifold;
    const Pose bInA = poseA.relative(poseB);
    const MinkowskiDifference pair(a, b, bInA, settings.bruteForceSupportLimit);
    const double size = a.radius() + b.radius();
    const double tolerance = 1e-9 * size;
    // The general pipeline's two early outs, as it computes them.
    const Vec3 centreOffset = pair.centreB - pair.centreA;
    const double centreDistance = centreOffset.norm();
    if (centreDistance > size + settings.margin) return manifold;
    if (centreDistance > 0 && pair.overlapAlong(centreOffset / centreDistance) < -settings.margin - tolerance)
        return manifold;

    // Stage 1: the closed-form growth distance of two boxes (growth_distance.cpp).
    const GrowthDistance growth = growthDistance(pair, settings, /*needWitnesses=*/false);
    if (!growth.valid) return general();  // coincident centres: the general fallback normal
    Vec3 normal = growth.normal;
    double normalOverlap = pair.overlapAlong(normal);
    if (normalOverlap < -settings.margin - tolerance) return manifold;
    // The overhang check can only act where the box pair's bound leaves room for a face of less
    // than half the normal's overlap (deep overlap): then the general pipeline runs it.
    if (!(growth.faceOverlapLowerBound >= kClearlySmallerOverlap * normalOverlap + tolerance)) return general();

    // Stage 2: one feature per box (B's with −n in its own frame).
    const AngularTolerance angularTolerance(settings.angularTolerance);
    manifold.featureA = selectBoxFeature(normal, angularTolerance);
    manifold.featureB = selectBoxFeature(bInA.rotation.transpose() * -normal, angularTolerance);
    const FeatureGeometry featureA = boxFeatureGeometry(a, manifold.featureA, nullptr);
    const FeatureGeometry featureB = boxFeatureGeometry(b, manifold.featureB, &bInA);
    refineNormal(normal, normalOverlap, featureA, featureB, pair);

    // Stage 3: the intersection in the contact plane.
    LiftedPoints kept =
        intersectFeatures(featureA, featureB, normal, tolerance, -settings.margin, settings.spanContactRegion);
    if (kept.empty()) return general();  // its fallbacks: the ray cast's witnesses or the supports' gap
    double deepest = -INFINITY;
    for (const LiftedPoint& point : kept) deepest = std::max(deepest, point.depth);
    // The depth confirmation: the general pipeline casts a ray along n through A − B where the
    // lifted points fall short of the supports' overlap, and adds a point where its exit is deeper
    // than the deepest lifted point by more than the slack. The exact exit decides it here: below
    // the slack by a clear margin — half the slack, less twice the cast's tolerance by which the
    // cast can overshoot the exit (it stops outside A − B, within its tolerance) — the cast
    // cannot add a point; otherwise the general pipeline runs and decides.
    if (deepest < normalOverlap - tolerance) {
        const double slack = kDepthSlack * std::abs(deepest) + tolerance;
        const LineThroughDifference line =
            lineThroughDifference(a.boxHalfExtents(), b.boxHalfExtents(), bInA, normal, tolerance);
        const double castTolerance = settings.rayCastTolerance * size;
        const bool clearlyMisses = line.missesSlab || line.entry > line.exit + 1e-6 * size;
        if (!clearlyMisses && !(line.exit <= deepest + 0.5 * slack - 2 * castTolerance)) return general();
    }
    emit(kept, normal, poseA, settings, manifold);
    return manifold;
}

}  // namespace gdc::detail
