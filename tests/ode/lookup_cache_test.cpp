// collide() finds hulls, box polytopes, plane normals and the installed settings through
// per-thread caches and the hull registry (src/ode/thread_cache.hpp, box_cache, installed_settings,
// convex_registry). These tests pin down that a cache never answers with
// something stale: settings installed later, more box sizes than a thread keeps, resized boxes,
// planes given new parameters and more planes than a thread keeps,
// convex geoms destroyed and re-created at the same address, and concurrent churn.
#include <gdcontact/ode.hpp>

#include "child_process.hpp"
#include "ode/ode_internals.hpp"
#include "ode_precision.hpp"
#include "ode_support.hpp"

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using namespace gdc;
using namespace gdc::ode::test;

namespace {

std::vector<dContactGeom> collideDirectly(dGeomID o1, dGeomID o2, int maxContacts = 8) {
    std::array<dContactGeom, 16> out;
    const int count = gdc::ode::collide(o1, o2, maxContacts, out.data(), sizeof(dContactGeom));
    return {out.begin(), out.begin() + count};
}

double deepest(const std::vector<dContactGeom>& contacts) {
    double depth = -1.0;
    for (const dContactGeom& contact : contacts) depth = std::max(depth, static_cast<double>(contact.depth));
    return depth;
}

// Runs jobs on one long-lived thread, one at a time, so that a test can interleave that thread's
// calls with the main thread's.
class Worker {
public:
    Worker() : thread_([this] { loop(); }) {}
    ~Worker() {
        run([this] { stop_ = true; });
        thread_.join();
    }
    void run(std::function<void()> job) {  // returns when the job has run
        std::unique_lock lock(mutex_);
        job_ = std::move(job);
        changed_.notify_all();
        changed_.wait(lock, [this] { return !job_; });
    }

private:
    void loop() {
        std::unique_lock lock(mutex_);
        while (!stop_) {
            changed_.wait(lock, [this] { return static_cast<bool>(job_); });
            job_();
            job_ = nullptr;
            changed_.notify_all();
        }
    }
    std::mutex mutex_;
    std::condition_variable changed_;
    std::function<void()> job_;
    bool stop_ = false;
    std::thread thread_;
};


// ODE allocates and frees its objects through replaceable handlers. This pair hands the block
// of one chosen geom, when ODE frees it, to the next ODE allocation of the same size: the next
// geom of that class then lands at the freed geom's address, as the allocator may do at any time.
struct AddressRecycler {
    static inline const void* watched = nullptr;
    static inline void* parked = nullptr;
    static inline dsizeint parkedSize = 0;
    static void* allocate(dsizeint size) {
        if (parked && size == parkedSize) return std::exchange(parked, nullptr);
        return std::malloc(size);
    }
    static void* reallocate(void* pointer, dsizeint, dsizeint newSize) { return std::realloc(pointer, newSize); }
    static void release(void* pointer, dsizeint size) {
        if (pointer && pointer == watched) {
            watched = nullptr;
            parked = pointer;
            parkedSize = size;
            return;
        }
        std::free(pointer);
    }
    dAllocFunction* previousAllocate = dGetAllocHandler();
    dReallocFunction* previousReallocate = dGetReallocHandler();
    dFreeFunction* previousRelease = dGetFreeHandler();
    // Installed before the geoms are made, so that gdcontact's free hook goes in front of it.
    AddressRecycler() {
        dSetAllocHandler(&allocate);
        dSetReallocHandler(&reallocate);
        dSetFreeHandler(&release);
    }
    ~AddressRecycler() {
        dSetAllocHandler(previousAllocate);
        dSetReallocHandler(previousReallocate);
        dSetFreeHandler(previousRelease);
        std::free(std::exchange(parked, nullptr));
    }
};

}  // namespace

