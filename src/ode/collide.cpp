// gdc::ode::install / collide: ODE's geoms in, the core's manifold out as dContactGeoms.
#include <gdcontact/ode.hpp>

#include "state.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <functional>
#include <string>

namespace gdc::ode {
namespace {

// One side of a pair. Built in place by readShape (no default-initialised pose to overwrite).
struct Shape {
    // Geom-local frame; nullptr for a plane. Borrowed from the adapter's state (see state.hpp)
    // for the duration of one collide call, so that no reference count is touched per pair.
    const Polytope* polytope;
    Pose pose;            // a polytope's world pose
    HalfSpace halfSpace;  // a plane, world frame
    bool isPlane() const { return polytope == nullptr; }
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

// poseOf without its checks, for geoms whose class is already known to be placeable.
Pose readPose(dGeomID geom) {
    const dReal* position = dGeomGetPosition(geom);
    // A dMatrix3 is 3x4 row-major (the fourth column is padding).
    using OdeRotation = Eigen::Map<const Eigen::Matrix<dReal, 3, 3, Eigen::RowMajor>, Eigen::Unaligned,
                                   Eigen::OuterStride<4>>;
    return Pose{OdeRotation(dGeomGetRotation(geom)).cast<double>(),
                Vec3(position[0], position[1], position[2])};
}

// Misuse of the adapter is a programming error: ODE's error handler (which by default prints
// the message and exits) is the loud way ODE itself reports those.
[[noreturn]] void misuse(const std::string& what) {
    dError(d_ERR_UASSERT, "%s", ("gdcontact: " + what).c_str());
}

Shape readShape(dGeomID geom, detail::ThreadCache& cache) {
    const int geomClass = dGeomGetClass(geom);
    switch (geomClass) {
        case dBoxClass: {
            dVector3 lengths;
            dGeomBoxGetLengths(geom, lengths);
            return Shape{&detail::borrowedBoxPolytope(cache, 0.5 * lengths[0], 0.5 * lengths[1], 0.5 * lengths[2]),
                         readPose(geom), HalfSpace{}};
        }
        case dConvexClass: {
            const Polytope* hull = detail::borrowedConvex(cache, geom);
            if (!hull)
                misuse("a dConvex geom made with plain dCreateConvex reached gdc::ode::collide. ODE "
                       "0.16.2 gives no access to a dConvex's data, so gdcontact cannot collide it. "
                       "Create the geom with gdc::ode::createConvex(space, planes, planeCount, points, "
                       "pointCount, polygons) (the same arguments as dCreateConvex) or "
                       "gdc::ode::createConvex(space, points, pointCount) instead.");
            return Shape{hull, readPose(geom), HalfSpace{}};
        }
        case dPlaneClass: {
            dVector4 parameters;  // a·x + b·y + c·z ≤ d is the solid; (a,b,c) points out of it
            dGeomPlaneGetParams(geom, parameters);
            return Shape{nullptr, Pose{},
                         HalfSpace{detail::unitPlaneNormal(cache, parameters[0], parameters[1], parameters[2]),
                                   static_cast<double>(parameters[3])}};
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

    detail::ThreadCache& cache = detail::threadCache();
    const Shape shape1 = readShape(o1, cache);
    const Shape shape2 = readShape(o2, cache);
    if (shape1.isPlane() && shape2.isPlane())
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
    const bool swapped = shape1.isPlane() || (!shape2.isPlane() && before(shape2, o2, shape1, o1));
    const Shape& a = swapped ? shape2 : shape1;
    const Shape& b = swapped ? shape1 : shape2;

    const Manifold manifold = [&] {
        auto collideWith = [&](const Settings& pairSettings) {
            return b.isPlane() ? gdc::collide(*a.polytope, a.pose, b.halfSpace, pairSettings)
                               : gdc::collide(*a.polytope, a.pose, *b.polytope, b.pose, pairSettings);
        };
        if (settings.maxContacts == maxContacts) return collideWith(settings);  // the common case: no copy
        Settings pairSettings = settings;
        pairSettings.maxContacts = maxContacts;
        return collideWith(pairSettings);
    }();
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
    const double sizeOfPair = a.polytope->radius() + (b.isPlane() ? 0.0 : b.polytope->radius());
    const double touchingTolerance = 1e-9 * sizeOfPair;
    // Deepest first, as ODE's own colliders list them. dWorldQuickStep sweeps the contact rows in
    // the order given; the core's order walks the contact polygon the same way round every step,
    // and under QuickStep that fixed order roughly doubled a 10-stack's drift (samples/ode_stack).
    // Kept points are inserted by depth as they are read (stable: equal depths keep the core's
    // order); at most 16, so an insertion sort on a compact copy of the depths is the cheapest.
    std::array<int, kMaxManifoldPoints> order;  // indices into manifold.points, deepest first
    std::array<double, kMaxManifoldPoints> orderDepth;
    int kept = 0;
    for (int i = 0; i < manifold.pointCount; ++i) {
        const ContactPoint& point = manifold.points[i];
        if (!(point.depth >= -touchingTolerance && point.position.allFinite())) continue;
        int slot = kept++;
        for (; slot > 0 && point.depth > orderDepth[slot - 1]; --slot) {
            order[slot] = order[slot - 1];
            orderDepth[slot] = orderDepth[slot - 1];
        }
        order[slot] = i;
        orderDepth[slot] = point.depth;
    }
    const int written = std::min(kept, maxContacts);
    const dReal odeNormal[4] = {static_cast<dReal>(normal.x()), static_cast<dReal>(normal.y()),
                                static_cast<dReal>(normal.z()), 0};
    char* outBytes = reinterpret_cast<char*>(contact);
    for (int k = 0; k < written; ++k, outBytes += skip) {
        const ContactPoint& point = manifold.points[order[k]];
        dContactGeom* out = reinterpret_cast<dContactGeom*>(outBytes);
        out->pos[0] = static_cast<dReal>(point.position.x());
        out->pos[1] = static_cast<dReal>(point.position.y());
        out->pos[2] = static_cast<dReal>(point.position.z());
        out->pos[3] = 0;
        std::memcpy(out->normal, odeNormal, sizeof odeNormal);
        out->depth = static_cast<dReal>(std::max(orderDepth[k], 0.0));
        out->g1 = o1;
        out->g2 = o2;
        out->side1 = -1;
        out->side2 = -1;
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
    static const Settings defaults;
    const Settings* settings = &defaults;
    try {
        settings = &detail::installedSettings(detail::threadCache());
    } catch (...) {  // a lock failure; the defaults are always valid
    }
    return collide(o1, o2, flags, contact, skip, *settings);
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
