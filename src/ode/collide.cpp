// gdc::ode::install / collide: ODE's geoms in, the core's manifold out as dContactGeoms.
#include <gdcontact/ode.hpp>

#include "state.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <functional>
#include <string>

namespace gdc::ode {
namespace {

enum class Kind { Polytope, Plane };

struct Shape {
    Kind kind = Kind::Polytope;
    std::shared_ptr<const Polytope> polytope;  // Kind::Polytope, geom-local frame
    Pose pose;                                  // Kind::Polytope
    HalfSpace halfSpace;                        // Kind::Plane, world frame
};

const char* className(int geomClass) {
    switch (geomClass) {
        case dSphereClass: return "sphere";
        case dBoxClass: return "box";
        case dCapsuleClass: return "capsule";
        case dCylinderClass: return "cylinder";
        case dPlaneClass: return "plane";
        case dRayClass: return "ray";
        case dConvexClass: return "convex";
        case dGeomTransformClass: return "geom transform";
        case dTriMeshClass: return "trimesh";
        case dHeightfieldClass: return "heightfield";
        default: return "unsupported class";
    }
}

std::shared_ptr<const Polytope> boxPolytopeOf(dGeomID box) {
    dVector3 lengths;
    dGeomBoxGetLengths(box, lengths);
    return detail::boxPolytope(0.5 * lengths[0], 0.5 * lengths[1], 0.5 * lengths[2]);
}

// Misuse of the adapter is a programming error: ODE's error handler (which by default prints
// the message and exits) is the loud way ODE itself reports those.
[[noreturn]] void misuse(const std::string& what) {
    dError(d_ERR_UASSERT, "%s", ("gdcontact: " + what).c_str());
}

Shape readShape(dGeomID geom) {
    Shape shape;
    const int geomClass = dGeomGetClass(geom);
    switch (geomClass) {
        case dBoxClass:
            shape.polytope = boxPolytopeOf(geom);
            shape.pose = poseOf(geom);
            return shape;
        case dConvexClass:
            shape.polytope = detail::registeredConvex(geom);
            if (!shape.polytope)
                misuse("a dConvex geom made with plain dCreateConvex reached gdc::ode::collide. ODE "
                       "0.16.2 gives no access to a dConvex's data, so gdcontact cannot collide it. "
                       "Create the geom with gdc::ode::createConvex(space, planes, planeCount, points, "
                       "pointCount, polygons) (the same arguments as dCreateConvex) or "
                       "gdc::ode::createConvex(space, points, pointCount) instead.");
            shape.pose = poseOf(geom);
            return shape;
        case dPlaneClass: {
            shape.kind = Kind::Plane;
            dVector4 parameters;  // a·x + b·y + c·z ≤ d is the solid; (a,b,c) points out of it
            dGeomPlaneGetParams(geom, parameters);
            shape.halfSpace = HalfSpace{Vec3(parameters[0], parameters[1], parameters[2]).normalized(),
                                        static_cast<double>(parameters[3])};
            return shape;
        }
        default:
            misuse(std::string("gdc::ode::collide handles box, convex (gdc::ode::createConvex) and plane "
                               "geoms; it got a ") + className(geomClass) +
                   " (leave that pair to ODE: install() overrides only the supported pairs)");
    }
}

int collideChecked(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip,
                   const Settings& settings) {
    const int maxContacts = std::min({flags & 0xffff, settings.maxContacts, kMaxManifoldPoints});
    if (maxContacts <= 0 || o1 == o2) return 0;
    if (!o1 || !o2) misuse("gdc::ode::collide got a null geom");
    if (!contact) misuse("gdc::ode::collide got a null contact array");
    if (skip < static_cast<int>(sizeof(dContactGeom)))
        misuse("gdc::ode::collide: skip (" + std::to_string(skip) +
               ") is smaller than sizeof(dContactGeom)");

    const Shape shape1 = readShape(o1);
    const Shape shape2 = readShape(o2);
    if (shape1.kind == Kind::Plane && shape2.kind == Kind::Plane)
        misuse("gdc::ode::collide: plane–plane is not a supported pair");

    // One fixed order per pair, so collide(a,b) and collide(b,a) make the same core call and
    // their answers are exact mirrors (ODE calls fn(b,a) for dCollide(a,b) on same-class pairs).
    // The order comes from the geoms' positions, not their addresses: a world rebuilt in the same
    // state must replay exactly, and allocation reuses addresses in another order (the address
    // only breaks exact ties).
    auto before = [](const Shape& x, dGeomID geomX, const Shape& y, dGeomID geomY) {
        const Vec3& p = x.pose.position;
        const Vec3& q = y.pose.position;
        if (p.x() != q.x()) return p.x() < q.x();
        if (p.y() != q.y()) return p.y() < q.y();
        if (p.z() != q.z()) return p.z() < q.z();
        return std::less<const void*>{}(static_cast<const void*>(geomX), static_cast<const void*>(geomY));
    };
    const bool swapped = shape1.kind == Kind::Plane || (shape2.kind == Kind::Polytope && before(shape2, o2, shape1, o1));
    const Shape& a = swapped ? shape2 : shape1;
    const Shape& b = swapped ? shape1 : shape2;

    Settings pairSettings = settings;
    pairSettings.maxContacts = maxContacts;
    const Manifold manifold =
        b.kind == Kind::Plane ? gdc::collide(*a.polytope, a.pose, b.halfSpace, pairSettings)
                              : gdc::collide(*a.polytope, a.pose, *b.polytope, b.pose, pairSettings);
    if (manifold.empty()) return 0;

    // The core's normal points from A towards B; ODE's from o2 into o1.
    Vec3 normal = swapped ? manifold.normal : Vec3(-manifold.normal);
    const double length = normal.norm();
    if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-6) {
        dMessage(d_ERR_UNKNOWN, "gdcontact: the core returned an invalid normal; pair skipped");
        return 0;
    }
    normal /= length;

