// Concurrent collide calls: the core is pure (shared immutable polytopes, value manifolds) and the
// ODE adapter's only shared state is its locked registry and box cache. scripts/sanitize runs
// these cases under ThreadSanitizer; here they also check that every thread gets the sequential
// answer.
#include "robustness_support.hpp"

#include <gdcontact/ode.hpp>

#include <ode/ode.h>

#include <catch2/catch.hpp>

#include <atomic>
#include <thread>

using namespace gdc;
using namespace gdc::robustness;

namespace {

bool sameManifold(const Manifold& a, const Manifold& b) {
    if (a.pointCount != b.pointCount || a.normal != b.normal) return false;
    for (int i = 0; i < a.pointCount; ++i)
        if (a.points[i].position != b.points[i].position || a.points[i].depth != b.points[i].depth) return false;
    return true;
}

}  // namespace

TEST_CASE("core collide from several threads on shared polytopes gives the sequential answers", "[robustness][threads]") {
    std::mt19937_64 random(31337);
    std::vector<Polytope> shapes;
    for (int i = 0; i < 8; ++i) shapes.push_back(randomHull(random));
    struct Query {
        int a, b;
        Pose poseA, poseB;
        Manifold expected;
    };
    std::vector<Query> queries;
    for (int i = 0; i < 400; ++i) {
        Query q{static_cast<int>(random() % shapes.size()), static_cast<int>(random() % shapes.size()), {}, {}, {}};
        randomContactPose(random, shapes[q.a], shapes[q.b], 0.02, q.poseA, q.poseB);
        q.expected = collide(shapes[q.a], q.poseA, shapes[q.b], q.poseB);
        queries.push_back(q);
    }
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int repeat = 0; repeat < 3; ++repeat)
                for (std::size_t i = t; i < queries.size(); i += 2) {  // overlapping halves: shared shapes
                    const Query& q = queries[i];
                    if (!sameManifold(collide(shapes[q.a], q.poseA, shapes[q.b], q.poseB), q.expected)) ++mismatches;
                }
        });
    for (std::thread& thread : threads) thread.join();
    CHECK(mismatches == 0);
}

TEST_CASE("ODE collide on disjoint geoms from several threads, while others create and destroy convex geoms",
          "[robustness][threads][ode]") {
    dInitODE2(0);
    gdc::ode::install();
    std::mt19937_64 random(4242);
    std::vector<dReal> corners;
    for (const Vec3& c : boxCorners(Vec3(0.4, 0.3, 0.5))) corners.insert(corners.end(), {c.x(), c.y(), c.z()});
    constexpr int kThreads = 4, kPairs = 40;
    std::vector<std::array<dGeomID, 2>> pairs;
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (int i = 0; i < kThreads * kPairs; ++i) {
        dGeomID a = i % 2 ? dCreateBox(0, 0.8, 0.6, 1.0) : gdc::ode::createConvex(0, corners.data(), 8);
        dGeomID b = gdc::ode::createConvex(0, corners.data(), 8);
        dGeomSetPosition(a, jitter(random), jitter(random), jitter(random));
        dGeomSetPosition(b, jitter(random), jitter(random), 0.7);
        // ODE recomputes a moved geom's pose lazily, on first read: read it here, once, so the
        // threads below only read (ODE's own lazy update is not thread-safe, even for disjoint
        // geoms' first reads — that is ODE's contract, not gdcontact's).
        dGeomGetPosition(a), dGeomGetPosition(b), dGeomGetRotation(a), dGeomGetRotation(b);
        pairs.push_back({a, b});
    }
    std::vector<std::array<dContactGeom, 8>> expected(pairs.size());
    std::vector<int> expectedCount(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i)
        expectedCount[i] = gdc::ode::collide(pairs[i][0], pairs[i][1], 8, expected[i].data(), sizeof(dContactGeom));
    std::atomic<int> mismatches{0};
    std::atomic<bool> done{false};
    // One thread churns the convex registry meanwhile (geoms it alone owns).
    std::thread churn([&] {
        while (!done) {
            dGeomID g = gdc::ode::createConvex(0, corners.data(), 8);
            dGeomDestroy(g);
        }
    });
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (int repeat = 0; repeat < 10; ++repeat)
                for (int i = t * kPairs; i < (t + 1) * kPairs; ++i) {
                    std::array<dContactGeom, 8> out;
                    const int count = gdc::ode::collide(pairs[i][0], pairs[i][1], 8, out.data(), sizeof(dContactGeom));
                    bool same = count == expectedCount[i];
                    for (int k = 0; same && k < count; ++k)
                        same = out[k].depth == expected[i][k].depth && out[k].pos[0] == expected[i][k].pos[0] &&
                               out[k].normal[2] == expected[i][k].normal[2];
                    if (!same) ++mismatches;
                }
        });
    for (std::thread& thread : threads) thread.join();
    done = true;
    churn.join();
    CHECK(mismatches == 0);
    int withContacts = 0;
    for (int count : expectedCount) withContacts += count > 0;
    CHECK(withContacts > 0);
    for (auto& pair : pairs) dGeomDestroy(pair[0]), dGeomDestroy(pair[1]);
    dCloseODE();
}
