// gdc::reduceBodyPairContacts (the per-body-pair contact budget) against exact answers: the
// budget per cluster, clusters by normal, the deepest kept, near-duplicates merged, the widest
// support, the carried body's centre of mass over the kept points, the mirrored call.
#include <gdcontact/body_pair.hpp>
#include <gdcontact/collide.hpp>
#include <gdcontact/polytope.hpp>

#include "geometry_oracles.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

using namespace gdc;
using gdc::testing::makePose;
using gdc::testing::rotationAbout;

namespace {

// A grid of nx × ny contacts on the plane z = height, normal +z (from B below into A above),
// spacing `step`, depths from `depth`.
std::vector<BodyPairContact> grid(int nx, int ny, double step, double height, double depth = 1e-4) {
    std::vector<BodyPairContact> contacts;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) contacts.push_back({Vec3(i * step, j * step, height), Vec3::UnitZ(), depth});
    return contacts;
}

Settings budget(int count) {
    Settings s;
    s.maxBodyPairContacts = count;
    return s;
}

std::vector<int> reduce(const std::vector<BodyPairContact>& contacts, const Settings& settings,
                        const BodyPairFrame& frame = {}) {
    std::vector<int> kept;
    const int n = reduceBodyPairContacts(contacts.data(), static_cast<int>(contacts.size()), frame, settings, kept);
    REQUIRE(n == static_cast<int>(kept.size()));
    REQUIRE(std::is_sorted(kept.begin(), kept.end()));
    REQUIRE(std::adjacent_find(kept.begin(), kept.end()) == kept.end());
    return kept;
}

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Area of the convex hull of the chosen contacts' (x, y) (gift wrapping over a few points).
double hullArea(const std::vector<BodyPairContact>& contacts, const std::vector<int>& chosen) {
    std::vector<Vec2> p;
    for (int i : chosen) p.push_back(contacts[i].position.head<2>());
    return gdc::testing::convexHullArea(p);
}

bool insideHull(const std::vector<BodyPairContact>& contacts, const std::vector<int>& chosen, const Vec2& q) {
    // Inside the convex hull: q is a convex combination, tested as "on the inner side of every
    // hull edge", with the hull by brute force over pairs (a pair is an edge when all points lie
    // on one side).
    std::vector<Vec2> p;
    for (int i : chosen) p.push_back(contacts[i].position.head<2>());
    if (p.size() < 3) return false;
    for (std::size_t a = 0; a < p.size(); ++a)
        for (std::size_t b = 0; b < p.size(); ++b) {
            if (a == b) continue;
            bool edge = true;
            for (std::size_t c = 0; c < p.size() && edge; ++c) edge = cross2(p[b] - p[a], p[c] - p[a]) >= 0;
            if (edge && cross2(p[b] - p[a], q - p[a]) <= 0) return false;
        }
    return true;
}

}  // namespace

TEST_CASE("body pair: the budget holds per cluster, and the kept points span the support's corners") {
    const auto contacts = grid(6, 6, 0.1, 0.0);  // a 0.5 × 0.5 support, 36 coplanar contacts
    for (int count : {1, 2, 3, 4, 6, 16}) {
        INFO("budget " << count);
        const auto kept = reduce(contacts, budget(count));
        CHECK(static_cast<int>(kept.size()) == std::min(count, 36));
    }
    // Four points of a square grid that span the most area: its four corners (area 0.25 exactly).
    const auto four = reduce(contacts, budget(4));
    CHECK(hullArea(contacts, four) == Approx(0.25).epsilon(1e-12));
}

TEST_CASE("body pair: off (0) keeps every contact") {
    const auto contacts = grid(5, 5, 0.1, 0.0);
    CHECK(reduce(contacts, budget(0)).size() == 25);
}

