// The per-pair benchmark cases, shared by every driver that measures them: bench_pairs (time,
// Google Benchmark), bench_instructions (instructions per call under callgrind) and bench_profile
// (perf). One definition, so that time, instruction counts and profiles are of the same calls.
//
// A case is one pair configuration (family/case), e.g. box_box/face_face_8, with its contenders
// (gdcontact core, gdcontact through the ODE adapter, ODE's native collider, Bullet). Every
// contender of a case cycles through the same poses: kPosesPerCase poses jittered about the
// canonical pose (fixtures.hpp) by up to ±1 mm and ±0.01 rad, so that every resting face is a
// little tilted as in a real scene, each pose with its own geom pair (ODE) or transforms
// (Bullet). The "_flat" families keep the single, exactly flat canonical pose (secondary figures).
#pragma once

#include "fixtures.hpp"

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace gdcbench {

/// Distinct poses each case cycles through.
constexpr int kPosesPerCase = 16;
/// Jitter of the cycled poses about the canonical pose.
constexpr double kJitterMetres = 1e-3;
constexpr double kJitterRadians = 0.01;

/// One contender of a case: `collide(poseIndex)` runs the query for pose poseIndex mod poseCount
/// (set up outside it) and returns the number of contacts.
struct PairContender {
    std::string name;
    std::function<int(int)> collide;
};

/// Which contenders (by name) to build; an empty filter builds them all.
using ContenderFilter = std::function<bool(const std::string&)>;

struct PairCaseSet {
    std::string family, caseName;
    int poseCount = 1;
    /// Builds the shapes, geoms and poses of every contender the filter wants (ODE must be
    /// initialised, and stay so while the returned contenders live).
    std::function<std::vector<PairContender>(const ContenderFilter&)> make;
    std::string name() const { return family + "/" + caseName; }
};

/// Every case, in the order the drivers run them: cube pairs, cube on a plane, the hull size sweep
/// (hull–hull and hull on a plane), the single-pose "_flat" families, then the curved pairs.
std::vector<PairCaseSet> pairCaseSets();

/// The curved pairs of issue 33 (curved_cases.cpp): cylinder_box, cylinder_plane, cylinder_convex,
/// capsule_box, capsule_convex, sphere_convex, cylinder_cylinder, capsule_cylinder, each resting,
/// with the contenders "ode" (ODE's own collider), "gdcontact_ode" and "gdcontact".
std::vector<PairCaseSet> curvedCaseSets();

/// For each curved case, the contacts (count, normal tilt, depths) that ODE's own collider, the
/// adapter and the core return for the cycled pose `poseIndex` (bench_curved_contacts).
void printCurvedContacts(std::ostream& out, int poseIndex);

/// `count` poses jittered about `canonical` (rotation about the body's centre), from `seed`.
std::vector<Pose> jitteredPoses(const Pose& canonical, int count, std::uint64_t seed);

}  // namespace gdcbench
