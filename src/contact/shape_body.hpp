// Any body shape of the pair table (a polytope or a curved kind) as the stages on support
// functions read it, in a common frame: its support and its Gauss-map feature for a direction, its
// contraction point and a bound of its size. The curved kinds' compositions (round_pair.cpp) and
// the mesh query (mesh_pair.cpp) use it.
#pragma once

#include "contact/feature_geometry.hpp"
#include "contact/gauss_map.hpp"
#include "contact/pair_table.hpp"
#include "contact/plane_contacts.hpp"
#include "shapes/round_shape.hpp"

#include <cmath>

namespace gdc::detail {

/// One body in the common frame (`toA` maps its own frame there), a polytope or a curved kind.
struct ShapeBody {
    ShapeKind kind;
    const Polytope* polytope;
    RoundShape round;
    Pose toA;
    Vec3 centre;    // the contraction point (a polytope's centroid, a curved kind's centre)
    double radius;  // bounds the body about `centre`
    int bruteForceLimit;
    mutable int lastVertex = -1;  // a hull's climb starts from its previous support (warm start)

    ShapeBody(const Shape& shape, const Pose& toA_, int limit)
        : kind(shape.kind), polytope(shape.polytope), round(shape.round), toA(toA_), bruteForceLimit(limit) {
        switch (kind) {
            case ShapeKind::Box:
            case ShapeKind::Hull:
                centre = toA.apply(polytope->centroid()), radius = polytope->radius();
                break;
            case ShapeKind::Sphere: centre = toA.position, radius = round.radius; break;
            case ShapeKind::Capsule: centre = toA.position, radius = round.radius + round.halfLength; break;
            default: centre = toA.position, radius = std::hypot(round.radius, round.halfLength); break;
        }
    }

    // A sphere is a point, a capsule a segment, grown by its radius (the ray cast's margin): the
    // core's support, and the radius it is grown by (0 for the other kinds: their own support).
    double margin() const { return kind == ShapeKind::Sphere || kind == ShapeKind::Capsule ? round.radius : 0.0; }
    Vec3 coreSupport(const Vec3& direction) const {
        if (kind == ShapeKind::Sphere) return toA.position;
        if (kind == ShapeKind::Capsule)
            return toA.apply(Vec3(0, 0, endToward(toA.rotation.transpose() * direction, round.halfLength)));
        return support(direction);
    }

    Vec3 support(const Vec3& direction) const {
        const Vec3 local = toA.rotation.transpose() * direction;
        switch (kind) {
            case ShapeKind::Box:
            case ShapeKind::Hull:
                lastVertex = polytope->supportVertex(local, bruteForceLimit, lastVertex);
                return toA.apply(polytope->vertices()[lastVertex]);
            case ShapeKind::Sphere: return toA.apply(sphereSupport(round, local));
            case ShapeKind::Capsule: return toA.apply(capsuleSupport(round, local));
            default: return toA.apply(cylinderSupport(round, local));
        }
    }

    // The Gauss-map feature for the unit `direction` (A's frame, pointing away from the body).
    AnyFeature feature(const Vec3& direction, const AngularTolerance& tolerance) const {
        const Vec3 local = toA.rotation.transpose() * direction;
        switch (kind) {
            case ShapeKind::Box:
            case ShapeKind::Hull: {
                const int support = polytope->supportVertex(local, bruteForceLimit, lastVertex);
                AnyFeature any;
                any.id = selectFeature(*polytope, local, support, tolerance);
                SmallVector<int, 8> pieces;
                featurePieces(*polytope, any.id, local, tolerance, pieces);
                any.geometry = featureGeometry(*polytope, any.id, pieces, toA);
                return any;
            }
            case ShapeKind::Sphere: return sphereFeature(round, local, toA);
            case ShapeKind::Capsule: return capsuleFeature(round, local, toA, tolerance);
            default: return cylinderFeature(round, local, toA, tolerance);
        }
    }
};

// The half-space's feature: a square of its plane around A's projection, wider than A's shadow, so
// that the intersection is A's feature itself, lifted onto the plane.
inline AnyFeature planeFeature(const PlaneInA& plane, const ShapeBody& a) {
    AnyFeature feature;
    feature.geometry.type = FeatureType::Face;
    feature.geometry.planeNormal = plane.m;
    feature.geometry.planeOffset = plane.offset;
    Vec3 u, v;
    planeBasis(plane.m, u, v);
    const Vec3 centre = a.centre + plane.depthOf(a.centre) * plane.m;
    const double half = 2 * a.radius;
    for (const Vec2& corner : {Vec2(1, 1), Vec2(-1, 1), Vec2(-1, -1), Vec2(1, -1)})
        feature.geometry.points.push_back(centre + half * (corner.x() * u + corner.y() * v));
    feature.id = {FeatureType::Face, 0};
    return feature;
}

}  // namespace gdc::detail