    // ODE treats every contact as active and clamps a negative depth to zero, so a speculative
    // point (depth < 0, only with Settings::margin > 0) would hold the bodies apart by its gap.
    // Such points are not passed on; a rounding-level negative depth is reported as touching.
    const double sizeOfPair = a.polytope->radius() + (b.kind == Kind::Plane ? 0.0 : b.polytope->radius());
    const double touchingTolerance = 1e-9 * sizeOfPair;
    // Deepest first, as ODE's own colliders list them. dWorldQuickStep sweeps the contact rows in
    // the order given; the core's order walks the contact polygon the same way round every step,
    // and under QuickStep that fixed order roughly doubled a 10-stack's drift (samples/ode_stack).
    std::array<int, kMaxManifoldPoints> order;
    int kept = 0;
    for (int i = 0; i < manifold.pointCount; ++i) {
        const ContactPoint& point = manifold.points[i];
        if (point.depth >= -touchingTolerance && point.position.allFinite()) order[kept++] = i;
    }
    for (int i = 1; i < kept; ++i)  // insertion sort: stable, no allocation, at most 16 points
        for (int j = i; j > 0 && manifold.points[order[j]].depth > manifold.points[order[j - 1]].depth; --j)
            std::swap(order[j], order[j - 1]);
    int written = 0;
    for (int k = 0; k < kept && written < maxContacts; ++k) {
        const ContactPoint& point = manifold.points[order[k]];
        dContactGeom* out = reinterpret_cast<dContactGeom*>(reinterpret_cast<char*>(contact) +
                                                           static_cast<std::ptrdiff_t>(written) * skip);
        for (int axis = 0; axis < 3; ++axis) {
            out->pos[axis] = static_cast<dReal>(point.position[axis]);
            out->normal[axis] = static_cast<dReal>(normal[axis]);
        }
        out->pos[3] = 0;
        out->normal[3] = 0;
        out->depth = static_cast<dReal>(std::max(point.depth, 0.0));
        out->g1 = o1;
        out->g2 = o2;
        out->side1 = -1;
        out->side2 = -1;
        ++written;
    }
    return written;
}

void validate(const Settings& settings) {
    auto require = [](bool ok, const char* what) {
        if (!ok) throw InvalidInput(std::string("gdc::ode::install: ") + what);
    };
    require(settings.maxContacts >= 1 && settings.maxContacts <= kMaxManifoldPoints,
            "Settings::maxContacts must be in 1..16");
    require(std::isfinite(settings.rayCastTolerance) && settings.rayCastTolerance > 0.0,
            "Settings::rayCastTolerance must be finite and positive");
    require(settings.maxRayCastIterations >= 1, "Settings::maxRayCastIterations must be at least 1");
    require(std::isfinite(settings.angularTolerance) && settings.angularTolerance >= 0.0,
            "Settings::angularTolerance must be finite and non-negative");
    require(std::isfinite(settings.margin) && settings.margin >= 0.0,
            "Settings::margin must be finite and non-negative");
    require(settings.bruteForceSupportLimit >= 0, "Settings::bruteForceSupportLimit must be non-negative");
    require(std::isfinite(settings.coplanarTolerance) && settings.coplanarTolerance >= 0.0,
            "Settings::coplanarTolerance must be finite and non-negative");
}

int collideInstalled(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) {
    return collide(o1, o2, flags, contact, skip);
}

}  // namespace

