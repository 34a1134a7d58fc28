// The paper's three stages for every pair with a curved kind (a sphere, a capsule, a cylinder) on
// either side, against any body or a half-space: the pair table's cells for those kinds
// (round_pair.hpp). A curved kind gives the method what a polytope gives it — a support point and a
// Gauss-map feature (shapes/round_shape.hpp) — so the stages are the general ones on support
// functions: stage 1 the growth distance by the GJK ray cast on (A − p_A) − (B − p_B), refined among
// the features' planes (a face, a cap) where one of them needs less translation; stage 2 one feature
// per body; stage 3 their exact intersection in the contact plane (disc_intersection.hpp), with the
// depth confirmation along n. Everything is computed in A's frame. On a half-space the stages are
// short: the plane's normal is the contact normal, and A's feature for it, lifted onto the plane, is
// the contact region.
#include "contact/round_pair.hpp"

#include "contact/collide_general.hpp"
#include "contact/disc_intersection.hpp"
#include "contact/feature_geometry.hpp"
#include "contact/gauss_map.hpp"
#include "contact/plane_contacts.hpp"
#include "contact/shape_body.hpp"
#include "geometry/growth_distance.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace gdc::detail {
namespace {

// The support points of one ray cast, so that its final simplex names the points of A and B it
// came from (a curved kind has no vertex indices: each support gets an index of its own). Inline
// for the usual casts (10–20 supports): a vector's growth was an eighth of a query's cost.
struct SupportLog {
    SmallVector<Vec3, 40> onA, onB;
    int add(const Vec3& a, const Vec3& b) {
        onA.push_back(a), onB.push_back(b);
        return static_cast<int>(onA.size()) - 1;
    }
};

// The outward normal of a planar feature (a face, a cap), in A's frame; zero for any other.
Vec3 planeNormalOf(const AnyFeature& feature) {
    if (feature.isDisc) return feature.disc.axis;
    return feature.geometry.type == FeatureType::Face ? feature.geometry.planeNormal : Vec3::Zero();
}

// Where the ray cast has no answer (coincident contraction points): the direction of least overlap
// among the axes of both bodies' frames (a box's face normals, a cylinder's axis).
Vec3 fallbackNormal(const ShapeBody& a, const ShapeBody& b) {
    Vec3 best = Vec3::UnitZ();
    double bestOverlap = INFINITY;
    for (const Pose* frame : {&a.toA, &b.toA})
        for (int axis = 0; axis < 3; ++axis)
            for (const double sign : {1.0, -1.0}) {
                const Vec3 direction = sign * frame->rotation.col(axis);
                const double overlap = direction.dot(a.support(direction)) - direction.dot(b.support(-direction));
                if (overlap < bestOverlap) bestOverlap = overlap, best = direction;
            }
    return best;
}

// The points written out: in lift order where the caller orders by depth itself (the ODE adapter)
// and the ranking could only have ordered them (emitInLiftOrder), else ranked.
void emitRound(const LiftedPoints& kept, const Vec3& normal, const Pose& poseA, const PairQuery& query,
               double tolerance, const Vec3* centroids, int centroidCount, Manifold& out) {
    const Settings& settings = query.settings;
    const bool ordered = query.order == ImportanceOrder::AmongEqualDepths &&
                         static_cast<int>(kept.size()) <= settings.maxContacts &&
                         emitInLiftOrder(kept, normal, poseA, settings, out);
    if (!ordered) emitManifold(kept, normal, poseA, settings, tolerance, centroids, centroidCount, out);
}

}  // namespace

