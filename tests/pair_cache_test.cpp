// The pair cache (gdcontact/pair_cache.hpp): exact by default — on motion sequences of every pair
// type (resting, sliding, tumbling, separating and re-touching) collide() with the pair's cache
// answers bit for bit what a fresh query answers, and skips the query exactly when nothing moved;
// with Settings::manifoldReuseDistance its carried answers stay within that distance of a fresh
// query, and only while the pair has moved less than that.
#include "geometry/growth_distance.hpp"
#include "geometry_oracles.hpp"
#include "sanitizer_scale.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstring>
#include <optional>

using namespace gdc;
using namespace gdc::testing;

namespace {

constexpr int kSteps = scaledForSanitizers(100000);

std::vector<Vec3> randomCloud(std::mt19937& random, int count, double scale) {
    std::normal_distribution<double> gaussian;
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i) points.emplace_back(scale * Vec3(gaussian(random), gaussian(random), gaussian(random)));
    return points;
}

bool sameBits(const Manifold& x, const Manifold& y) {
    if (x.pointCount != y.pointCount || x.featureA.type != y.featureA.type || x.featureA.index != y.featureA.index ||
        x.featureB.type != y.featureB.type || x.featureB.index != y.featureB.index)
        return false;
    if (x.empty()) return true;
    if (std::memcmp(x.normal.data(), y.normal.data(), sizeof(double) * 3) != 0) return false;
    for (int i = 0; i < x.pointCount; ++i)
        if (std::memcmp(x.points[i].position.data(), y.points[i].position.data(), sizeof(double) * 3) != 0 ||
            std::memcmp(&x.points[i].depth, &y.points[i].depth, sizeof(double)) != 0)
            return false;
    return true;
}

// B's pose in A's frame with B resting on A along `direction` (A's frame), overlapping by `overlap`.
Pose touching(const Polytope& a, const Polytope& b, const Mat3& rotationB, const Vec3& direction, double overlap) {
    Pose bInA{rotationB, a.centroid() - rotationB * b.centroid()};
    const detail::SeparationAlong apart = detail::separationAlong(a, b, bInA, direction, Settings{});
    if (apart.valid) bInA.position += (apart.distance - overlap) * direction;
    return bInA;
}

// One step of a motion sequence: how B moves relative to A (and A in the world, so that the world
// poses change even where the relative pose barely does).
enum class Motion { Resting, Sliding, Tumbling, SeparatingAndRetouching };
const char* nameOf(Motion motion) {
    switch (motion) {
        case Motion::Resting: return "resting";
        case Motion::Sliding: return "sliding";
        case Motion::Tumbling: return "tumbling";
        default: return "separating and re-touching";
    }
}

// One step of a motion: how `moving` (B's pose in A's frame, or A's pose for a half-space) moves.
// `up` is the direction along which the pair rests (the frame of `moving`'s parent).
void advance(Pose& moving, Motion motion, int step, const Vec3& up, double size, std::mt19937& random) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Vec3 axis = Vec3(unit(random), unit(random), unit(random)).normalized();
    switch (motion) {
        case Motion::Resting:
            // Most steps nothing moves (bodies at rest or asleep); every third a jitter of the
            // size a solver leaves on a resting body.
            if (step % 3 == 0) moving.position += 1e-7 * size * axis;
            break;
        case Motion::Sliding: moving.position += 2e-3 * size * (axis - axis.dot(up) * up).normalized(); break;
        case Motion::Tumbling: {
            const Mat3 turn = rotationAbout(axis, 0.05);
            const Vec3 pivot = moving.position;  // about the body's own origin
            moving.rotation = turn * moving.rotation;
            moving.position = pivot;
            break;
        }
        case Motion::SeparatingAndRetouching:
            // Out for 8 steps, back in for 8: the pair parts, stays apart a while and touches again.
            moving.position += (step % 16 < 8 ? 1.0 : -1.0) * 4e-3 * size * up;
            break;
    }
}

