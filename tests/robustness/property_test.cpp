// The invariants every contact must satisfy, on thousands of random overlapping poses of random
// polytopes (seeded). GDCONTACT_PROPERTY_POSES=N runs N poses instead (the long mode of
// scripts/fuzz runs millions).
#include "robustness_support.hpp"

#include <catch2/catch.hpp>

using namespace gdc;
using namespace gdc::robustness;

namespace {

// Checks one manifold and its swapped twin; returns a description of the first violated
// invariant, or an empty string.
std::string violation(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                      const Settings& settings) {
    const double size = a.radius() + b.radius();
    const double tolerance = 1e-9 * size;
    const Manifold m = collide(a, poseA, b, poseB, settings);
    const double trueOverlap = satOverlap(a, poseA, b, poseB);
    if (m.empty()) return trueOverlap > tolerance ? "no contacts for an overlapping pair" : "";
    if (!m.normal.allFinite() || std::abs(m.normal.norm() - 1) > 1e-12) return "normal not unit and finite";
    if (m.pointCount < 1 || m.pointCount > settings.maxContacts) return "point count out of range";
    double deepest = -INFINITY;
    for (int i = 0; i < m.pointCount; ++i) {
        const ContactPoint& p = m.points[i];
        if (!p.position.allFinite() || !std::isfinite(p.depth)) return "non-finite point or depth";
        if (p.depth < -tolerance) return "negative depth " + std::to_string(p.depth);
        // Midway between a point of A and a point of B `depth` apart: within depth/2 of both.
        if (signedDistance(a, poseA, p.position) > 0.5 * p.depth + tolerance) return "point outside A by more than depth/2";
        if (signedDistance(b, poseB, p.position) > 0.5 * p.depth + tolerance) return "point outside B by more than depth/2";
        deepest = std::max(deepest, p.depth);
    }
    // ODE's own collider property (ODE's demo_collision, dBoxBox): moving B along the normal by
    // 0.96·depth leaves the pair touching, by 1.04·depth separates it.
    auto movedB = [&](double distance) { return Pose{poseB.rotation, poseB.position + distance * m.normal}; };
    if (satOverlap(a, poseA, b, movedB(0.96 * deepest)) < -tolerance) return "separated after 0.96·depth";
    if (satOverlap(a, poseA, b, movedB(1.04 * deepest)) > tolerance) return "still overlapping after 1.04·depth";
    // Swap symmetry: the same contacts with the normal negated.
    const Manifold swapped = collide(b, poseB, a, poseA, settings);
    if (swapped.pointCount != m.pointCount) return "swap changes the point count";
    if ((swapped.normal + m.normal).norm() > 1e-9) return "swap does not negate the normal";
    for (int i = 0; i < m.pointCount; ++i) {
        bool matched = false;
        for (int j = 0; j < swapped.pointCount && !matched; ++j)
            matched = (swapped.points[j].position - m.points[i].position).norm() <= 1e-9 * size &&
                      std::abs(swapped.points[j].depth - m.points[i].depth) <= 1e-9 * size;
        if (!matched) return "swap changes a contact point";
    }
    return "";
}

}  // namespace

TEST_CASE("random overlapping polytopes: every contact satisfies every invariant", "[robustness][property]") {
    const long poses = environmentCount("GDCONTACT_PROPERTY_POSES", 3000);
    const unsigned long seed = static_cast<unsigned long>(environmentCount("GDCONTACT_PROPERTY_SEED", 20100701));
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> push(0.0, 0.05);
    Settings settings;
    settings.maxContacts = kMaxManifoldPoints;
    long failures = 0;
    for (long pose = 0; pose < poses; ++pose) {
        const Polytope a = randomHull(random), b = randomHull(random);
        Pose poseA, poseB;
        randomContactPose(random, a, b, push(random), poseA, poseB);
        const std::string problem = violation(a, poseA, b, poseB, settings);
        if (!problem.empty() && failures++ < 10) {
            INFO("seed " << seed << ", pose " << pose << ": " << problem);
            CHECK(problem.empty());
        }
    }
    CHECK(failures == 0);
}