TEST_CASE("install() takes effect for later collide calls on every thread, also one that collided before",
          "[ode][cache]") {
    OdeSession session;
    // A cube resting face down on a wider box: four contacts with the default settings.
    dGeomID lower = dCreateBox(0, 2, 2, 1);
    dGeomID upper = dCreateBox(0, 1, 1, 1);
    dGeomSetPosition(upper, 0.1, 0.2, 0.99);
    Worker worker;
    std::size_t workerCount = 0;
    auto collideOnWorker = [&] {
        worker.run([&] { workerCount = collideDirectly(upper, lower).size(); });
        return workerCount;
    };
    REQUIRE(collideOnWorker() == 4);
    REQUIRE(collideDirectly(upper, lower).size() == 4);

    Settings two;
    two.maxContacts = 2;
    gdc::ode::install(two);
    CHECK(collideOnWorker() == 2);
    CHECK(collideDirectly(upper, lower).size() == 2);

    gdc::ode::install();
    CHECK(collideOnWorker() == 4);
    CHECK(collideDirectly(lower, upper).size() == 4);
    dGeomDestroy(lower);
    dGeomDestroy(upper);
}

TEST_CASE("boxes of more sizes than a thread keeps, and resized boxes, collide with their current size",
          "[ode][cache]") {
    OdeSession session;
    // Box i rests on box j, axis-aligned, overlapping by depth(i, j) along z.
    constexpr int kSizes = 20;
    std::vector<dGeomID> boxes;
    std::vector<Vec3> half;
    for (int i = 0; i < kSizes; ++i) {
        half.emplace_back(0.3 + 0.01 * i, 0.4 + 0.02 * i, 0.2 + 0.015 * i);
        boxes.push_back(dCreateBox(0, 2 * half[i].x(), 2 * half[i].y(), 2 * half[i].z()));
    }
    auto depthOf = [](int i, int j) { return 0.001 * (1 + (i + 3 * j) % 17); };
    auto check = [&](int i, int j) {
        dGeomSetPosition(boxes[j], 0, 0, 0);
        dGeomSetPosition(boxes[i], 0, 0, half[j].z() + half[i].z() - depthOf(i, j));
        const auto contacts = collideDirectly(boxes[i], boxes[j]);
        REQUIRE(contacts.size() == 4);
        CHECK(deepest(contacts) == Approx(depthOf(i, j)).margin(realTolerance(1e-9)));
        CHECK(toVec(contacts[0].normal).z() == Approx(1.0));
    };
    // Each call looks up two sizes; cycling through 20 sizes evicts from the thread's cache all
    // the time, so a size is looked up right after its polytope was evicted.
    for (int round = 0; round < 3; ++round)
        for (int i = 0; i < kSizes; ++i) {
            check(i, (i + 1) % kSizes);
            check((i + 7) % kSizes, i);
        }
    // A box resized between two calls is collided with its new size.
    check(3, 4);
    half[3] = Vec3(0.5, 0.5, 0.45);
    dGeomBoxSetLengths(boxes[3], 1.0, 1.0, 0.9);
    check(3, 4);
    for (dGeomID box : boxes) dGeomDestroy(box);
}

TEST_CASE("planes given new parameters, and more planes than a thread keeps, collide with their current parameters",
          "[ode][cache]") {
    OdeSession session;
    // A box hanging 0.3 above the origin, axis-aligned (lengths 1, 0.8, 0.6), against planes whose
    // parameters change between calls: the deepest contact is the deepest corner's distance into
    // the plane's solid, as the current parameters say.
    dGeomID box = dCreateBox(0, 1.0, 0.8, 0.6);
    dGeomSetPosition(box, 0, 0, 0.3);
    const auto expectedDepth = [](double a, double b, double c, double d) {
        const Vec3 normal = Vec3(a, b, c).normalized();
        double deepestCorner = -1e300;
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner(i & 1 ? 0.5 : -0.5, i & 2 ? 0.4 : -0.4, i & 4 ? 0.6 : 0.0);
            deepestCorner = std::max(deepestCorner, d / Vec3(a, b, c).norm() - normal.dot(corner));
        }
        return deepestCorner;
    };
    dGeomID plane = dCreatePlane(0, 0, 0, 1, 0.01);
    const auto check = [&](double a, double b, double c, double d) {
        dGeomPlaneSetParams(plane, a, b, c, d);
        for (const bool planeFirst : {false, true}) {
            const auto contacts = planeFirst ? collideDirectly(plane, box) : collideDirectly(box, plane);
            REQUIRE_FALSE(contacts.empty());
            CHECK(deepest(contacts) == Approx(expectedDepth(a, b, c, d)).margin(realTolerance(1e-9)));
            // ODE's normal points from o2 into o1; the plane's own normal points out of its solid.
            const Vec3 normal = Vec3(a, b, c).normalized() * (planeFirst ? -1.0 : 1.0);
            CHECK((toVec(contacts[0].normal) - normal).norm() < realTolerance(1e-12));
        }
    };
    check(0, 0, 1, 0.01);
    check(0, 0, 1, 0.02);   // only d changed
    check(0, 0, 2, 0.04);   // the same plane, scaled
    check(0.1, 0, 1, 0.01);  // only a changed
    check(0, 0.1, 1, 0.01);  // only b changed
    // More planes than the thread keeps (ThreadCache::kPlaneSlots), cycled: each call finds its
    // plane evicted or kept, and the first ones again after the others.
    for (int round = 0; round < 3; ++round)
        for (int i = 0; i < 7; ++i) check(0.02 * i, -0.01 * i, 1, 0.005 * (i + 1));
    dGeomDestroy(plane);
    dGeomDestroy(box);
}

