// Scenes of bodies that must come to rest and stay there (barrels, terrain): the exact LCP stepper
// (dWorldStep, dt 0.01 s: what the bodies do is the contacts' doing), rest declared at 2 s
// (docs/measures.md: skip the first 2 s), 6 s in all, and one verdict: "rest" when every body is
// still (below 5 mm/s) and none has sunk or slid by more than a millimetre since rest.
#pragma once

#include "scene.hpp"

#include <cstdio>
#include <string>
#include <utility>

namespace gdc::scenes {

class RestingScene : public Scene {
public:
    double duration() const override { return 6.0; }

    Outcome outcome() const override {
        Outcome result;
        if (exploded()) {
            result.text = "a body left the world";
            return result;
        }
        const Measures& last = measures();
        const Summary summary = this->summary();
        const bool still = last.speed < kStillSpeed;
        const bool held = summary.maxSag < kHeld && summary.maxDrift < kHeld;
        result.success = atRest() && still && held;
        char text[240];
        std::snprintf(text, sizeof text, "%s %s: speed %.3g m/s, sag %.3g m, drift %.3g m, penetration %.3g m since rest",
                      name().c_str(), result.success ? "rest" : "do NOT rest", last.speed, summary.maxSag,
                      summary.maxDrift, summary.maxPenetration);
        result.text = text;
        result.values = {{"final_speed", last.speed},
                         {"max_sag", summary.maxSag},
                         {"max_drift", summary.maxDrift},
                         {"max_penetration", summary.maxPenetration}};
        return result;
    }

protected:
    RestingScene(std::string name, const SceneOptions& options) : Scene(std::move(name), options, exactStepper()) {}

    void script() override {
        if (!atRest() && time() >= kSettleTime - 1e-9) markRest();
    }

private:
    static constexpr double kSettleTime = 2.0;   // s
    static constexpr double kStillSpeed = 5e-3;  // m/s
    static constexpr double kHeld = 1e-3;        // m

    static SolverSettings exactStepper() {
        SolverSettings solver;
        solver.stepper = SolverSettings::Stepper::World;
        solver.dt = 0.01;
        return solver;
    }
};

}  // namespace gdc::scenes