struct Tally {
    int steps = 0, repeated = 0, touching = 0;
};

// Runs `steps` steps of every motion on the pair (a, b), or (a, half-space) when b is null, and
// requires the cached answer to equal a fresh query bit for bit at each, and to come from the
// cache whenever nothing moved.
Tally requireExactOnSequences(const Polytope& a, const Polytope* b, int steps, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double size = a.radius() + (b ? b->radius() : 0.0);
    Tally tally;
    const Motion motions[] = {Motion::Resting, Motion::Sliding, Motion::Tumbling, Motion::SeparatingAndRetouching};
    const int sequenceLength = 48;
    for (int begun = 0; begun < steps; begun += sequenceLength) {
        const Motion motion = motions[(begun / sequenceLength) % 4];
        Pose poseA{randomRotation(random), Vec3(unit(random), unit(random), unit(random))};
        const Vec3 direction = Vec3(0.2 * unit(random), 0.2 * unit(random), 1.0).normalized();
        Pose bInA;
        if (b) bInA = touching(a, *b, randomRotation(random), direction, 0.01 * size);
        const HalfSpace ground{Vec3(0.1 * unit(random), 0.1 * unit(random), 1.0), unit(random)};
        const Vec3 groundUp = ground.normal.normalized();
        if (!b) {  // A resting on the half-space, its lowest vertex 0.01·size deep
            const Vec3 upInA = poseA.rotation.transpose() * groundUp;
            const double lowest = groundUp.dot(poseA.apply(a.vertices()[a.supportVertex(-upInA)]));
            poseA.position += (ground.offset / ground.normal.norm() - lowest - 0.01 * size) * groundUp;
        }
        Settings settings;
        settings.maxContacts = 4 + begun % 5;
        PairCache cache;
        for (int step = 0; step < sequenceLength; ++step) {
            const Pose poseB{poseA.rotation * bInA.rotation, poseA.apply(bInA.position)};
            const Manifold cached = b ? collide(a, poseA, *b, poseB, settings, cache) : collide(a, poseA, ground, settings, cache);
            const Manifold fresh = b ? collide(a, poseA, *b, poseB, settings) : collide(a, poseA, ground, settings);
            INFO(nameOf(motion) << " sequence at step " << begun << " + " << step);
            REQUIRE(sameBits(cached, fresh));
            REQUIRE(cache.lastAnswer() != CacheAnswer::Carried);  // never without manifoldReuseDistance
            tally.repeated += cache.lastAnswer() == CacheAnswer::Repeated;
            tally.touching += !fresh.empty();
            ++tally.steps;
            const Pose before = b ? bInA : poseA;
            advance(b ? bInA : poseA, motion, step, b ? direction : groundUp, size, random);
            if (std::memcmp(&before, b ? &bInA : &poseA, sizeof(Pose)) == 0) {
                // Nothing moved: the cache must answer (the same world poses, recomputed).
                const Pose sameB{poseA.rotation * bInA.rotation, poseA.apply(bInA.position)};
                b ? collide(a, poseA, *b, sameB, settings, cache) : collide(a, poseA, ground, settings, cache);
                REQUIRE(cache.lastAnswer() == CacheAnswer::Repeated);
            }
        }
    }
    return tally;
}

}  // namespace