TEST_CASE("body pair: the deepest point is kept") {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> depth(0.0, 1e-3);
    for (int trial = 0; trial < 200; ++trial) {
        auto contacts = grid(5, 4, 0.07, 0.3);
        for (BodyPairContact& c : contacts) c.depth = depth(random);
        const int deepest = static_cast<int>(
            std::max_element(contacts.begin(), contacts.end(), [](auto& a, auto& b) { return a.depth < b.depth; }) -
            contacts.begin());
        for (int count : {1, 3, 4}) {
            const auto kept = reduce(contacts, budget(count));
            CHECK(std::find(kept.begin(), kept.end(), deepest) != kept.end());
        }
    }
}

TEST_CASE("body pair: clusters by normal, opposite and tilted supports keep their own budget") {
    // A body clamped between two faces of another: a bottom support (normal +z) and a top one
    // (normal −z) of the same shape; and a side wall (normal +x). Each is a 4 × 4 grid.
    auto bottom = grid(4, 4, 0.1, 0.0);
    auto top = grid(4, 4, 0.1, 0.2);
    for (BodyPairContact& c : top) c.normal = -Vec3::UnitZ();
    std::vector<BodyPairContact> side;
    for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 4; ++k) side.push_back({Vec3(-0.05, j * 0.1, 0.02 + k * 0.05), Vec3::UnitX(), 1e-4});
    std::vector<BodyPairContact> contacts;
    for (auto* part : {&bottom, &top, &side}) contacts.insert(contacts.end(), part->begin(), part->end());
    const auto kept = reduce(contacts, budget(4));
    int inBottom = 0, inTop = 0, inSide = 0;
    for (int i : kept) (i < 16 ? inBottom : i < 32 ? inTop : inSide) += 1;
    CHECK(inBottom == 4);
    CHECK(inTop == 4);
    CHECK(inSide == 4);

    // Normals 2° apart are one cluster at the default tolerance (5°), two at 1°.
    auto tilted = grid(4, 4, 0.1, 0.0);
    const Vec3 n = Vec3(std::sin(0.035), 0, std::cos(0.035));
    for (BodyPairContact& c : tilted) c.normal = n, c.position.x() += 1.0;
    std::vector<BodyPairContact> both = bottom;
    both.insert(both.end(), tilted.begin(), tilted.end());
    CHECK(reduce(both, budget(4)).size() == 4);
    Settings narrow = budget(4);
    narrow.bodyPairNormalTolerance = 0.0175;
    CHECK(reduce(both, narrow).size() == 8);
}

TEST_CASE("body pair: two parallel supports at different heights are one cluster, reduced over both") {
    // Two parts of A resting on two parts of B, both faces +z but 5 cm apart in height and 1 m
    // apart sideways: the kept points span both (a body on one of them alone would tip).
    auto left = grid(3, 3, 0.1, 0.0);
    auto right = grid(3, 3, 0.1, 0.05);
    for (BodyPairContact& c : right) c.position.x() += 1.0;
    std::vector<BodyPairContact> contacts = left;
    contacts.insert(contacts.end(), right.begin(), right.end());
    const auto kept = reduce(contacts, budget(4));
    REQUIRE(kept.size() == 4);
    const int onLeft = static_cast<int>(std::count_if(kept.begin(), kept.end(), [](int i) { return i < 9; }));
    CHECK(onLeft == 2);
    CHECK(hullArea(contacts, kept) == Approx(1.2 * 0.2).epsilon(1e-12));  // the corners of both
}