TEST_CASE("a createConvex geom re-created at a destroyed one's address collides with its own hull",
          "[ode][cache][lifetime]") {
    OdeSession session;
    AddressRecycler recycler;
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    const auto small = boxCorners(Vec3(0.3, 0.3, 0.3));
    const auto large = boxCorners(Vec3(0.5, 0.5, 0.5));
    dGeomID first = gdc::ode::createConvex(0, small.data(), 8);
    dGeomSetPosition(first, 0, 0, 0.25);
    CHECK(deepest(collideDirectly(first, ground)) == Approx(0.05));  // its hull is now cached
    // Held, so that the old hull's memory is not reused by the new one: a stale cache entry would
    // then still answer with the old hull's contacts, not by luck with the new one's.
    const std::shared_ptr<const Polytope> firstHull = gdc::ode::polytopeOf(first);
    AddressRecycler::watched = first;
    dGeomDestroy(first);
    dGeomID second = gdc::ode::createConvex(0, large.data(), 8);
    REQUIRE(second == first);  // otherwise the test proves nothing
    dGeomSetPosition(second, 0, 0, 0.25);
    CHECK(deepest(collideDirectly(second, ground)) == Approx(0.25));
    dGeomDestroy(second);
    dGeomDestroy(ground);
}

TEST_CASE("a plain dCreateConvex geom at the address of a collided createConvex geom gets ODE's contacts, not the old hull",
          "[ode][cache][lifetime]") {
    const auto corners = boxCorners(Vec3(0.3, 0.3, 0.3));
    // ODE's demo cube in dCreateConvex's layout (half size 0.25).
    const std::vector<dReal> planes{1, 0, 0, 0.25, 0, 1, 0, 0.25, 0, 0, 1, 0.25,
                                    -1, 0, 0, 0.25, 0, -1, 0, 0.25, 0, 0, -1, 0.25};
    const std::vector<dReal> points{0.25, 0.25, 0.25, -0.25, 0.25, 0.25, 0.25, -0.25, 0.25, -0.25, -0.25, 0.25,
                                    0.25, 0.25, -0.25, -0.25, 0.25, -0.25, 0.25, -0.25, -0.25, -0.25, -0.25, -0.25};
    const std::vector<unsigned> polygons{4, 0, 2, 6, 4, 4, 1, 0, 4, 5, 4, 0, 1, 3, 2,
                                         4, 3, 1, 5, 7, 4, 2, 3, 7, 6, 4, 5, 4, 6, 7};
    const auto [status, text] = runInChild([&] {
        dInitODE2(0);
        AddressRecycler recycler;
        dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
        gdc::ode::createConvex(0, corners.data(), 8);  // keeps the registry non-empty
        dGeomID ours = gdc::ode::createConvex(0, corners.data(), 8);
        dGeomSetPosition(ours, 0, 0, 0.25);
        if (collideDirectly(ours, ground).empty()) _exit(5);  // the hull must have been found (and cached)
        AddressRecycler::watched = ours;
        dGeomDestroy(ours);
        dGeomID plain = dCreateConvex(0, planes.data(), 6, points.data(), 8, polygons.data());
        if (plain != ours) _exit(6);  // the test would prove nothing
        dGeomSetPosition(plain, 0, 0, 0.24);  // 1 cm into the ground; the old hull would be 6 cm in
        const auto contacts = collideDirectly(plain, ground);  // ODE's own collider, one message
        // Where this ODE does not let its collider be reached, none (docs/ode.md).
        const bool reached =
            gdc::ode::detail::odeColliders().convexPlane.fallback == gdc::ode::detail::OdeFallback::OdeCollider;
        if (reached == contacts.empty()) _exit(3);
        for (const dContactGeom& contact : contacts)
            if (std::abs(contact.depth - 0.01) > 1e-6) _exit(4);  // the old hull's depth is 0.06
    });
    if (status == 6) {
        WARN("ODE did not reuse the address: nothing to check");
        return;
    }
    CHECK(status == 0);  // 3: no contacts (or some where ODE's are out of reach), 4: the old hull's depth, 5: set-up failed
    CHECK_THAT(text, Catch::Contains("plain dCreateConvex") && Catch::Contains("gdc::ode::createConvex"));
}

