// Brick wall (paper Fig. 7–8): a 10-brick-long, 6-course wall in running bond (half bricks at the
// ends of every other course) stands on the ground; a scripted user removes ten bricks one by one,
// cutting a stepped notch from the top. The order only ever takes a brick that nothing rests on,
// so every remaining brick keeps its full support: with correct contacts the wall must stand.
#include "scene_registry.hpp"

#include <algorithm>
#include <cstdio>

namespace gdc::scenes {
namespace {

class BrickWall final : public Scene {
public:
    explicit BrickWall(const SceneOptions& options) : Scene("brick_wall", options, solverDefaults()) {}

    std::vector<std::string> extraColumns() const override { return {"removed", "max_displacement"}; }

    Outcome outcome() const override {
        Outcome result;
        if (exploded()) {
            result.text = "wall exploded (a brick left the world)";
            return result;
        }
        // The displacement each removal caused: the maximum over the remaining bricks, read just
        // before the next removal (or at the end of the run for the last one).
        std::vector<double> perRemoval = displacementAfterRemoval_;
        if (static_cast<int>(perRemoval.size()) < removed_) perRemoval.push_back(currentMaxDisplacement());
        double worst = currentMaxDisplacement();
        for (std::size_t k = 0; k < perRemoval.size(); ++k) {
            result.values.push_back({"after_removal_" + std::to_string(k + 1), perRemoval[k]});
            worst = std::max(worst, perRemoval[k]);
        }
        result.values.push_back({"max_displacement", worst});
        result.values.push_back({"removed", static_cast<double>(removed_)});
        result.success = atRest() && worst < kStandsBelow;
        char text[200];
        std::snprintf(text, sizeof text, "wall %s: %d bricks removed, max displacement of the rest %.3g m",
                      result.success ? "stands" : "does NOT stand", removed_, worst);
        result.text = text;
        return result;
    }

    /// Settling, ten removals, then two seconds to see the last one's effect.
    double duration() const override { return kSettleTime + kRemovalInterval * (kRemovals - 1) + 2.0; }

    static constexpr int kRemovals = 10;

private:
    static constexpr int kCourses = 6;
    static constexpr int kBricksPerCourse = 10;
    static constexpr double kPitch = 0.30;            // m, brick length + joint
    static constexpr double kJoint = 0.002;           // m, gap between neighbours in a course
    static constexpr double kHalfDepth = 0.075;       // m
    static constexpr double kHalfHeight = 0.05;       // m
    static constexpr double kDensity = 2000.0;        // kg/m³, clay brick
    static constexpr double kSettleTime = 2.0;        // s
    static constexpr double kRemovalInterval = 1.0;   // s
    static constexpr double kStandsBelow = 0.01;      // m: a brick moved more than 10 % of its height

    static SolverSettings solverDefaults() {
        // ~60 bricks with ~8 contacts each are beyond the exact LCP at interactive rates, so the
        // wall runs QuickStep; compare against the dBox reference (--method ode, boxes as dBox).
        SolverSettings solver;
        solver.stepper = SolverSettings::Stepper::Quick;
        solver.iterations = 50;
        solver.dt = 0.01;
        return solver;
    }

    void build() override {
        removed_ = 0;
        displacementAfterRemoval_.clear();
        addGroundPlane();
        const double halfLength = 0.5 * kPitch - 0.5 * kJoint;
        const double wallHalfLength = 0.5 * kPitch * kBricksPerCourse;
        for (int course = 0; course < kCourses; ++course) {
            const double z = kHalfHeight + 2.0 * kHalfHeight * course;
            const std::array<float, 3> colour = course % 2 ? std::array<float, 3>{0.72f, 0.33f, 0.25f}
                                                           : std::array<float, 3>{0.78f, 0.40f, 0.30f};
            auto add = [&](const std::string& name, double x, double half) {
                Pose pose;
                pose.position = Vec3(x, 0.0, z);
                Body& body = addBox(name, Vec3(half, kHalfDepth, kHalfHeight), kDensity, pose, colour);
                body.removable = true;
            };
            if (course % 2 == 0) {
                for (int i = 0; i < kBricksPerCourse; ++i)
                    add(brickName(course, i), -wallHalfLength + kPitch * (i + 0.5), halfLength);
            } else {  // running bond: offset by half a brick, half bricks close the ends
                const double halfBrick = 0.25 * kPitch - 0.5 * kJoint;
                add("course" + std::to_string(course) + "_left_half", -wallHalfLength + 0.25 * kPitch, halfBrick);
                for (int i = 0; i < kBricksPerCourse - 1; ++i)
                    add(brickName(course, i), -wallHalfLength + kPitch * (i + 1.0), halfLength);
                add("course" + std::to_string(course) + "_right_half", wallHalfLength - 0.25 * kPitch, halfBrick);
            }
        }
    }

    static std::string brickName(int course, int index) {
        return "course" + std::to_string(course) + "_brick" + std::to_string(index);
    }

    /// Top course first: four neighbours of course 5, then the three of course 4 that only they
    /// covered, then two of course 3, then one of course 2 — a stepped notch.
    static std::string removalName(int k) {
        static const std::pair<int, int> order[kRemovals] = {{5, 3}, {5, 4}, {5, 5}, {5, 6}, {4, 4},
                                                             {4, 5}, {4, 6}, {3, 4}, {3, 5}, {2, 5}};
        return brickName(order[k].first, order[k].second);
    }

    double currentMaxDisplacement() const {
        if (!atRest()) return 0.0;
        double worst = 0.0;
        for (const Body& body : bodies())
            if (body.measured)  // a body a person threw in is no brick of the wall
                worst = std::max(worst, (bodyPosition(body.body) - body.restPose.position).norm());
        return worst;
    }

    void script() override {
        if (!atRest()) {
            if (time() >= kSettleTime - 1e-9) markRest();
            return;
        }
        if (!scripted() || removed_ >= kRemovals) return;
        const double nextRemoval = kSettleTime + kRemovalInterval * removed_;
        if (time() < nextRemoval - 1e-9) return;
        if (removed_ > 0) displacementAfterRemoval_.push_back(currentMaxDisplacement());
        const std::string name = removalName(removed_);
        for (const Body& body : bodies()) {
            if (body.name == name) {
                removeBody(body.body);
                break;
            }
        }
        ++removed_;
    }

    std::vector<double> extraValues() const override {
        return {static_cast<double>(removed_), currentMaxDisplacement()};
    }

    int removed_ = 0;
    std::vector<double> displacementAfterRemoval_;
};

}  // namespace

std::unique_ptr<Scene> makeBrickWall(const SceneOptions& options) { return std::make_unique<BrickWall>(options); }

}  // namespace gdc::scenes
