// The contact query: the paper's three stages, composed. Everything is computed in A's frame
// (precision far from the origin) and mapped to the world at the end.
#include <gdcontact/collide.hpp>

#include "feature_intersection.hpp"
#include "gauss_map.hpp"
#include "growth_distance.hpp"
#include "minkowski.hpp"
#include "reduction.hpp"

#include <cmath>

namespace gdc {
namespace {

using namespace detail;

void requireFinite(const Pose& pose, const char* which) {
    if (!pose.isFinite()) throw InvalidInput(std::string("the pose of ") + which + " is not finite");
}

// Contact normal when the growth distance has no answer (coincident contraction points, or a
// failed cast): the face normal of either body along which the overlap is smallest — the
// direction a separating-axis test would push them apart. Deterministic and swap-symmetric.
Vec3 minimumOverlapFaceNormal(const MinkowskiDifference& pair) {
    Vec3 best = Vec3::UnitZ();
    double bestOverlap = INFINITY;
    for (const Polytope::Face& face : pair.a.faces()) {
        double overlap = pair.overlapAlong(face.normal);
        if (overlap < bestOverlap) bestOverlap = overlap, best = face.normal;
    }
    for (const Polytope::Face& face : pair.b.faces()) {
        Vec3 normal = -(pair.bInA.rotation * face.normal);
        double overlap = pair.overlapAlong(normal);
        if (overlap < bestOverlap) bestOverlap = overlap, best = normal;
    }
    return best;
}

FeatureGeometry featureGeometry(const Polytope& polytope, const Feature& feature, const Pose& toCommon) {
    FeatureGeometry geometry;
    geometry.type = feature.type;
    int storage[2];
    const int* indices = nullptr;
    int count = featureVertices(polytope, feature, &indices, storage);
    for (int i = 0; i < count; ++i) geometry.points.push_back(toCommon.apply(polytope.vertices()[indices[i]]));
    if (feature.type == FeatureType::Face) {
        const Polytope::Face& face = polytope.faces()[feature.index];
        geometry.planeNormal = toCommon.rotation * face.normal;
        geometry.planeOffset = face.offset + geometry.planeNormal.dot(toCommon.position);
    }
    return geometry;
}

// The Gauss-map features widen the normal into a region; where a face was picked the exact
// contact normal is that face's normal (vertex–face, edge–face, face–face all rest on a face),
// and for edge–edge it is the edges' common perpendicular. Of two faces, the one closer to the
// growth-distance normal is the face the cast actually hit.
Vec3 refineNormal(const Vec3& normal, const FeatureGeometry& a, const FeatureGeometry& b) {
    Vec3 best = normal;
    double bestCos = -2;
    if (a.type == FeatureType::Face && a.planeNormal.dot(normal) > bestCos)
        bestCos = a.planeNormal.dot(normal), best = a.planeNormal;
    if (b.type == FeatureType::Face && -b.planeNormal.dot(normal) > bestCos)
        bestCos = -b.planeNormal.dot(normal), best = -b.planeNormal;
    if (bestCos > -2) return best;
    if (a.type == FeatureType::Edge && b.type == FeatureType::Edge) {
        Vec3 perpendicular = (a.points[1] - a.points[0]).cross(b.points[1] - b.points[0]);
        double scale = (a.points[1] - a.points[0]).norm() * (b.points[1] - b.points[0]).norm();
        if (perpendicular.norm() > 1e-6 * scale) {
            perpendicular.normalize();
            return perpendicular.dot(normal) < 0 ? -perpendicular : perpendicular;
        }
    }
    return normal;
}

// Writes the chosen points to the manifold, mapping from the common frame to the world.
void emit(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
          Manifold& manifold) {
    int chosen[kMaxManifoldPoints];
    int maxCount = std::max(1, std::min(settings.maxContacts, kMaxManifoldPoints));
    int count = reduceContacts(points, maxCount, chosen);
    manifold.normal = commonToWorld.rotation * normal;
    manifold.pointCount = count;
    for (int i = 0; i < count; ++i)
        manifold.points[i] = {commonToWorld.apply(points[chosen[i]].position), points[chosen[i]].depth};
}

}  // namespace

Manifold collide(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                 const Settings& settings) {
    requireFinite(poseA, "A");
    requireFinite(poseB, "B");
    Manifold manifold;
    const Pose bInA = poseA.relative(poseB);
    const MinkowskiDifference pair(a, b, bInA, settings.bruteForceSupportLimit);
    const double size = a.radius() + b.radius();
    const double tolerance = 1e-9 * size;
    // Bounding spheres about the centroids: the cheap early out for separated pairs.
    if ((pair.centreB - pair.centreA).norm() > size + settings.margin) return manifold;

    // Stage 1: contact normal from the growth distance.
    GrowthDistance growth = growthDistance(a, b, bInA, settings, /*needWitnesses=*/false);
    Vec3 normal = growth.valid ? growth.normal : minimumOverlapFaceNormal(pair);
    if (pair.overlapAlong(normal) < -settings.margin - tolerance) return manifold;  // separated along n

    // Stage 2: one Gauss-map feature per body (B's searched in its own frame with −n).
    const AngularTolerance angularTolerance(settings.angularTolerance);
    manifold.featureA = selectFeature(a, normal, angularTolerance, settings.bruteForceSupportLimit);
    manifold.featureB = selectFeature(b, bInA.rotation.transpose() * -normal, angularTolerance,
                                      settings.bruteForceSupportLimit);
    const FeatureGeometry featureA = featureGeometry(a, manifold.featureA, Pose{});
    const FeatureGeometry featureB = featureGeometry(b, manifold.featureB, bInA);
    normal = refineNormal(normal, featureA, featureB);

    // Stage 3: intersection in the contact plane, each point with its own depth.
    LiftedPoints kept = intersectFeatures(featureA, featureB, normal, tolerance, -settings.margin - tolerance);
    if (kept.empty()) {
        // The projections do not meet: at a vertex–vertex touch (rounding), or in deep overlap,
        // where the features that touch when the bodies are shrunk to the growth distance drift
        // apart once they are full size. Never a missing contact: one point in the overlap, midway
        // between the growth-distance witnesses (both lie on the line through the contraction
        // points, inside A ∩ B), with the overlap along n as depth — the translation that separates.
        if (growth.valid && !growth.hasWitnesses) growth = growthDistance(a, b, bInA, settings);
        Vec3 middle = growth.hasWitnesses ? 0.5 * (growth.witnessA + growth.witnessB)
                                   : 0.5 * (a.vertices()[pair.supportA(normal)] + pair.vertexB(pair.supportB(-normal)));
        kept.push_back({middle, pair.overlapAlong(normal), Vec2::Zero()});
    }
    emit(kept, normal, poseA, settings, manifold);
    return manifold;
}

Manifold collide(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings) {
    requireFinite(poseA, "A");
    const double normalLength = b.normal.norm();
    if (!b.normal.allFinite() || !std::isfinite(b.offset) || !(normalLength > 0))
        throw InvalidInput("the half-space normal must be finite and non-zero");
    Manifold manifold;
    // In A's frame: the solid is {x : m·x ≤ offset}; the normal from A into the solid is −m.
    const Vec3 m = poseA.rotation.transpose() * (b.normal / normalLength);
    const double offset = b.offset / normalLength - (b.normal / normalLength).dot(poseA.position);
    const Vec3 normal = -m;
    const double size = a.radius();
    const double tolerance = 1e-9 * size;
    const int deepest = a.supportVertex(normal, settings.bruteForceSupportLimit);
    if (offset - m.dot(a.vertices()[deepest]) < -settings.margin - tolerance) return manifold;

    // The half-space's Gauss map is the single point −n, so its feature is its plane; A's
    // feature comes from its Gauss map as usual, and each of its vertices is lifted onto the plane.
    manifold.featureA = selectFeature(a, normal, AngularTolerance(settings.angularTolerance),
                                      settings.bruteForceSupportLimit);
    manifold.featureB = {FeatureType::Face, 0};
    int storage[2];
    const int* indices = nullptr;
    int count = featureVertices(a, manifold.featureA, &indices, storage);
    Vec3 u, v;
    planeBasis(normal, u, v);
    LiftedPoints kept;
    for (int i = 0; i < count; ++i) {
        const Vec3& x = a.vertices()[indices[i]];
        double depth = offset - m.dot(x);
        if (depth >= -settings.margin - tolerance) kept.push_back({x + 0.5 * depth * m, depth, Vec2(x.dot(u), x.dot(v))});
    }
    if (kept.empty()) {  // a tilted face whose selected vertices all float: keep the deepest one
        const Vec3& x = a.vertices()[deepest];
        double depth = offset - m.dot(x);
        kept.push_back({x + 0.5 * depth * m, depth, Vec2(x.dot(u), x.dot(v))});
    }
    emit(kept, normal, poseA, settings, manifold);
    return manifold;
}

}  // namespace gdc