TEST_CASE("pair cache: exact on motion sequences of every pair type (10^5 steps each)") {
    std::mt19937 random(5);
    const Polytope box = Polytope::box(Vec3(0.5, 0.3, 0.2));
    const Polytope cube = Polytope::box(Vec3(0.25, 0.25, 0.25));
    const Polytope rock = Polytope::fromPoints(randomCloud(random, 24, 0.3));
    const Polytope pebble = Polytope::fromPoints(randomCloud(random, 12, 0.15));
    const Polytope boulder = Polytope::fromPoints(randomCloud(random, 200, 0.4));
    struct PairType {
        const char* name;
        const Polytope* a;
        const Polytope* b;
    } types[] = {{"box-box", &box, &cube},         {"box-hull", &box, &rock},       {"hull-hull", &rock, &pebble},
                 {"large hull-hull", &boulder, &rock}, {"box-half-space", &box, nullptr}, {"hull-half-space", &rock, nullptr}};
    std::uint32_t seed = 1;
    for (const PairType& type : types) {
        const Tally tally = requireExactOnSequences(*type.a, type.b, kSteps, seed++);
        std::printf("pair cache, %s: %d steps, %d touching, %d answered from the cache, all equal to a fresh query bit for bit\n",
                    type.name, tally.steps, tally.touching, tally.repeated);
        CHECK(tally.touching > tally.steps / 3);  // the sequences exercise contact
        CHECK(tally.repeated > tally.steps / 8);  // and the cache answers some
    }
}

TEST_CASE("pair cache: a cache passed with other shapes, settings or half-space queries afresh") {
    const Polytope box = Polytope::box(Vec3(0.5, 0.5, 0.5));
    const Pose poseA = makePose(Vec3(0, 0, 0));
    const Pose poseB = makePose(Vec3(0.1, 0.05, 0.99));
    PairCache cache;
    std::optional<Polytope> other = Polytope::box(Vec3(0.5, 0.5, 0.5));
    collide(box, poseA, *other, poseB, Settings{}, cache);
    REQUIRE(cache.lastAnswer() == CacheAnswer::Computed);
    collide(box, poseA, *other, poseB, Settings{}, cache);
    REQUIRE(cache.lastAnswer() == CacheAnswer::Repeated);

    SECTION("another shape built where the cached one was") {
        other.reset();
        other.emplace(Polytope::box(Vec3(0.5, 0.5, 0.6)));  // taller: it overlaps more
        const Manifold m = collide(box, poseA, *other, poseB, Settings{}, cache);
        CHECK(cache.lastAnswer() == CacheAnswer::Computed);
        CHECK(m.maxDepth() == Approx(collide(box, poseA, *other, poseB).maxDepth()));
    }
    SECTION("every settings field") {
        auto changed = [](int field) {
            Settings s;
            switch (field) {
                case 0: s.rayCastTolerance *= 2; break;
                case 1: s.maxRayCastIterations += 1; break;
                case 2: s.angularTolerance *= 2; break;
                case 3: s.margin = 0.01; break;
                case 4: s.spanContactRegion = !s.spanContactRegion; break;
                case 5: s.maxContacts -= 1; break;
                case 6: s.bruteForceSupportLimit += 1; break;
                case 7: s.coplanarTolerance *= 2; break;
                case 8: s.normalMethod = NormalMethod::SeparatingAxis; break;
                case 9: s.manifoldReuseDistance = 1e-3; break;
                case 10: s.contactOrder = s.contactOrder == ContactOrder::DeepestLast ? ContactOrder::DeepestFirst : ContactOrder::DeepestLast; break;
                case 11: s.reductionHysteresis *= 2; break;
                case 12: s.maxBodyPairContacts = 0; break;
                case 13: s.loadedDepthFraction *= 2; break;
                case 14: s.rimPointsPerTurn += 1; break;
                default: s.bodyPairNormalTolerance *= 2; break;
            }
            return s;
        };
        for (int field = 0; field <= 15; ++field) {
            INFO("field " << field);
            CHECK(changed(field) != Settings{});
            collide(box, poseA, *other, poseB, changed(field), cache);
            CHECK(cache.lastAnswer() == CacheAnswer::Computed);
            collide(box, poseA, *other, poseB, Settings{}, cache);
            CHECK(cache.lastAnswer() == CacheAnswer::Computed);
        }
    }
    SECTION("a half-space after a polytope, and another half-space") {
        collide(box, poseA, HalfSpace{Vec3::UnitZ(), -0.49}, Settings{}, cache);
        CHECK(cache.lastAnswer() == CacheAnswer::Computed);
        collide(box, poseA, HalfSpace{Vec3::UnitZ(), -0.49}, Settings{}, cache);
        CHECK(cache.lastAnswer() == CacheAnswer::Repeated);
        const Manifold m = collide(box, poseA, HalfSpace{Vec3::UnitZ(), -0.48}, Settings{}, cache);
        CHECK(cache.lastAnswer() == CacheAnswer::Computed);
        CHECK(m.maxDepth() == Approx(0.02));
    }
    SECTION("a query that throws leaves the cache empty") {
        Pose broken = poseB;
        broken.position.x() = NAN;
        CHECK_THROWS_AS(collide(box, poseA, *other, broken, Settings{}, cache), InvalidInput);
        CHECK(cache.empty());
        collide(box, poseA, *other, poseB, Settings{}, cache);
        CHECK(cache.lastAnswer() == CacheAnswer::Computed);
    }
}