TEST_CASE("collide from several threads while install() runs and convex geoms come and go gives the sequential answers",
          "[ode][threads][cache]") {
    OdeSession session;
    const auto corners = boxCorners(Vec3(0.4, 0.3, 0.5));
    std::mt19937_64 random(99);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    constexpr int kThreads = 3, kPairsPerThread = 30;
    dGeomID ground = dCreatePlane(0, 0.1, -0.2, 1.0, -0.3);
    std::vector<std::array<dGeomID, 2>> pairs;
    for (int i = 0; i < kThreads * kPairsPerThread; ++i) {
        dGeomID a = i % 3 == 0 ? dCreateBox(0, 0.8 + 0.01 * (i % 11), 0.6, 1.0)  // more sizes than a thread keeps
                               : gdc::ode::createConvex(0, corners.data(), 8);
        dGeomID b = i % 4 == 0 ? ground : gdc::ode::createConvex(0, corners.data(), 8);
        setPose(a, Pose{randomRotation(random), Vec3(jitter(random), jitter(random), jitter(random))});
        if (b != ground) setPose(b, Pose{randomRotation(random), Vec3(jitter(random), jitter(random), 0.7)});
        // ODE recomputes a moved geom's pose lazily on first read, which is not thread-safe even
        // for disjoint geoms (ODE's contract): read each pose once here.
        dGeomGetPosition(a), dGeomGetRotation(a);
        if (b != ground) dGeomGetPosition(b), dGeomGetRotation(b);
        pairs.push_back({a, b});
    }
    std::vector<std::vector<dContactGeom>> expected;
    for (const auto& pair : pairs) expected.push_back(collideDirectly(pair[0], pair[1]));

    std::atomic<bool> done{false};
    std::atomic<int> mismatches{0};
    // Destroying geoms moves the registry's generation (every thread's cached hulls go stale);
    // install() moves the settings' generation (every thread refreshes its copy).
    std::thread churn([&] {
        while (!done) {
            dGeomID geom = gdc::ode::createConvex(0, corners.data(), 8);
            dGeomDestroy(geom);
            gdc::ode::install();
        }
    });
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (int repeat = 0; repeat < 20; ++repeat)
                for (int i = t * kPairsPerThread; i < (t + 1) * kPairsPerThread; ++i) {
                    const auto contacts = collideDirectly(pairs[i][0], pairs[i][1]);
                    bool same = contacts.size() == expected[i].size();
                    for (std::size_t k = 0; same && k < contacts.size(); ++k)
                        same = toVec(contacts[k].pos) == toVec(expected[i][k].pos) &&
                               toVec(contacts[k].normal) == toVec(expected[i][k].normal) &&
                               contacts[k].depth == expected[i][k].depth;
                    if (!same) ++mismatches;
                }
        });
    for (std::thread& thread : threads) thread.join();
    done = true;
    churn.join();
    CHECK(mismatches == 0);
    int withContacts = 0;
    for (const auto& contacts : expected) withContacts += !contacts.empty();
    CHECK(withContacts > 0);
    for (const auto& pair : pairs) {
        dGeomDestroy(pair[0]);
        if (pair[1] != ground) dGeomDestroy(pair[1]);
    }
    dGeomDestroy(ground);
}