void collideRoundOnPlaneInto(const Shape& shapeA, const Pose& poseA, const Shape& shapeB, const Pose&,
                             const PairQuery& query, Manifold& out) {
    const Settings& settings = query.settings;
    clearManifold(out);
    const AngularTolerance angular = query.angular();
    const ShapeBody a(shapeA, Pose{}, settings.bruteForceSupportLimit);
    const double tolerance = 1e-9 * a.radius;
    const double minimumDepth = -settings.margin;
    // Stage 1 on a plane: its normal is exact; the overlap is the depth of A's support.
    const PlaneInA plane = planeInA(*shapeB.halfSpace, poseA);
    const Vec3 normal = -plane.m;
    if (plane.depthOf(a.support(normal)) < minimumDepth - tolerance) return;
    // Stage 2: A's feature (the plane's is the plane). Stage 3: that feature lifted onto the plane.
    const AnyFeature featureA = a.feature(normal, angular);
    LiftedPoints kept;
    liftOntoPlane(featureA, normal, plane.offset, tolerance, minimumDepth, settings.spanContactRegion,
                  settings.rimPointsPerTurn, wholeRimPoints(settings), kept);
    if (kept.empty()) return;
    emitRound(kept, normal, poseA, query, tolerance, &a.centre, 1, out);
    out.featureA = featureA.id;
    out.featureB = {FeatureType::Face, 0};
}

void collideRoundInto(const Shape& shapeA, const Pose& poseA, const Shape& shapeB, const Pose& poseB,
                      const PairQuery& query, Manifold& out) {
    const Settings& settings = query.settings;
    clearManifold(out);
    const AngularTolerance angular = query.angular();
    const ShapeBody a(shapeA, Pose{}, settings.bruteForceSupportLimit);
    const ShapeBody b(shapeB, poseA.relative(poseB), settings.bruteForceSupportLimit);
    const double size = a.radius + b.radius;
    const double tolerance = 1e-9 * size;
    const double minimumDepth = -settings.margin;
    auto overlapAlong = [&](const Vec3& n) { return n.dot(a.support(n)) - n.dot(b.support(-n)); };

    const Vec3 offset = b.centre - a.centre;
    const double distance = offset.norm();
    if (distance > size + settings.margin + tolerance) return;  // the bounding spheres are apart
    // Stage 1: the growth distance, the exit of the ray along p_B − p_A through C. A curved
    // surface is met only in the limit: each support adds a point, and the cast stops within
    // its tolerance of the surface.
    // A sphere's or a capsule's core and radius: the cast on the cores, grown by the radii.
    Vec3 normal;
    bool found = false;
    const double margin = a.margin() + b.margin();
    if (distance > 1e-12 * size) {
        const Vec3 w = offset / distance;
        SupportLog log;
        auto support = [&](const Vec3& d) {
            const Vec3 onA = a.coreSupport(d), onB = b.coreSupport(-d);
            const int id = log.add(onA, onB);
            return SupportPoint{(onA - a.centre) - (onB - b.centre), id, id};
        };
        const double start = w.dot(support(w).point) + margin + 0.5 * size;
        const RayCastResult cast = gjkRayCast(support, start * w, -w, settings.rayCastTolerance * size,
                                              settings.maxRayCastIterations, margin);
        if (cast.hit && start - cast.lambda > 0 && cast.normal.squaredNorm() > 0 && cast.normal.allFinite())
            normal = cast.normal.normalized(), found = true;
    }
    if (!found) normal = fallbackNormal(a, b);
    double normalOverlap = overlapAlong(normal);
    if (normalOverlap < minimumDepth - tolerance) return;
    // Stage 2, and the normal among the features' planes: a face or a cap along which the pair
    // overlaps less is the contact normal (a cap resting on a face: the face's, exactly).
    AnyFeature featureA = a.feature(normal, angular);
    AnyFeature featureB = b.feature(-normal, angular);
    Vec3 best = normal;
    double bestOverlap = normalOverlap;
    for (const Vec3& candidate : {planeNormalOf(featureA), Vec3(-planeNormalOf(featureB))}) {
        if (!(candidate.squaredNorm() > 0)) continue;
        const double overlap = overlapAlong(candidate);
        if (overlap < bestOverlap - tolerance) best = candidate, bestOverlap = overlap;
    }
    if (best != normal) {
        normal = best, normalOverlap = bestOverlap;
        if (normalOverlap < minimumDepth - tolerance) return;
        featureA = a.feature(normal, angular);
        featureB = b.feature(-normal, angular);
    }

    // Stage 3: the features' intersection in the contact plane, each point with its own depth.
    LiftedPoints kept;
    intersectAnyFeatures(featureA, featureB, normal, tolerance, minimumDepth, settings.spanContactRegion,
                         settings.rimPointsPerTurn, wholeRimPoints(settings), kept);
    double deepest = -INFINITY;
    for (const LiftedPoint& point : kept) deepest = std::max(deepest, point.depth);
    // The depth confirmation: where the intersection falls short of the supports' overlap along n
    // (the supports do not face each other across the contact plane — an overhang), the exact
    // depth along n is where the ray along n leaves A − B; its touching points are a contact.
    if (deepest < normalOverlap - 1e-7 * size) {
        SupportLog log;
        auto support = [&](const Vec3& d) {
            const Vec3 onA = a.coreSupport(d), onB = b.coreSupport(-d);
            const int id = log.add(onA, onB);
            return SupportPoint{onA - onB, id, id};
        };
        const double start = normal.dot(support(normal).point) + margin + 0.5 * size;
        const RayCastResult cast = gjkRayCast(support, start * normal, -normal, settings.rayCastTolerance * size,
                                              settings.maxRayCastIterations, margin);
        const double depth = start - cast.lambda;
        if (cast.hit && cast.simplexCount > 0 && depth >= minimumDepth - tolerance && depth > deepest + tolerance) {
            // The cores' witnesses, each grown by its radius along the cast's normal.
            Vec3 onA = Vec3::Zero(), onB = Vec3::Zero();
            for (int i = 0; i < cast.simplexCount; ++i) {
                onA += cast.weights[i] * log.onA[cast.simplex[i].vertexA];
                onB += cast.weights[i] * log.onB[cast.simplex[i].vertexB];
            }
            // Grown along the hit's direction from the cores' closest point (the final v), so that
            // the two witnesses differ by the hit itself.
            const Vec3 fromCores = depth * normal - (onA - onB);
            const Vec3 outward = fromCores.squaredNorm() > 0 ? Vec3(fromCores.normalized()) : normal;
            onA += a.margin() * outward;
            onB -= b.margin() * outward;
            // The point on B is B's witness itself (a convex combination of B's supports: inside
            // B); the one on A is it moved by the depth along n, A's witness within the cast's
            // tolerance.
            Vec3 u, v;
            planeBasis(normal, u, v);
            const double measured = (onA - onB).dot(normal);
            const Vec3 middle = onB + 0.5 * measured * normal;
            kept.push_back({middle, measured, Vec2(middle.dot(u), middle.dot(v)), -1, -1});
        }
    }
    if (kept.empty()) return;
    const Vec3 centroids[2] = {a.centre, b.centre};
    emitRound(kept, normal, poseA, query, tolerance, centroids, 2, out);
    out.featureA = featureA.id;
    out.featureB = featureB.id;
}

