// Bullet (double precision, like ODE and gdcontact here) contenders on the shared fixtures.
// Every shape has a zero collision margin, so Bullet answers for the same exact geometry.
#pragma once

#include "fixtures.hpp"

#include <btBulletCollisionCommon.h>

#include <array>
#include <memory>
#include <vector>

namespace gdcbench {

btTransform toBullet(const Pose& pose);

/// Counts what a Bullet detector reports, keeps the first positions and the deepest point's
/// normal (from A towards B, the gdcontact convention; Bullet reports the normal on B).
struct BulletContacts : btDiscreteCollisionDetectorInterface::Result {
    static constexpr int kKeptPositions = 16;
    int count = 0;
    double deepest = -1e300;  ///< largest penetration (Bullet's depth is negative when overlapping)
    Vec3 normal = Vec3::Zero();
    std::array<Vec3, kKeptPositions> positions;
    void setShapeIdentifiersA(int, int) override {}
    void setShapeIdentifiersB(int, int) override {}
    void addContactPoint(const btVector3& normalOnBInWorld, const btVector3&, btScalar depth) override;
};

/// A convex hull with Bullet's polyhedral features (needed by btPolyhedralContactClipping).
std::unique_ptr<btConvexHullShape> makeBulletHull(const std::vector<Vec3>& points);
/// A box with zero margin (btBoxShape would otherwise shrink the core by its margin).
std::unique_ptr<btBoxShape> makeBulletBox(const Vec3& halfExtents);

/// btBoxBoxDetector, the box–box collider of Bullet's default dispatcher (at most 4 points).
int bulletBoxBox(const btBoxShape& a, const btTransform& poseA, const btBoxShape& b,
                 const btTransform& poseB, BulletContacts& out);
/// btGjkPairDetector with the EPA penetration solver: one point.
int bulletGjkEpa(const btConvexShape& a, const btTransform& poseA, const btConvexShape& b,
                 const btTransform& poseB, BulletContacts& out);
/// Bullet's default polyhedral path of btConvexConvexAlgorithm: GJK(+EPA) normal, then
/// btPolyhedralContactClipping::clipHullAgainstHull for the full manifold.
int bulletGjkClip(const btConvexHullShape& a, const btTransform& poseA, const btConvexHullShape& b,
                  const btTransform& poseB, BulletContacts& out);
/// Bullet's optional SAT path (m_enableSatConvex): findSeparatingAxis, then clipHullAgainstHull.
int bulletSatClip(const btConvexHullShape& a, const btTransform& poseA, const btConvexHullShape& b,
                  const btTransform& poseB, BulletContacts& out);

}  // namespace gdcbench