// The hull registry (src/ode/convex_registry.cpp) at scene sizes: every hull found, through removals
// and re-creation at reused addresses, while other threads read it.
namespace {

// Geom i of a batch is a cube of half size halfOf(i) standing on the plane z = 0 with its centre
// at height kCentre: its deepest contact tells which hull collide() used.
constexpr double kCentre = 0.2;
double halfOf(int i) { return 0.25 + 1e-5 * (i % 4999); }

dGeomID standingCube(int i) {
    const auto corners = boxCorners(Vec3::Constant(halfOf(i)));
    dGeomID geom = gdc::ode::createConvex(0, corners.data(), 8);
    dGeomSetPosition(geom, 0.01 * (i % 97), 0.0, kCentre);
    dGeomGetPosition(geom);  // ODE computes a moved geom's pose lazily, which is not thread-safe
    return geom;
}

bool usesItsOwnHull(dGeomID geom, int i, dGeomID ground) {
    std::array<dContactGeom, 8> out;
    const int count = gdc::ode::collide(geom, ground, 8, out.data(), sizeof(dContactGeom));
    return count == 4 && std::abs(out[0].depth - (halfOf(i) - kCentre)) < realTolerance(1e-9);
}

}  // namespace

TEST_CASE("thousands of createConvex geoms each collide with their own hull, through removals and re-creation",
          "[ode][cache][lifetime]") {
    OdeSession session;
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    constexpr int kGeoms = 5000;
    const std::size_t before = gdc::ode::liveConvexCount();
    std::vector<dGeomID> geoms;
    for (int i = 0; i < kGeoms; ++i) geoms.push_back(standingCube(i));
    CHECK(gdc::ode::liveConvexCount() >= kGeoms);
    int wrong = 0;
    for (int i = 0; i < kGeoms; ++i) wrong += !usesItsOwnHull(geoms[i], i, ground);
    CHECK(wrong == 0);
    // Every third geom goes and comes back with another hull (tombstones, reused slots and, as
    // the allocator likes, reused addresses), then all are checked again.
    for (int i = 0; i < kGeoms; i += 3) dGeomDestroy(geoms[i]);
    for (int i = 0; i < kGeoms; i += 3) geoms[i] = standingCube(i + 1);
    wrong = 0;
    for (int i = 0; i < kGeoms; ++i) wrong += !usesItsOwnHull(geoms[i], i % 3 == 0 ? i + 1 : i, ground);
    CHECK(wrong == 0);
    for (dGeomID geom : geoms) dGeomDestroy(geom);
    // Not "== before": an entry an earlier test left stale (its geom freed while another free
    // handler was in front) is replaced, not added, when a new geom lands at its address.
    CHECK(gdc::ode::liveConvexCount() <= before);
    dGeomDestroy(ground);
}

