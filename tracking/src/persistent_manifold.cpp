// The persistent manifold of one pair: libccd MPR for one new point per step, Bullet-style refresh,
// breaking and replacement. See gdcontact/tracking.hpp for the contract and docs/tracking.md for
// why it is built this way.
#include <gdcontact/tracking.hpp>

#include <ccd/ccd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

namespace gdc::tracking {
namespace {

// Debian's libccd is built with CCD_DOUBLE; a single-precision build would silently lose the
// precision the comparison against gdcontact depends on, so refuse to compile against it.
static_assert(std::is_same<ccd_real_t, double>::value,
              "gdcontact tracking needs a double-precision libccd (CCD_DOUBLE)");

// A polytope placed in the frame MPR works in (world axes, origin at pose A's position).
struct PlacedPolytope {
    const Polytope* polytope;
    Pose pose;
};

Vec3 fromCcd(const ccd_vec3_t& vector) {
    return {vector.v[0], vector.v[1], vector.v[2]};
}

void toCcd(const Vec3& vector, ccd_vec3_t* out) {
    out->v[0] = vector.x();
    out->v[1] = vector.y();
    out->v[2] = vector.z();
}

// libccd callbacks: the support point of a placed polytope in a world direction, and an interior
// point (the centroid), which MPR uses as the start of its portal ray.
void supportOf(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
    const auto& placed = *static_cast<const PlacedPolytope*>(object);
    const Vec3 localDirection = placed.pose.rotation.transpose() * fromCcd(*direction);
    const int vertex = placed.polytope->supportVertex(localDirection);
    toCcd(placed.pose.apply(placed.polytope->vertices()[vertex]), out);
}

void centerOf(const void* object, ccd_vec3_t* out) {
    const auto& placed = *static_cast<const PlacedPolytope*>(object);
    toCcd(placed.pose.apply(placed.polytope->centroid()), out);
}

struct MprContact {
    Vec3 normal;    // from A towards B
    Vec3 position;  // a point in the overlap
    double depth;
};

// ccdMPRPenetration(A, B) reports `dir` such that translating B by depth·dir separates the pair
// (verified in the tests: B above A gives +z), i.e. from A towards B: exactly the core's normal.
// Returns false for no overlap and for libccd's exact-touching answer (depth 0 with a zero
// direction, which has no usable normal).
bool runMpr(const PlacedPolytope& a, const PlacedPolytope& b, const TrackingSettings& settings,
            MprContact* contact) {
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = supportOf;
    ccd.support2 = supportOf;
    ccd.center1 = centerOf;
    ccd.center2 = centerOf;
    ccd.max_iterations = static_cast<unsigned long>(settings.maxMprIterations);
    ccd.mpr_tolerance = settings.mprRelativeTolerance * (a.polytope->radius() + b.polytope->radius());

    ccd_real_t depth = 0.0;
    ccd_vec3_t direction, position;
    if (ccdMPRPenetration(&a, &b, &ccd, &depth, &direction, &position) != 0) return false;

    const Vec3 normal = fromCcd(direction);
    const Vec3 point = fromCcd(position);
    const double length = normal.norm();
    if (!std::isfinite(depth) || !point.allFinite() || !std::isfinite(length) ||
        std::abs(length - 1.0) > 1e-6 || depth <= 0.0)
        return false;
    *contact = {normal / length, point, depth};
    return true;
}

// Signed distance along the unit `direction` from `point` to where the line through them leaves the
// polytope (≥ 0 when `point` is inside), or NaN when the line misses the polytope. The polytope's
// face planes bound it: the line is inside while it is on the inner side of every plane, so it
// leaves at the nearest front-facing plane and enters at the farthest back-facing one.
double exitDistance(const PlacedPolytope& placed, const Vec3& point, const Vec3& direction) {
    const Vec3 localPoint = placed.pose.applyInverse(point);
    const Vec3 localDirection = placed.pose.rotation.transpose() * direction;
    const double slack = 1e-9 * placed.polytope->radius();
    double entry = -std::numeric_limits<double>::infinity();
    double exit = std::numeric_limits<double>::infinity();
    for (const Polytope::Face& face : placed.polytope->faces()) {
        const double along = face.normal.dot(localDirection);
        const double gap = face.offset - face.normal.dot(localPoint);  // > 0: inside this plane
        if (std::abs(along) < 1e-12) {
            if (gap < -slack) return std::numeric_limits<double>::quiet_NaN();  // parallel, outside
        } else if (along > 0.0) {
            exit = std::min(exit, gap / along);
        } else {
            entry = std::max(entry, gap / along);
        }
    }
    if (!(entry <= exit + slack) || !std::isfinite(exit)) return std::numeric_limits<double>::quiet_NaN();
    return exit;
}

// The new point's two anchors. MPR's `pos` is a point of the overlap, not of either surface, so
// the anchors are where the line through it along the normal leaves A (on B's side) and leaves B
// (on A's side); their offset along the normal is the overlap at that spot, never more than MPR's
// depth. If the line misses a body (pos numerically outside it), MPR's own depth is split evenly
// about pos instead, which keeps the convention (anchor A − anchor B = depth·normal).
void anchorsOf(const PlacedPolytope& a, const PlacedPolytope& b, const MprContact& contact, Vec3* onA,
               Vec3* onB) {
    const double alongA = exitDistance(a, contact.position, contact.normal);
    const double alongB = exitDistance(b, contact.position, -contact.normal);
    if (std::isfinite(alongA) && std::isfinite(alongB) && alongA + alongB >= 0.0) {
        *onA = contact.position + alongA * contact.normal;
        *onB = contact.position - alongB * contact.normal;
    } else {
        *onA = contact.position + 0.5 * contact.depth * contact.normal;
        *onB = contact.position - 0.5 * contact.depth * contact.normal;
    }
}

// Any two unit vectors spanning the plane perpendicular to `normal`.
void planeBasis(const Vec3& normal, Vec3* u, Vec3* v) {
    const Vec3 helper = std::abs(normal.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    *u = normal.cross(helper).normalized();
    *v = normal.cross(*u);
}

void requireSettings(bool ok, const std::string& what) {
    if (!ok) throw InvalidInput("tracking: " + what);
}

}  // namespace

PersistentManifold::PersistentManifold(TrackingSettings settings) : settings_(settings) {
    requireSettings(std::isfinite(settings.breakingThreshold) && settings.breakingThreshold > 0.0,
                    "breakingThreshold must be finite and positive");
    requireSettings(settings.maxPoints >= 1 && settings.maxPoints <= kMaxManifoldPoints,
                    "maxPoints must be in 1.." + std::to_string(kMaxManifoldPoints));
    requireSettings(std::isfinite(settings.mergeDistance) && settings.mergeDistance >= 0.0,
                    "mergeDistance must be finite and non-negative");
    requireSettings(std::isfinite(settings.speculativeMargin) && settings.speculativeMargin >= 0.0,
                    "speculativeMargin must be finite and non-negative");
    requireSettings(std::isfinite(settings.mprRelativeTolerance) && settings.mprRelativeTolerance > 0.0,
                    "mprRelativeTolerance must be finite and positive");
    requireSettings(settings.maxMprIterations >= 1, "maxMprIterations must be at least 1");
}

const TrackedPoint& PersistentManifold::point(int index) const {
    if (index < 0 || index >= count_)
        throw InvalidInput("tracking: point index " + std::to_string(index) + " out of range (" +
                           std::to_string(count_) + " points)");
    return points_[index];
}

void PersistentManifold::clear() {
    count_ = 0;
    hasNormal_ = false;
    report_ = {};
}

void PersistentManifold::swapBodies() {
    for (int i = 0; i < count_; ++i) {
        std::swap(points_[i].anchorOnA, points_[i].anchorOnB);
        std::swap(points_[i].worldOnA, points_[i].worldOnB);
        // depth = (onA − onB)·normal is invariant under swapping the anchors and negating normal.
    }
    normalWorld_ = -normalWorld_;
    const Vec3 oldNormalInA = normalInA_;
    normalInA_ = -normalInB_;
    normalInB_ = -oldNormalInA;
}

// Bullet's refreshContactPoints, along the manifold's single current normal: recompute both world
// anchors from the new poses, the depth along the normal and the tangential drift; drop a point
// that separated or slid by more than the breaking threshold. Poses are relative to `origin`.
void PersistentManifold::refresh(const Pose& poseA, const Pose& poseB, const Vec3& origin) {
    int kept = 0;
    for (int i = 0; i < count_; ++i) {
        TrackedPoint point = points_[i];
        const Vec3 onA = poseA.apply(point.anchorOnA);
        const Vec3 onB = poseB.apply(point.anchorOnB);
        const Vec3 offset = onA - onB;
        point.depth = offset.dot(normalWorld_);
        const double drift = (offset - point.depth * normalWorld_).norm();
        point.worldOnA = onA + origin;
        point.worldOnB = onB + origin;
        ++point.age;
        if (-point.depth > settings_.breakingThreshold || drift > settings_.breakingThreshold) {
            ++report_.dropped;
            continue;
        }
        points_[kept++] = point;
    }
    count_ = kept;
}

// Bullet's addManifoldPoint: merge with a stored point close on A, else a free slot, else replace
// by the area rule (in the contact plane, world anchors taken relative to `origin`).
void PersistentManifold::insert(const TrackedPoint& candidate, const Vec3& origin) {
    int nearest = -1;
    double nearestDistance = settings_.mergeDistance;
    for (int i = 0; i < count_; ++i) {
        const double distance = (points_[i].anchorOnA - candidate.anchorOnA).norm();
        // `<=` for the first hit so that mergeDistance = 0 still merges an identical point.
        if (distance < nearestDistance || (nearest < 0 && distance <= nearestDistance)) {
            nearest = i;
            nearestDistance = distance;
        }
    }
    if (nearest >= 0) {
        points_[nearest] = candidate;
        report_.mergedInto = nearest;
        return;
    }
    if (count_ < settings_.maxPoints) {
        points_[count_] = candidate;
        report_.added = count_++;
        return;
    }
    Vec3 u, v;
    planeBasis(normalWorld_, &u, &v);
    const auto inPlane = [&](const TrackedPoint& point) {
        const Vec3 middle = 0.5 * (point.worldOnA + point.worldOnB) - origin;
        return Vec2(middle.dot(u), middle.dot(v));
    };
    std::array<Vec2, kMaxManifoldPoints> projected;
    std::array<double, kMaxManifoldPoints> depths;
    for (int i = 0; i < count_; ++i) {
        projected[i] = inPlane(points_[i]);
        depths[i] = points_[i].depth;
    }
    const int victim =
        choosePointToReplace(projected.data(), depths.data(), count_, inPlane(candidate), candidate.depth);
    if (victim < 0) return;
    points_[victim] = candidate;
    report_.added = victim;
    report_.replacedExisting = true;
}

Manifold PersistentManifold::update(const Polytope& a, const Pose& poseA, const Polytope& b,
                                    const Pose& poseB) {
    if (!poseA.isFinite()) throw InvalidInput("tracking: pose of A is not finite");
    if (!poseB.isFinite()) throw InvalidInput("tracking: pose of B is not finite");
    return step(a, poseA, b, poseB, poseB);
}

Manifold PersistentManifold::update(const Polytope& a, const Pose& poseA, const HalfSpace& b) {
    if (!poseA.isFinite()) throw InvalidInput("tracking: pose of A is not finite");
    const double length = b.normal.norm();
    if (!b.normal.allFinite() || !std::isfinite(b.offset) || !(length > 0.0))
        throw InvalidInput("tracking: the half-space normal must be finite and non-zero");
    const Vec3 up = b.normal / length;
    // The plane's frame: local z along the plane's outward normal, origin on the plane. Fixed for
    // a fixed plane (the basis is a deterministic function of the normal), so B's anchors stay put.
    Vec3 u, v;
    planeBasis(up, &u, &v);
    Pose plane;
    plane.rotation.col(0) = u;
    plane.rotation.col(1) = v;
    plane.rotation.col(2) = up;
    plane.position = (b.offset / length) * up;

    // The stand-in: a cube of half size h, top face in the plane, centred under A's centroid.
    // h = 4·radius(A) covers every point of A laterally with room to spare and keeps the cube's
    // centre deep enough that MPR's first ray (centre to centre) runs along the plane normal.
    const double halfSize = 4.0 * a.radius();
    if (!proxy_ || proxyHalfSize_ != halfSize) {
        proxy_ = Polytope::box(Vec3::Constant(halfSize));
        proxyHalfSize_ = halfSize;
    }
    const Vec3 centroid = plane.applyInverse(poseA.apply(a.centroid()));
    Pose stand = plane;
    stand.position = plane.apply(Vec3(centroid.x(), centroid.y(), -halfSize));
    return step(a, poseA, *proxy_, stand, plane);
}

Manifold PersistentManifold::step(const Polytope& a, const Pose& poseA, const Polytope& b,
                                  const Pose& mprPoseB, const Pose& anchorPoseB) {
    report_ = {};

    // Work relative to A's position: libccd and the refresh subtract nearby points, which loses
    // every digit the absolute coordinates carry (1 km from the origin costs 3 of them).
    const Vec3 origin = poseA.position;
    const PlacedPolytope placedA{&a, {poseA.rotation, Vec3::Zero()}};
    const PlacedPolytope placedB{&b, {mprPoseB.rotation, mprPoseB.position - origin}};
    const Pose frameB{anchorPoseB.rotation, anchorPoseB.position - origin};
    const Pose& poseB = anchorPoseB;

    MprContact contact{};
    report_.mprFoundContact = runMpr(placedA, placedB, settings_, &contact);
    if (report_.mprFoundContact) {
        normalWorld_ = contact.normal;
        normalInA_ = poseA.rotation.transpose() * contact.normal;
        normalInB_ = poseB.rotation.transpose() * contact.normal;
        hasNormal_ = true;
    } else if (hasNormal_) {
        // No new information about the normal: carry the last one along with B's rotation (a
        // consistent choice; exact for a half-space, whose frame is fixed).
        normalWorld_ = (poseB.rotation * normalInB_).normalized();
        normalInA_ = poseA.rotation.transpose() * normalWorld_;
    }

    if (hasNormal_) refresh(placedA.pose, frameB, origin);

    if (report_.mprFoundContact) {
        Vec3 onA, onB;
        anchorsOf(placedA, placedB, contact, &onA, &onB);
        TrackedPoint fresh;
        fresh.anchorOnA = placedA.pose.applyInverse(onA);
        fresh.anchorOnB = frameB.applyInverse(onB);
        fresh.worldOnA = onA + origin;
        fresh.worldOnB = onB + origin;
        fresh.depth = (onA - onB).dot(normalWorld_);
        fresh.age = 0;
        insert(fresh, origin);
    }
    if (count_ == 0) hasNormal_ = false;

    Manifold result;
    result.normal = normalWorld_;
    for (int i = 0; i < count_; ++i) {
        const TrackedPoint& point = points_[i];
        if (point.depth < -settings_.speculativeMargin) continue;
        ContactPoint& out = result.points[result.pointCount++];
        out.position = 0.5 * (point.worldOnA + point.worldOnB);
        out.depth = point.depth;
    }
    return result;
}

}  // namespace gdc::tracking