namespace {

[[noreturn, gnu::cold, gnu::noinline]] void throwBadSize(ShapeRef::Kind kind, const char* what, double value,
                                                         const char* which, const char* bound) {
    const char* name = kind == ShapeRef::Kind::Sphere ? "sphere" : kind == ShapeRef::Kind::Capsule ? "capsule" : "cylinder";
    throw InvalidInput(std::string("the ") + name + " " + which + " has " + what + " " + std::to_string(value) +
                       ": it must be " + bound);
}

}  // namespace

Shape enterRound(ShapeRef::Kind kind, double radius, double length, const char* which) {
    if (!(std::isfinite(radius) && radius > 0)) throwBadSize(kind, "radius", radius, which, "positive and finite");
    if (kind == ShapeRef::Kind::Cylinder && !(std::isfinite(length) && length > 0))
        throwBadSize(kind, "length", length, which, "positive and finite");
    if (kind == ShapeRef::Kind::Capsule && !(std::isfinite(length) && length >= 0))
        throwBadSize(kind, "length", length, which, "finite and not negative");
    const ShapeKind shapeKind = kind == ShapeRef::Kind::Sphere    ? ShapeKind::Sphere
                                : kind == ShapeRef::Kind::Capsule ? ShapeKind::Capsule
                                                                  : ShapeKind::Cylinder;
    return Shape::of(shapeKind, RoundShape{radius, kind == ShapeRef::Kind::Sphere ? 0.0 : 0.5 * length});
}

}  // namespace gdc::detail
