// Shapes and poses shared by every contender, so that gdcontact, ODE and Bullet are timed on
// exactly the same geometry. Only Eigen and the gdcontact value types; no engine headers here.
#pragma once

#include <gdcontact/collide.hpp>
#include <gdcontact/types.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace gdcbench {

using gdc::Mat3;
using gdc::Pose;
using gdc::Vec3;

/// Half extent of the canonical cube (1 m edge), the size every canonical case is built for.
constexpr double kCubeHalfExtent = 0.5;
/// Overlap of the "resting" cases (metres): a typical penetration after a solver step.
constexpr double kRestingOverlap = 0.01;
/// Radius of the near-sphere hulls in the size sweep (metres).
constexpr double kSphereRadius = 0.5;
/// Vertex counts of the size sweep. 8 is the cube (inscribed in the same sphere), the others are
/// Fibonacci spheres.
const std::vector<int>& hullSizes();

/// Rotation by `angle` radians about `axis` (normalised here).
Mat3 rotation(const Vec3& axis, double angle);
/// outer ∘ inner: first inner, then outer.
Pose compose(const Pose& outer, const Pose& inner);

/// A small deterministic generator (splitmix64), so that the random pose sets are the same on
/// every machine and standard library (std::uniform_*_distribution is implementation-defined).
class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next();
    double uniform();  ///< in [0, 1)
    double uniform(double low, double high) { return low + (high - low) * uniform(); }
    Vec3 unitVector();
    Mat3 rotation();  ///< uniformly distributed over SO(3)
private:
    std::uint64_t state_;
};

/// CPU time of the calling thread (seconds). The benchmarks time with it rather than the wall
/// clock: on a shared machine other processes then cost us nothing but cache.
double threadCpuSeconds();

/// The 8 corners of an axis-aligned box centred at the origin.
std::vector<Vec3> boxVertices(const Vec3& halfExtents);
/// `count` points on a sphere of `radius` about the origin, spread by the golden angle (all of
/// them are hull vertices, so the hull has exactly `count` vertices).
std::vector<Vec3> fibonacciSphere(int count, double radius);
/// The point cloud of the size sweep: the cube inscribed in the sphere for 8, else a Fibonacci sphere.
std::vector<Vec3> sweepHullPoints(int count);

/// A frame applied to every canonical case, so that no contender profits from axis-aligned
/// world coordinates (the relative geometry, hence the exact answer, is unchanged).
Pose commonFrame();

/// Two canonical cubes (half extent kCubeHalfExtent); A above B.
struct PairCase {
    std::string name;
    Pose poseA, poseB;
    int maxContacts;
    int expectedContacts;  ///< corners of the exact contact region (-1: not a single face contact)
};
/// resting face–face (octagon, 8 points), the same culled to 4, edge–edge, vertex–face,
/// separated (early out), deep overlap.
std::vector<PairCase> cubePairCases();

/// A canonical cube over a plane.
struct PlaneCase {
    std::string name;
    Pose pose;
    gdc::HalfSpace plane;
    int maxContacts;
    int expectedContacts;
};
/// resting face (4 points), edge (2), vertex (1), separated, deep (centre 0.1 m above the plane).
std::vector<PlaneCase> cubePlaneCases();

/// A plane at the common frame's z = 0 (solid below).
gdc::HalfSpace groundPlane();

}  // namespace gdcbench