// A thread remembers each convex geom it collided (its hull and where its AABB check ended) in a
// set-associative table of 64 sets of 4 (ThreadCache::GeomMemo): more geoms than that, collided in
// orders that evict each other (forwards, backwards, strided), must each still find their own hull,
// and a geom given other data through dGeomSetConvex must be seen whether its memo is warm (collided
// just before) or was evicted since.
TEST_CASE("hundreds of convex geoms collided in evicting orders keep their own hull, and dGeomSetConvex is seen warm or evicted",
          "[ode][cache][lifetime]") {
    OdeSession session;
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    constexpr int kGeoms = 700;  // ~11 a set
    std::vector<dGeomID> geoms;
    for (int i = 0; i < kGeoms; ++i) geoms.push_back(standingCube(i));
    int wrong = 0;
    for (int round = 0; round < 3; ++round) {
        for (int i = 0; i < kGeoms; ++i) wrong += !usesItsOwnHull(geoms[i], i, ground);
        for (int i = kGeoms - 1; i >= 0; --i) wrong += !usesItsOwnHull(geoms[i], i, ground);
        for (int i = 0; i < kGeoms; ++i) {
            const int k = (i * 257) % kGeoms;
            wrong += !usesItsOwnHull(geoms[k], k, ground);
            wrong += !usesItsOwnHull(geoms[k], k, ground);  // at once again: a warm memo
        }
    }
    CHECK(wrong == 0);

    // Other data for two geoms: a cube of half size 0.3 (0.1 into the ground, where the
    // registered hulls reach 0.05 and a little more). The arrays must outlive the geoms.
    const std::vector<dReal> planes{1, 0, 0, 0.3, 0, 1, 0, 0.3, 0, 0, 1, 0.3, -1, 0, 0, 0.3, 0, -1, 0, 0.3, 0, 0, -1, 0.3};
    const std::vector<dReal> points{0.3, 0.3, 0.3,  -0.3, 0.3, 0.3,  0.3, -0.3, 0.3,  -0.3, -0.3, 0.3,
                                    0.3, 0.3, -0.3, -0.3, 0.3, -0.3, 0.3, -0.3, -0.3, -0.3, -0.3, -0.3};
    const std::vector<unsigned> polygons{4, 0, 2, 6, 4, 4, 1, 0, 4, 5, 4, 0, 1, 3, 2,
                                         4, 3, 1, 5, 7, 4, 2, 3, 7, 6, 4, 5, 4, 6, 7};
    const int warm = 123, evicted = 456;
    auto giveOtherData = [&](dGeomID geom) {
        dGeomSetConvex(geom, planes.data(), 6, points.data(), 8, polygons.data());
        // ODE 0.16.2's dGeomSetConvex does not mark the AABB stale; the next move does.
        const dReal* p = dGeomGetPosition(geom);
        dGeomSetPosition(geom, p[0], p[1], p[2]);
        dGeomGetPosition(geom);
    };
    // The other data is seen: ODE's collider answers for it where this ODE lets it be reached,
    // else the pair gets none (docs/ode.md) — never the old hull's contacts.
    const bool odeReached =
        gdc::ode::detail::odeColliders().convexPlane.fallback == gdc::ode::detail::OdeFallback::OdeCollider;
    auto seesOtherData = [&](int k) {
        const std::vector<dContactGeom> contacts = collideDirectly(geoms[k], ground);
        if (!odeReached) return contacts.empty();
        return !contacts.empty() && std::abs(deepest(contacts) - (0.3 - kCentre)) < realTolerance(1e-9);  // ODE's collider
    };
    REQUIRE(usesItsOwnHull(geoms[warm], warm, ground));  // its memo verified at this very pose
    giveOtherData(geoms[warm]);
    CHECK(seesOtherData(warm));
    REQUIRE(usesItsOwnHull(geoms[evicted], evicted, ground));
    for (int i = 0; i < kGeoms; ++i)  // evicts `evicted`'s memo
        if (i != warm && i != evicted) usesItsOwnHull(geoms[i], i, ground);
    giveOtherData(geoms[evicted]);
    CHECK(seesOtherData(evicted));
    CHECK(seesOtherData(warm));  // and still, a call later
    wrong = 0;
    for (int i = 0; i < kGeoms; ++i)
        if (i != warm && i != evicted) wrong += !usesItsOwnHull(geoms[i], i, ground);
    CHECK(wrong == 0);
    for (dGeomID geom : geoms) dGeomDestroy(geom);
    dGeomDestroy(ground);
}

TEST_CASE("collide from several threads finds every hull while another thread creates and destroys hulls",
          "[ode][threads][cache]") {
    OdeSession session;
    dGeomID ground = dCreatePlane(0, 0, 0, 1, 0);
    // Few geoms stay; every round registers and forgets many more while the readers look theirs up.
    constexpr int kThreads = 2, kReadGeoms = 40, kChurnRounds = 4, kChurnGeoms = 600;
    std::vector<dGeomID> geoms;
    for (int i = 0; i < kReadGeoms; ++i) geoms.push_back(standingCube(i));

    std::atomic<bool> done{false};
    std::atomic<int> wrong{0}, reads{0};
    std::thread churn([&] {
        // Batches of new geoms grow the registry's map (rehashing it); destroying a batch empties it again.
        for (int round = 0; round < kChurnRounds; ++round) {
            std::vector<dGeomID> batch;
            for (int i = 0; i < kChurnGeoms; ++i) batch.push_back(standingCube(kReadGeoms + i));
            for (dGeomID geom : batch) dGeomDestroy(geom);
        }
        done = true;
    });
    std::vector<std::thread> readers;
    for (int t = 0; t < kThreads; ++t)
        readers.emplace_back([&, t] {
            // Each reader reads all geoms at least once, then for as long as the churn lasts.
            for (int pass = 0; pass == 0 || !done; ++pass)
                for (int i = t; i < kReadGeoms; i += kThreads) {
                    if (!usesItsOwnHull(geoms[i], i, ground)) ++wrong;
                    ++reads;
                }
        });
    churn.join();
    for (std::thread& reader : readers) reader.join();
    CHECK(wrong == 0);
    CHECK(reads >= kReadGeoms);
    for (dGeomID geom : geoms) dGeomDestroy(geom);
    dGeomDestroy(ground);
}