TEST_CASE("body pair: near-duplicates are merged, the deeper kept") {
    // The same point reported by two pairs of parts (overlapping parts of one body), to rounding,
    // and a point 1e-5 of the support's size away: each pair is one row to the solver.
    std::vector<BodyPairContact> contacts = {{Vec3(0, 0, 0), Vec3::UnitZ(), 1e-4},
                                             {Vec3(1, 0, 0), Vec3::UnitZ(), 1e-4},
                                             {Vec3(1 + 6e-17, 0, 0), Vec3::UnitZ(), 2e-4},
                                             {Vec3(0, 1, 0), Vec3::UnitZ(), 1e-4},
                                             {Vec3(1e-5, 1, 0), Vec3::UnitZ(), 1e-4}};
    const auto kept = reduce(contacts, budget(8));  // the budget is not what drops them
    // 2 is deeper than its twin 1; 3 and 4 are equally deep: the tie goes to the fixed identity
    // (the larger position along detail::identityDirection, whose x component is positive), 4.
    CHECK(kept == std::vector<int>{0, 2, 4});
    // Depths within rounding (1e-9 of the size) are equal too: the identity decides.
    contacts[4].depth = 1e-4 - 1e-12;
    CHECK(reduce(contacts, budget(8)) == std::vector<int>{0, 2, 4});
    contacts[4].depth = 1e-4 - 1e-8;  // deeper by more than rounding: the deeper
    CHECK(reduce(contacts, budget(8)) == std::vector<int>{0, 2, 3});
    // Same positions seen along the normal, different depths (one above the other): one row.
    std::vector<BodyPairContact> stacked = {{Vec3(0, 0, 0), Vec3::UnitZ(), 1e-4},
                                            {Vec3(0, 0, 0.01), Vec3::UnitZ(), 3e-4},
                                            {Vec3(1, 0, 0), Vec3::UnitZ(), 1e-4}};
    CHECK(reduce(stacked, budget(8)) == std::vector<int>{1, 2});
    // Points 1 % of the support apart are distinct.
    std::vector<BodyPairContact> apart = {{Vec3(0, 0, 0), Vec3::UnitZ(), 1e-4},
                                          {Vec3(0.01, 0, 0), Vec3::UnitZ(), 1e-4},
                                          {Vec3(1, 0, 0), Vec3::UnitZ(), 1e-4}};
    CHECK(reduce(apart, budget(8)).size() == 3);
    // A cluster of nothing but one point reported twice (a side contact where two parts of one body
    // meet on an edge of the other): its extent is the rounding itself, and it is still one row.
    // Found as an "LCP internal error" in the composites scene built with clang (two rows with the
    // same point, normal and depth).
    const Vec3 side(-0.898885, -0.438185, 0);
    std::vector<BodyPairContact> twice = {{Vec3(-0.217654, -0.116606, 0.5), side.normalized(), 4.8e-10},
                                          {Vec3(-0.217654, -0.116606 + 2e-17, 0.5), side.normalized(), 4.8e-10},
                                          {Vec3(-0.2, 0.1, 0.5), Vec3::UnitZ(), 1e-9}};
    const auto once = reduce(twice, budget(4));  // which twin stays: the fixed identity's tie rule
    CHECK(once.size() == 2);
    CHECK(once.back() == 2);
}

TEST_CASE("body pair: the carried body's centre of mass stays over the kept points") {
    // A 10 × 10 grid (0.9 m square) whose deepest point is the corner (0.9, 0). Budget 3: the
    // deepest, the farthest (0, 0.9) and by area (0, 0) — half the square. A centre of mass over
    // the other half lies inside the support but outside those three: the rule must keep a
    // triangle with the deepest that holds it.
    auto contacts = grid(10, 10, 0.1, 0.0);
    contacts[90].depth = 5e-4;  // (0.9, 0)
    std::mt19937 random(3);
    std::uniform_real_distribution<double> coordinate(0.01, 0.89);
    int missedWithoutRule = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Vec2 centre(coordinate(random), coordinate(random));  // inside the support
        BodyPairFrame frame;
        frame.centreA = Vec3(centre.x(), centre.y(), 0.3);  // A above: the normal +z lifts A
        frame.hasCentreA = true;
        frame.gravity = Vec3(0, 0, -9.81);
        const auto kept = reduce(contacts, budget(3), frame);
        INFO("centre " << centre.transpose());
        CHECK(kept.size() == 3);
        CHECK(std::find(kept.begin(), kept.end(), 90) != kept.end());
        CHECK(insideHull(contacts, kept, centre));
        // B's centre is not carried (the normal pushes B down): the plain reduction.
        BodyPairFrame below;
        below.centreB = frame.centreA;
        below.hasCentreB = true;
        below.gravity = frame.gravity;
        const auto plain = reduce(contacts, budget(3));
        CHECK(reduce(contacts, budget(3), below) == plain);
        if (!insideHull(contacts, plain, centre)) ++missedWithoutRule;
    }
    CHECK(missedWithoutRule > 100);  // about half: the rule is what keeps them
}

