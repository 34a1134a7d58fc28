#include "round_geoms.hpp"

#include <cmath>

namespace gdc::ode::detail {

bool isGdcontactPair(int class1, int class2) {
    auto pair = [&](int x, int y) { return (class1 == x && class2 == y) || (class1 == y && class2 == x); };
    // The polytopes and planes (not plane–plane).
    if (pair(dBoxClass, dBoxClass) || pair(dBoxClass, dConvexClass) || pair(dConvexClass, dConvexClass) ||
        pair(dBoxClass, dPlaneClass) || pair(dConvexClass, dPlaneClass))
        return true;
    // The curved pairs where ODE gives one point (or none) for a region.
    return pair(dCylinderClass, dBoxClass) || pair(dCylinderClass, dConvexClass) ||
           pair(dCylinderClass, dPlaneClass) || pair(dCylinderClass, dCylinderClass) ||
           pair(dCapsuleClass, dBoxClass) || pair(dCapsuleClass, dConvexClass) ||
           pair(dCapsuleClass, dCylinderClass) || pair(dSphereClass, dConvexClass) ||
           // A polytope, a capsule or a cylinder on a triangle mesh (trimesh_geoms.hpp).
           pair(dTriMeshClass, dBoxClass) || pair(dTriMeshClass, dConvexClass) ||
           pair(dTriMeshClass, dCapsuleClass) || pair(dTriMeshClass, dCylinderClass);
}

void readRound(dGeomID geom, int geomClass, gdc::detail::ShapeKind& kind, gdc::detail::RoundShape& round) {
    dReal radius = 0, length = 0;
    ShapeRef::Kind named = ShapeRef::Kind::Sphere;
    if (geomClass == dSphereClass) {
        radius = dGeomSphereGetRadius(geom);
    } else if (geomClass == dCapsuleClass) {
        dGeomCapsuleGetParams(geom, &radius, &length);
        named = ShapeRef::Kind::Capsule;
    } else {
        dGeomCylinderGetParams(geom, &radius, &length);
        named = ShapeRef::Kind::Cylinder;
    }
    // ODE accepts a zero radius (a segment, a point) and a zero-length cylinder (a disc): they
    // become the thinnest shape the core takes, a billionth of the other size (or of a millimetre
    // where both are zero), so that their contacts stay valid. Negative or non-finite sizes are
    // refused by the core's check, which names them.
    double r = static_cast<double>(radius), l = static_cast<double>(length);
    if (r == 0) r = 1e-9 * std::max(l, 1e-3);
    if (l == 0 && named == ShapeRef::Kind::Cylinder) l = 1e-9 * r;
    const gdc::detail::Shape shape = gdc::detail::enterRound(named, r, l, "geom");
    kind = shape.kind;
    round = shape.round;
}

double roundRadius(gdc::detail::ShapeKind kind, const gdc::detail::RoundShape& round) {
    if (kind == gdc::detail::ShapeKind::Cylinder) return std::hypot(round.radius, round.halfLength);
    return round.radius + round.halfLength;
}

}  // namespace gdc::ode::detail
