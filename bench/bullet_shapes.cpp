#include "bullet_shapes.hpp"

#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

namespace gdcbench {

btTransform toBullet(const Pose& pose) {
    const Mat3& r = pose.rotation;
    const btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2));
    return btTransform(basis, btVector3(pose.position.x(), pose.position.y(), pose.position.z()));
}

void BulletContacts::addContactPoint(const btVector3& normalOnBInWorld, const btVector3& point, btScalar depth) {
    if (count < kKeptPositions) positions[count] = Vec3(point.x(), point.y(), point.z());
    ++count;
    if (-depth > deepest) {
        deepest = -depth;
        normal = -Vec3(normalOnBInWorld.x(), normalOnBInWorld.y(), normalOnBInWorld.z());
    }
}

std::unique_ptr<btConvexHullShape> makeBulletHull(const std::vector<Vec3>& points) {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const Vec3& p : points) hull->addPoint(btVector3(p.x(), p.y(), p.z()), false);
    hull->recalcLocalAabb();
    hull->setMargin(0);
    hull->initializePolyhedralFeatures();
    return hull;
}

std::unique_ptr<btBoxShape> makeBulletBox(const Vec3& halfExtents) {
    auto box = std::make_unique<btBoxShape>(btVector3(halfExtents.x(), halfExtents.y(), halfExtents.z()));
    box->setMargin(0);  // keeps the outer extents, so the box is exactly the given one
    return box;
}

int bulletBoxBox(const btBoxShape& a, const btTransform& poseA, const btBoxShape& b,
                 const btTransform& poseB, BulletContacts& out) {
    btBoxBoxDetector detector(&a, &b);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = poseA;
    input.m_transformB = poseB;
    detector.getClosestPoints(input, out, nullptr);
    return out.count;
}

namespace {

/// Bullet's GJK (with EPA for overlapping shapes): the closest points, or the deepest one.
BulletContacts gjkEpaClosest(const btConvexShape& a, const btTransform& poseA, const btConvexShape& b,
                             const btTransform& poseB) {
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    btGjkPairDetector detector(&a, &b, &simplex, &epa);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = poseA;
    input.m_transformB = poseB;
    BulletContacts closest;
    detector.getClosestPoints(input, closest, nullptr);
    return closest;
}

}  // namespace

int bulletGjkEpa(const btConvexShape& a, const btTransform& poseA, const btConvexShape& b,
                 const btTransform& poseB, BulletContacts& out) {
    const BulletContacts closest = gjkEpaClosest(a, poseA, b, poseB);
    // GJK also reports the closest points of separated shapes; count only touching ones, as the others do.
    if (closest.count > 0 && closest.deepest >= 0) {
        if (out.count < BulletContacts::kKeptPositions) out.positions[out.count] = closest.positions[0];
        out.count += 1;
        out.deepest = closest.deepest;
        out.normal = closest.normal;
    }
    return out.count;
}

namespace {

// Both clipping paths clip with B's normal (pointing from B into A), reporting points whose
// depth lies in [minDist, 0]: touching or overlapping, like the other contenders.
int clip(const btConvexHullShape& a, const btTransform& poseA, const btConvexHullShape& b,
         const btTransform& poseB, const btVector3& normalOnB, double distance, BulletContacts& out) {
    btVertexArray scratch1, scratch2;
    btPolyhedralContactClipping::clipHullAgainstHull(normalOnB, *a.getConvexPolyhedron(), *b.getConvexPolyhedron(),
                                                     poseA, poseB, distance, 0.0, scratch1, scratch2, out);
    return out.count;
}

}  // namespace

int bulletGjkClip(const btConvexHullShape& a, const btTransform& poseA, const btConvexHullShape& b,
                  const btTransform& poseB, BulletContacts& out) {
    const BulletContacts closest = gjkEpaClosest(a, poseA, b, poseB);
    if (closest.count == 0 || closest.deepest < 0) return out.count;
    const Vec3 normalOnB = -closest.normal;
    return clip(a, poseA, b, poseB, btVector3(normalOnB.x(), normalOnB.y(), normalOnB.z()), -closest.deepest, out);
}

int bulletSatClip(const btConvexHullShape& a, const btTransform& poseA, const btConvexHullShape& b,
                  const btTransform& poseB, BulletContacts& out) {
    btVector3 separatingAxis;
    BulletContacts unused;
    if (!btPolyhedralContactClipping::findSeparatingAxis(*a.getConvexPolyhedron(), *b.getConvexPolyhedron(), poseA,
                                                         poseB, separatingAxis, unused))
        return out.count;
    // As btConvexConvexAlgorithm does on this path: no distance bound from SAT, so clip from far below.
    return clip(a, poseA, b, poseB, separatingAxis, -1e30, out);
}

}  // namespace gdcbench