void install(const Settings& settings) {
    validate(settings);
    detail::setInstalledSettings(settings);
    dSetColliderOverride(dBoxClass, dBoxClass, &collideInstalled);
    dSetColliderOverride(dBoxClass, dConvexClass, &collideInstalled);
    dSetColliderOverride(dConvexClass, dConvexClass, &collideInstalled);
    dSetColliderOverride(dBoxClass, dPlaneClass, &collideInstalled);
    dSetColliderOverride(dConvexClass, dPlaneClass, &collideInstalled);
}

int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip,
            const Settings& settings) {
    // ODE is C: no exception may cross back into it.
    try {
        return collideChecked(o1, o2, flags, contact, skip, settings);
    } catch (const InvalidInput& error) {  // its message already starts with "gdcontact: "
        dMessage(d_ERR_UNKNOWN, "%s (pair skipped)", error.what());
    } catch (const std::exception& error) {
        dMessage(d_ERR_UNKNOWN, "gdcontact: %s (pair skipped)", error.what());
    } catch (...) {
        dMessage(d_ERR_UNKNOWN, "gdcontact: unknown failure (pair skipped)");
    }
    return 0;
}

int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) {
    Settings settings;
    try {
        settings = detail::installedSettings();
    } catch (...) {  // a lock failure; the defaults are always valid
    }
    return collide(o1, o2, flags, contact, skip, settings);
}

std::shared_ptr<const Polytope> polytopeOf(dGeomID geom) {
    if (!geom) throw InvalidInput("gdc::ode::polytopeOf: null geom");
    switch (dGeomGetClass(geom)) {
        case dBoxClass: return boxPolytopeOf(geom);
        case dConvexClass: return detail::registeredConvex(geom);
        default: return nullptr;
    }
}

Pose poseOf(dGeomID geom) {
    if (!geom) throw InvalidInput("gdc::ode::poseOf: null geom");
    if (dGeomIsSpace(geom) || dGeomGetClass(geom) == dPlaneClass)
        throw InvalidInput("gdc::ode::poseOf: a plane or space has no pose");
    const dReal* position = dGeomGetPosition(geom);
    const dReal* rotation = dGeomGetRotation(geom);  // 3x4 row-major (dMatrix3)
    Pose pose;
    for (int row = 0; row < 3; ++row) {
        pose.position[row] = position[row];
        for (int column = 0; column < 3; ++column) pose.rotation(row, column) = rotation[4 * row + column];
    }
    return pose;
}

std::size_t liveConvexCount() { return detail::registeredConvexCount(); }

}  // namespace gdc::ode
