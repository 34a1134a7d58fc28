// Composites (paper Fig. 10): bodies made of several convex parts — a table (top and four legs),
// two gears (hub and teeth), a cross, an L and a dumbbell — are held in the air and let go one
// after another. Five land on one spot, each on the one before, and come to rest as a stack (the
// order puts each on a support wider than its own footprint, so the stack is statically stable);
// the dumbbell lands beside it on its two octagonal wheels.
#include "scene_registry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gdc::scenes {
namespace {

class Composites final : public Scene {
public:
    explicit Composites(const SceneOptions& options) : Scene("composites", options, solverDefaults()) {}

    // Multi-part bodies lying flat on each other give many nearly dependent contact rows (most
    // with gdcontact, which returns the whole support polygon of every pair of parts); at ODE's
    // default CFM (1e-10) its Dantzig LCP then fails ("LCP internal error") and kicks the resting
    // stack — hard enough to throw a body out of the world in a clang build. CFM 1e-5, the
    // regularisation ODE's manual recommends and the setting of the project's world tests, keeps
    // the problem well posed for every method. (With the per-body-pair contact budget,
    // Settings::maxBodyPairContacts, gdcontact's rows are no longer redundant and the scene runs
    // without an ODE message at 1e-10 too: tests/scenes/scene_test.cpp.)
    static SolverSettings solverDefaults() {
        SolverSettings solver = exactStackingSolver();
        solver.cfm = 1e-5;
        return solver;
    }

    double duration() const override { return kRestTime + 3.0; }

    std::vector<std::string> extraColumns() const override { return {"released", "stacked", "stack_height"}; }

    Outcome outcome() const override {
        Outcome result;
        if (exploded()) {
            result.text = "composites exploded (a body left the world)";
            return result;
        }
        const int stacked = stackedCount();
        const double speed = measures().speed;
        const auto stacking = std::count_if(drops_.begin(), drops_.end(), [](const Drop& d) { return d.stacks; });
        result.success = atRest() && stacked == stacking && speed < kStillSpeed;
        char text[200];
        std::snprintf(text, sizeof text, "composites %s: %d of %ld stacked in place, all bodies' speed below %.3g m/s, penetration %.3g m",
                      result.success ? "rest" : "do NOT rest", stacked, static_cast<long>(stacking), speed,
                      measures().penetration);
        result.text = text;
        result.values = {{"stacked", static_cast<double>(stacked)}, {"final_speed", speed},
                         {"stack_height", stackHeight()}};
        return result;
    }

private:
    static constexpr double kDensity = 700.0;       // kg/m³
    static constexpr double kDropInterval = 0.8;    // s between releases
    static constexpr double kDropGap = 0.2;         // m of free fall onto the stack
    static constexpr int kBodies = 6;
    static constexpr double kRestTime = kDropInterval * kBodies + 2.0;
    static constexpr double kStillSpeed = 0.01;     // m/s
    static constexpr double kStackedOffset = 0.1;   // m from the drop spot
    static constexpr double kStackedTilt = 0.15;    // rad

    struct Drop {
        dBodyID body = nullptr;
        double releaseTime = 0.0;
        bool released = false;
        Vec3 spot = Vec3::Zero();
        int below = -1;
        bool stacks = true;  ///< false: it only has to come to rest somewhere (the dumbbell may roll)
    };