TEST_CASE("pair cache: carried manifolds stay within manifoldReuseDistance of a fresh query") {
    std::mt19937 random(17);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Polytope box = Polytope::box(Vec3(0.5, 0.3, 0.2));
    const Polytope rock = Polytope::fromPoints(randomCloud(random, 24, 0.3));
    for (const Polytope* b : {&box, &rock}) {
        Settings settings;
        settings.manifoldReuseDistance = 1e-3;
        int carried = 0, computed = 0;
        double largestDepthError = 0;
        for (int sequence = 0; sequence < 200; ++sequence) {
            const Pose poseA{randomRotation(random), Vec3(unit(random), unit(random), unit(random))};
            const Vec3 direction = Vec3(0.1 * unit(random), 0.1 * unit(random), 1.0).normalized();
            Pose bInA = touching(box, *b, rotationAbout(direction, M_PI * unit(random)), direction, 0.01);
            PairCache cache;
            Vec3 positionAtQuery = bInA.position;
            for (int step = 0; step < 40; ++step) {
                const Pose poseB{poseA.rotation * bInA.rotation, poseA.apply(bInA.position)};
                const Manifold answer = collide(box, poseA, *b, poseB, settings, cache);
                const Manifold fresh = collide(box, poseA, *b, poseB);
                if (cache.lastAnswer() == CacheAnswer::Computed) positionAtQuery = bInA.position, ++computed;
                if (cache.lastAnswer() == CacheAnswer::Carried) {
                    ++carried;
                    // Carried only while the pair moved less than the distance since the last query
                    // (B only slides, so its motion relative to A is the shift of its origin).
                    REQUIRE((bInA.position - positionAtQuery).norm() <= settings.manifoldReuseDistance + 1e-12);
                    REQUIRE(!fresh.empty());
                    // The deepest depths are within twice the distance of each other: the cached
                    // query was exact, and neither depth changes faster than the motion.
                    const double error = std::abs(answer.maxDepth() - fresh.maxDepth());
                    largestDepthError = std::max(largestDepthError, error);
                    REQUIRE(error <= 2 * settings.manifoldReuseDistance + 1e-9);
                    REQUIRE(answer.normal.dot(fresh.normal) > std::cos(0.05));
                    for (int i = 0; i < answer.pointCount; ++i) REQUIRE(answer.points[i].depth >= -settings.margin);
                }
                // A small slide: a quarter of the distance, so a few steps in a row are carried.
                bInA.position += 2.5e-4 * Vec3(unit(random), unit(random), 0.0).normalized();
            }
        }
        std::printf("pair cache, carried manifolds (%s): %d carried, %d queried, largest depth error %.3g (distance 1e-3)\n",
                    b == &box ? "box-box" : "box-hull", carried, computed, largestDepthError);
        CHECK(carried > computed);  // most resting steps are carried
    }
}
