// Exact answers and alternative normal sources for the benchmarks. The exact minimum-translation
// normal (SAT over every face normal and edge pair) and the analytic contact polygon are the
// references the accuracy columns are measured against; libccd's MPR and GJK+EPA normals are the
// alternative "normal methods" of the sweep (the core only has the growth distance).
#pragma once

#include "fixtures.hpp"

#include <gdcontact/polytope.hpp>

#include <vector>

namespace gdcbench {

/// A hull placed in the world, seen through its vertices only (what libccd needs).
struct PlacedPoints {
    const std::vector<Vec3>* vertices;
    Pose pose;
};

struct NormalAnswer {
    bool overlapping = false;
    Vec3 normal = Vec3::UnitZ();  ///< unit, from A towards B
    double depth = 0.0;
};

/// Exact minimum translation: the smallest overlap of the projections over every face normal of
/// A and B and every cross product of an edge of A with an edge of B. For convex polytopes the
/// minimum over these axes is the penetration depth, and its axis the minimum normal.
NormalAnswer exactMinimumNormal(const gdc::Polytope& a, const Pose& poseA, const gdc::Polytope& b,
                                const Pose& poseB);
/// libccd's Minkowski Portal Refinement (what ODE 0.16.2 uses for convex–convex).
NormalAnswer mprNormal(const PlacedPoints& a, const PlacedPoints& b, double tolerance = 1e-4);
/// libccd's GJK + EPA.
NormalAnswer epaNormal(const PlacedPoints& a, const PlacedPoints& b, double tolerance = 1e-4);
/// Whether the two hulls intersect (libccd's GJK).
bool intersects(const PlacedPoints& a, const PlacedPoints& b);

/// The largest distance t by which A, posed at rotationA and translated by t·direction, still
/// touches B posed at (rotationB, origin); by bisection on libccd's GJK test. Both point clouds
/// must contain their origin in the interior.
double touchingDistance(const std::vector<Vec3>& a, const Mat3& rotationA, const std::vector<Vec3>& b,
                        const Mat3& rotationB, const Vec3& direction);

/// `count` random relative poses of hulls A and B (rotations uniform, approach direction uniform),
/// each overlapping by `overlap` metres along the line of centres. Deterministic for a seed.
std::vector<std::pair<Pose, Pose>> touchingPoses(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                                                 int count, double overlap, std::uint64_t seed);

// ---- 2-D polygons in a contact plane --------------------------------------------------------
using Polygon2 = std::vector<gdc::Vec2>;
/// Orthonormal basis (u, v) of the plane perpendicular to `normal`.
void planeBasis(const Vec3& normal, Vec3& u, Vec3& v);
Polygon2 project(const std::vector<Vec3>& points, const Vec3& u, const Vec3& v);
/// Counter-clockwise convex hull (Andrew's monotone chain); degenerate inputs give ≤ 2 points.
Polygon2 convexHull2(Polygon2 points);
/// Intersection of two counter-clockwise convex polygons (exact clipping of one by the other's edges).
Polygon2 intersectConvex(const Polygon2& subject, const Polygon2& clip);
double area(const Polygon2& polygon);
/// Hausdorff distance between two convex regions (each given by its vertices): for convex sets
/// the farthest point of one from the other is one of its vertices.
double hausdorff(const Polygon2& p, const Polygon2& q);

}  // namespace gdcbench