    void build() override {
        drops_.clear();
        addGroundPlane();
        auto part = [](const Vec3& half, const Vec3& at) {
            Pose offset;
            offset.position = at;
            return PlacedPart{makeBox(half), offset, true, half};
        };
        std::vector<std::pair<std::string, std::vector<PlacedPart>>> bodies;
        bodies.push_back({"table",
                          {part({0.25, 0.18, 0.03}, {0, 0, 0.13}), part({0.03, 0.03, 0.1}, {0.2, 0.13, 0}),
                           part({0.03, 0.03, 0.1}, {-0.2, 0.13, 0}), part({0.03, 0.03, 0.1}, {0.2, -0.13, 0}),
                           part({0.03, 0.03, 0.1}, {-0.2, -0.13, 0})}});
        bodies.push_back({"gear_a", makeGear(0.15, 12, 8, {0.05, 0.03, 0.04}, 0.04)});
        bodies.push_back({"cross", {part({0.2, 0.04, 0.04}, {0, 0, 0}), part({0.04, 0.2, 0.04}, {0, 0, 0})}});
        bodies.push_back({"gear_b", makeGear(0.11, 10, 6, {0.04, 0.025, 0.04}, 0.04)});
        bodies.push_back({"l_shape", {part({0.2, 0.05, 0.04}, {0, -0.1, 0}), part({0.05, 0.15, 0.04}, {-0.15, 0.0, 0})}});
        {
            // Octagonal wheels on a bar, axes along x, each wheel resting on a face.
            const auto wheel = makePrism(8, 0.08, 0.03);
            Pose left, right;
            left.rotation = right.rotation = (Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()) *
                                              Eigen::AngleAxisd(kPi / 8, Vec3::UnitZ())).toRotationMatrix();
            left.position = Vec3(-0.16, 0, 0);
            right.position = Vec3(0.16, 0, 0);
            bodies.push_back({"dumbbell", {{wheel, left, false, Vec3::Zero()}, {wheel, right, false, Vec3::Zero()},
                                           part({0.16, 0.025, 0.025}, {0, 0, 0})}});
        }
        // Where each lands (its centre of mass over this spot) and what it lands on (−1: the ground).
        const std::array<Vec3, kBodies> spots = {{{-0.3, 0, 0}, {-0.3, 0, 0}, {-0.3, 0, 0}, {-0.3, 0, 0},
                                                  {-0.3, 0, 0}, {0.5, 0, 0}}};
        const std::array<int, kBodies> below = {-1, 0, 1, 2, 3, -1};
        const std::array<std::array<float, 3>, kBodies> colours = {{{0.6f, 0.4f, 0.25f}, {0.8f, 0.75f, 0.2f},
                                                                   {0.3f, 0.6f, 0.8f}, {0.7f, 0.3f, 0.5f},
                                                                   {0.9f, 0.55f, 0.15f}, {0.4f, 0.75f, 0.4f}}};
        Random random(19);
        std::array<double, kBodies> topOf{};  // expected height of each body's top once landed
        for (int k = 0; k < kBodies; ++k) {
            double bottom = 1e300, top = -1e300, volume = 0.0;
            Vec3 centreOfMass = Vec3::Zero();
            for (const PlacedPart& p : bodies[k].second) {
                for (const Vec3& v : p.shape->vertices()) {
                    bottom = std::min(bottom, p.offset.apply(v).z());
                    top = std::max(top, p.offset.apply(v).z());
                }
                const MassProperties properties = massProperties(*p.shape);
                volume += properties.volume;
                centreOfMass += properties.volume * p.offset.apply(properties.centroid);
            }
            centreOfMass /= volume;
            const double support = below[k] < 0 ? 0.0 : topOf[below[k]];
            topOf[k] = support + (top - bottom);
            Pose pose;
            // Let go slightly tilted and turned, a centimetre or two off the spot, like a hand would.
            pose.rotation = (Eigen::AngleAxisd(random.uniform(0, 2 * kPi), Vec3::UnitZ()) *
                             Eigen::AngleAxisd(0.05, Vec3(random.uniform(-1, 1), random.uniform(-1, 1), 0).normalized()))
                                .toRotationMatrix();
            const Vec3 spot = spots[k] + Vec3(random.uniform(-0.02, 0.02), random.uniform(-0.02, 0.02), 0.0);
            // Centre of mass over the spot, bottom kDropGap above where it will land.
            pose.position = spot - pose.rotation * centreOfMass;
            pose.position.z() = support + kDropGap - bottom + 0.02;  // + room for the tilt
            Body& body = addBody(bodies[k].first, bodies[k].second, kDensity, pose, colours[k]);
            // Held until its release time: kinematic, and out of the collision pass (the held
            // bodies hang each above its own landing place, so they may overlap one another).
            dBodySetKinematic(body.body);
            for (const Part& held : body.parts) dGeomDisable(held.geom);
            drops_.push_back({body.body, kDropInterval * k, false, spots[k], below[k], below[k] >= 0 || k == 0});
        }
    }

    /// Bodies that landed where they should: upright, near their spot, above what they landed on.
    int stackedCount() const {
        int count = 0;
        for (const Drop& drop : drops_) {
            if (!drop.released || !drop.stacks) continue;
            const Vec3 position = bodyPosition(drop.body);
            if ((position - drop.spot).head<2>().norm() > kStackedOffset || bodyTilt(drop.body) > kStackedTilt) continue;
            if (drop.below >= 0 && position.z() <= bodyPosition(drops_[drop.below].body).z()) continue;
            ++count;
        }
        return count;
    }

    double stackHeight() const {
        double height = 0.0;
        for (const Body& body : bodies()) {
            if (!body.measured) continue;  // a body a person dropped in is not part of the stack
            for (const Part& part : body.parts)
                for (const Vec3& v : part.shape->vertices()) height = std::max(height, worldHeight(part, v));
        }
        return height;
    }

    void script() override {
        // Releases are part of the scene, not of a user: they happen with or without scripting.
        for (Drop& drop : drops_) {
            if (!drop.released && time() >= drop.releaseTime - 1e-9) {
                dBodySetDynamic(drop.body);
                for (const Body& body : bodies())
                    if (body.body == drop.body)
                        for (const Part& part : body.parts) dGeomEnable(part.geom);
                drop.released = true;
            }
        }
        if (!atRest() && time() >= kRestTime - 1e-9) markRest();
    }

    std::vector<double> extraValues() const override {
        const auto released = std::count_if(drops_.begin(), drops_.end(), [](const Drop& d) { return d.released; });
        return {static_cast<double>(released), static_cast<double>(stackedCount()), stackHeight()};
    }

    std::vector<Drop> drops_;
};

}  // namespace

std::unique_ptr<Scene> makeComposites(const SceneOptions& options) {
    return std::make_unique<Composites>(options);
}

}  // namespace gdc::scenes