TEST_CASE("body pair: the swapped pair gives the same contacts, mirrored") {
    std::mt19937 random(9);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), depth(0.0, 1e-3);
    for (int trial = 0; trial < 200; ++trial) {
        // Three clusters with random normals, random points on each plane, random depths.
        std::vector<BodyPairContact> contacts;
        for (int cluster = 0; cluster < 3; ++cluster) {
            const Vec3 n = Vec3(unit(random), unit(random), unit(random)).normalized();
            const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
            const Vec3 origin(unit(random), unit(random), unit(random));
            for (int i = 0; i < 12; ++i)
                contacts.push_back({origin + unit(random) * u + unit(random) * v, n, depth(random)});
        }
        BodyPairFrame frame;
        frame.centreA = Vec3(unit(random), unit(random), unit(random));
        frame.centreB = Vec3(unit(random), unit(random), unit(random));
        frame.hasCentreA = frame.hasCentreB = true;
        frame.gravity = Vec3(0, 0, -9.81);
        std::vector<BodyPairContact> mirrored = contacts;
        for (BodyPairContact& c : mirrored) c.normal = -c.normal;
        BodyPairFrame swapped = frame;
        std::swap(swapped.centreA, swapped.centreB);
        for (int count : {3, 4, 6}) {
            const auto kept = reduce(contacts, budget(count), frame);
            CHECK(kept == reduce(mirrored, budget(count), swapped));
            CHECK(static_cast<int>(kept.size()) <= 3 * count);
        }
    }
}

TEST_CASE("body pair: bad contacts are refused where they enter") {
    std::vector<int> kept;
    std::vector<BodyPairContact> contacts = grid(2, 2, 0.1, 0.0);
    CHECK_THROWS_AS(reduceBodyPairContacts(contacts.data(), -1, {}, Settings{}, kept), InvalidInput);
    CHECK_THROWS_AS(reduceBodyPairContacts(nullptr, 2, {}, Settings{}, kept), InvalidInput);
    contacts[1].normal = Vec3::Zero();
    CHECK_THROWS_WITH(reduceBodyPairContacts(contacts.data(), 4, {}, Settings{}, kept),
                      Catch::Contains("contact 1") && Catch::Contains("unit"));
    contacts[1].normal = Vec3::UnitZ();
    contacts[2].depth = NAN;
    CHECK_THROWS_WITH(reduceBodyPairContacts(contacts.data(), 4, {}, Settings{}, kept),
                      Catch::Contains("contact 2") && Catch::Contains("non-finite"));
    CHECK(reduceBodyPairContacts(contacts.data(), 0, {}, Settings{}, kept) == 0);
}

TEST_CASE("body pair: settings out of bounds are refused by validate") {
    Settings s;
    s.maxBodyPairContacts = -1;
    CHECK_THROWS_WITH(validate(s), Catch::Contains("maxBodyPairContacts"));
    s.maxBodyPairContacts = 17;
    CHECK_THROWS_WITH(validate(s), Catch::Contains("maxBodyPairContacts"));
    s = Settings{};
    s.bodyPairNormalTolerance = 0.51;
    CHECK_THROWS_WITH(validate(s), Catch::Contains("bodyPairNormalTolerance"));
    s.bodyPairNormalTolerance = NAN;
    CHECK_THROWS_WITH(validate(s), Catch::Contains("bodyPairNormalTolerance"));
    CHECK_NOTHROW(validate(Settings{}));
}

namespace {

// A composite of boxes whose bottom faces (`bottom`) or top faces lie in the plane z = 0,
// in its body frame: 3–5 boxes of random size at random places, some overlapping (their shared
// corners are reported by several pairs of parts: near-duplicates).
struct Part {
    Polytope box;
    Vec3 offset;
};
template <class Random>
std::vector<Part> randomComposite(Random& random, bool bottom) {
    std::uniform_real_distribution<double> half(0.04, 0.15), place(-0.2, 0.2), height(0.03, 0.08);
    std::vector<Part> parts;
    const int count = 3 + static_cast<int>(random() % 3);
    for (int k = 0; k < count; ++k) {
        const Vec3 extents(half(random), half(random), height(random));
        // A third of the parts sit edge to edge with the previous one: coincident corners.
        Vec3 offset(place(random), place(random), 0);
        if (k > 0 && random() % 3 == 0) offset.x() = parts.back().offset.x() + parts.back().box.vertices()[0].cwiseAbs().x() + extents.x();
        offset.z() = bottom ? extents.z() : -extents.z();
        parts.push_back({Polytope::box(extents), offset});
    }
    return parts;
}

// Every contact between the parts of A (above) and those of B (below), normal from B into A.
std::vector<BodyPairContact> compositeContacts(const std::vector<Part>& a, const Pose& poseA, const std::vector<Part>& b,
                                               const Pose& poseB) {
    std::vector<BodyPairContact> contacts;
    for (const Part& pa : a)
        for (const Part& pb : b) {
            const Pose partA{poseA.rotation, poseA.apply(pa.offset)}, partB{poseB.rotation, poseB.apply(pb.offset)};
            const Manifold m = collide(pa.box, partA, pb.box, partB);
            for (int i = 0; i < m.pointCount; ++i)
                contacts.push_back({m.points[i].position, Vec3(-m.normal), m.points[i].depth});
        }
    return contacts;
}

// Whether the kept points of two calls are the same points: each kept position of one within
// `tolerance` of a kept position of the other, and as many.
bool samePoints(const std::vector<BodyPairContact>& a, const std::vector<int>& keptA,
                const std::vector<BodyPairContact>& b, const std::vector<int>& keptB, double tolerance) {
    if (keptA.size() != keptB.size()) return false;
    auto covered = [&](const std::vector<BodyPairContact>& p, const std::vector<int>& kp, const std::vector<BodyPairContact>& q,
                       const std::vector<int>& kq) {
        for (int i : kp) {
            bool found = false;
            for (int j : kq) found = found || (p[i].position - q[j].position).norm() <= tolerance;
            if (!found) return false;
        }
        return true;
    };
    return covered(a, keptA, b, keptB) && covered(b, keptB, a, keptA);
}

}  // namespace

TEST_CASE("body pair: a 1e-9 perturbation keeps the same points (hysteresis), and the mirrored call the same") {
    // 600 random composites resting on random composites (coplanar faces: equal depths, symmetric
    // supports — the ties a reduction without hysteresis breaks by rounding), half of them exactly
    // flat, half tilted by up to 1e-3 rad. Each perturbed 10 times by 1e-9 relative (positions by
    // 1e-9 of the size, the rotation by 1e-9 rad): the kept points must be the same points.
    // (Without the band — the reduction before it had one — 5165 of the 12 000 perturbed calls
    // kept other points.)
    std::mt19937 random(22);
    std::uniform_real_distribution<double> unit(-1, 1);
    int configurations = 0, reduced = 0, checked = 0;
    for (int trial = 0; trial < 600; ++trial) {
        const auto upper = randomComposite(random, true);
        const auto lower = randomComposite(random, false);
        const Pose poseB = makePose(Vec3::Zero());
        const double tilt = trial % 2 ? 1e-3 * unit(random) : 0.0;
        const Mat3 turn = rotationAbout(Vec3(unit(random), unit(random), 0).normalized() + Vec3(0, 0, 1e-9), tilt) *
                          rotationAbout(Vec3::UnitZ(), 3.14159 * unit(random));
        const Pose poseA = makePose(Vec3(0.1 * unit(random), 0.1 * unit(random), -1e-3), turn);
        const auto contacts = compositeContacts(upper, poseA, lower, poseB);
        if (contacts.size() < 5) continue;
        ++configurations;
        BodyPairFrame frame;
        frame.centreA = poseA.position + Vec3(0, 0, 0.05);
        frame.centreB = poseB.position - Vec3(0, 0, 0.05);
        frame.hasCentreA = frame.hasCentreB = true;
        frame.gravity = Vec3(0, 0, -9.81);
        for (int count : {3, 4}) {
            const auto kept = reduce(contacts, budget(count), frame);
            reduced += kept.size() < contacts.size();
            // The mirrored call: every normal negated, A and B exchanged — the same indices.
            std::vector<BodyPairContact> mirrored = contacts;
            for (BodyPairContact& c : mirrored) c.normal = -c.normal;
            BodyPairFrame swapped = frame;
            std::swap(swapped.centreA, swapped.centreB);
            CHECK(reduce(mirrored, budget(count), swapped) == kept);
            for (int k = 0; k < 10; ++k) {
                Pose moved = poseA;
                moved.position += 1e-9 * Vec3(unit(random), unit(random), unit(random));
                moved.rotation = rotationAbout(Vec3(unit(random), unit(random), unit(random)), 1e-9) * moved.rotation;
                const auto perturbed = compositeContacts(upper, moved, lower, poseB);
                BodyPairFrame movedFrame = frame;
                movedFrame.centreA = moved.position + Vec3(0, 0, 0.05);
                const auto keptPerturbed = reduce(perturbed, budget(count), movedFrame);
                INFO("trial " << trial << " budget " << count << " perturbation " << k);
                CHECK(samePoints(contacts, kept, perturbed, keptPerturbed, 1e-7));
                ++checked;
            }
        }
    }
    CHECK(configurations >= 500);
    CHECK(reduced >= configurations);  // the budget dropped points in most of them
    CHECK(checked >= 10000);
}

TEST_CASE("body pair: touching points (depth 0) go where their cluster overlaps, and stay where nothing does") {
    // A 3 × 3 grid resting with its corners overlapping and the other points exactly touching
    // (depth 0: the adapter's report of a rounding-level overlap or gap). A touching row has a
    // right-hand side of exactly 0 and, between bodies moving together, a zero relative velocity:
    // ODE's Dantzig LCP stalls on it ("LCP internal error, s <= 0"). Within the budget and
    // without it, the touching points are not kept.
    auto contacts = grid(3, 3, 0.1, 0.0, 0.0);
    for (int corner : {0, 2, 6, 8}) contacts[corner].depth = 1e-9;
    for (int count : {4, 6, 16}) CHECK(reduce(contacts, budget(count)) == std::vector<int>{0, 2, 6, 8});
    // Three overlap, the rest touch: the three are kept (a budget of 4 is not filled with a touching one).
    contacts[8].depth = 0.0;
    CHECK(reduce(contacts, budget(4)) == std::vector<int>{0, 2, 6});
    // A second cluster (a side wall) that only touches keeps its points: it has nothing else.
    auto wall = contacts;
    wall.push_back({Vec3(0.3, 0, 0.1), Vec3::UnitX(), 0.0});
    wall.push_back({Vec3(0.3, 0.2, 0.1), Vec3::UnitX(), 0.0});
    CHECK(reduce(wall, budget(4)) == std::vector<int>{0, 2, 6, 9, 10});
    // Budget 0 (off) keeps everything, touching or not.
    CHECK(reduce(contacts, budget(0)).size() == 9);
}
