// Tower (paper Fig. 5–6): nine convex objects (four boxes, a hexagonal and a triangular prism, three
// irregular hulls) and two gears (each one body of a hub and teeth) lie scattered on the ground.
// A scripted user picks them up one at a time (as a kinematic body, like a mouse drag), carries each
// over the tower and lets go just above its top. Once the tower stands, the user presses down on
// the top object, off-centre, with the weight of the whole tower, then lets go.
#include "scene_registry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gdc::scenes {
namespace {

class Tower final : public Scene {
public:
    explicit Tower(const SceneOptions& options) : Scene("tower", options, exactStackingSolver()) {}

    double duration() const override { return kPushEnd + kObserveAfterPush; }
    double pushForce() const override { return towerWeight_; }

    std::vector<std::string> extraColumns() const override {
        return {"placed", "stacked", "top_tilt", "lean_change", "push_force"};
    }

    void applyPush(double newtons) override {
        const Body* top = topBody();
        if (!top || !(newtons > 0.0)) return;
        dBodyAddForceAtRelPos(top->body, 0, 0, -newtons, pushPoint_.x(), pushPoint_.y(), pushPoint_.z());
        pushApplied_ = newtons;
    }

    Outcome outcome() const override {
        Outcome result;
        if (exploded()) {
            result.text = "tower exploded (a body left the world)";
            return result;
        }
        const int stackedNow = stackedLevels();
        const bool builtTower = stackedBeforePush_ == kLevels;
        const bool pushed = time() >= kPushEnd - 1e-9;
        const bool holdsAfter = pushed && stackedNow == kLevels;
        result.success = builtTower && (!scripted() || !pushed || holdsAfter);
        char text[240];
        if (!atRest())
            std::snprintf(text, sizeof text, "tower being built: %d of %d placed", placed_, kLevels);
        else if (!pushed)
            std::snprintf(text, sizeof text, "tower %s before the push (%d of %d levels stacked)",
                          builtTower ? "holds" : "does NOT hold", stackedBeforePush_, kLevels);
        else
            std::snprintf(text, sizeof text,
                          "tower %s before the push (%d/%d stacked), %s after it (%d/%d); push tilted the top "
                          "%.3g rad, the tower's lean changed %.3g rad",
                          builtTower ? "holds" : "does NOT hold", stackedBeforePush_, kLevels,
                          holdsAfter ? "holds" : "does NOT hold", stackedNow, kLevels, maxTopTiltDuringPush_,
                          maxLeanChangeDuringPush_);
        result.text = text;
        result.values = {{"stacked_before_push", static_cast<double>(stackedBeforePush_)},
                         {"stacked_now", static_cast<double>(stackedNow)},
                         {"max_top_tilt_during_push", maxTopTiltDuringPush_},
                         {"max_lean_change_during_push", maxLeanChangeDuringPush_},
                         {"final_top_tilt", topTilt()},
                         {"push_force", towerWeight_}};
        return result;
    }

private:
    static constexpr int kLevels = 11;
    static constexpr double kDensity = 500.0;        // kg/m³, wooden toy blocks
    static constexpr double kFirstPickup = 1.0;      // s: let the scattered objects settle first
    static constexpr double kLift = 0.3, kCarry = 0.4, kLower = 0.3, kWait = 0.5;  // s per object
    static constexpr double kPerObject = kLift + kCarry + kLower + kWait;
    static constexpr double kBuildEnd = kFirstPickup + kLevels * kPerObject;
    static constexpr double kRestTime = kBuildEnd + 1.0;
    static constexpr double kPushRamp = 0.5, kPushHold = 1.5;
    static constexpr double kPushEnd = kRestTime + kPushRamp + kPushHold;
    static constexpr double kObserveAfterPush = 2.5;
    static constexpr double kReleaseGap = 0.003;     // m above the tower top when let go
    static constexpr double kStackedOffset = 0.05;   // m: farther from its place, a level has fallen
    static constexpr double kStackedTilt = 0.1;      // rad (5.7°): more, and it no longer rests flat

    struct Level {
        dBodyID body = nullptr;
        Vec3 target = Vec3::Zero();  // where its centre of mass goes on the tower (xy; z when placed)
        Mat3 carryRotation = Mat3::Identity();
        Vec3 pickup = Vec3::Zero();
        double clearance = 0.0;
        double releaseHeight = 0.0;
    };

    void build() override {
        levels_.clear();
        placed_ = 0;
        stackedBeforePush_ = 0;
        maxTopTiltDuringPush_ = maxLeanChangeDuringPush_ = 0.0;
        pushApplied_ = pushInLastStep_ = 0.0;
        towerWeight_ = 0.0;
        addGroundPlane();

        Random random(20100711);
        struct Object {
            std::string name;
            std::vector<PlacedPart> parts;
            std::array<float, 3> colour;
        };
        auto box = [](const Vec3& half) { return std::vector<PlacedPart>{{makeBox(half), Pose{}, true, half}}; };
        auto hull = [](std::shared_ptr<const Polytope> shape) {
            return std::vector<PlacedPart>{{std::move(shape), Pose{}, false, Vec3::Zero()}};
        };
        // Bottom to top. Objects are built with their flat bottom down.
        std::vector<Object> objects;
        objects.push_back({"base_box", box({0.25, 0.25, 0.08}), {0.55f, 0.35f, 0.2f}});
        objects.push_back({"gear_a", makeGear(0.16, 12, 8, {0.05, 0.03, 0.05}, 0.05), {0.75f, 0.75f, 0.2f}});
        objects.push_back({"hex_prism", hull(makePrism(6, 0.18, 0.06)), {0.2f, 0.6f, 0.8f}});
        objects.push_back({"irregular_1", hull(makeIrregularSlab(random, 0.2, 0.06)), {0.6f, 0.3f, 0.7f}});
        objects.push_back({"box_2", box({0.2, 0.15, 0.06}), {0.8f, 0.45f, 0.25f}});
        objects.push_back({"gear_b", makeGear(0.13, 10, 6, {0.045, 0.03, 0.05}, 0.05), {0.85f, 0.6f, 0.1f}});
        objects.push_back({"irregular_2", hull(makeIrregularSlab(random, 0.18, 0.06)), {0.4f, 0.7f, 0.4f}});
        objects.push_back({"box_3", box({0.15, 0.13, 0.05}), {0.8f, 0.5f, 0.35f}});
        objects.push_back({"triangular_prism", hull(makePrism(3, 0.22, 0.06)), {0.3f, 0.4f, 0.85f}});
        objects.push_back({"irregular_3", hull(makeIrregularSlab(random, 0.16, 0.05)), {0.7f, 0.35f, 0.45f}});
        objects.push_back({"top_box", box({0.12, 0.12, 0.05}), {0.9f, 0.25f, 0.2f}});

        for (int k = 0; k < kLevels; ++k) {
            const Object& object = objects[k];
            double bottom = 1e300;
            for (const PlacedPart& part : object.parts)
                for (const Vec3& v : part.shape->vertices()) bottom = std::min(bottom, part.offset.apply(v).z());
            const double angle = 2.0 * kPi * k / kLevels;
            Pose pose;
            pose.rotation = Eigen::AngleAxisd(random.uniform(-0.8, 0.8), Vec3::UnitZ()).toRotationMatrix();
            pose.position = Vec3(1.3 * std::cos(angle), 1.3 * std::sin(angle), -bottom + 0.001);
            Body& body = addBody(object.name, object.parts, kDensity, pose, object.colour);
            Level level;
            level.body = body.body;
            // A person stacks by eye: a centimetre or two off the axis.
            level.target = Vec3(random.uniform(-0.015, 0.015), random.uniform(-0.015, 0.015), 0.0);
            levels_.push_back(level);
            dMass mass;
            dBodyGetMass(body.body, &mass);
            towerWeight_ += mass.mass * solver().gravity;
        }
        Body* top = findBody(levels_.back().body);
        top->pushable = true;
        // Off-centre on the top face, 3 cm from the axis: inside every level's support (the
        // narrowest, the triangular prism's inscribed circle, has an 11 cm radius), so the push
        // alone tips nothing over; whatever tilts the tower beyond the solver's compliance is
        // the contacts.
        pushPoint_ = Vec3(0.03, 0.0, 0.05);
    }

    const Body* topBody() const {
        for (const Body& body : bodies())
            if (body.pushable) return &body;
        return nullptr;
    }

    /// Lowest and highest vertex heights of a body.
    std::pair<double, double> heightRange(dBodyID id) const {
        double low = 1e300, high = -1e300;
        for (const Body& body : bodies()) {
            if (body.body != id) continue;
            for (const Part& part : body.parts) {
                for (const Vec3& v : part.shape->vertices()) {
                    const double z = worldHeight(part, v);
                    low = std::min(low, z);
                    high = std::max(high, z);
                }
            }
        }
        return {low, high};
    }

    /// Levels from the bottom that are still where they were put: upright, on their place, each
    /// above the one below.
    int stackedLevels() const {
        int count = 0;
        for (int k = 0; k < placed_; ++k) {
            const Vec3 position = bodyPosition(levels_[k].body);
            const double offset = (position.head<2>() - levels_[k].target.head<2>()).norm();
            if (offset > kStackedOffset || bodyTilt(levels_[k].body) > kStackedTilt) break;
            if (k > 0 && position.z() <= bodyPosition(levels_[k - 1].body).z()) break;
            ++count;
        }
        return count;
    }

    double topTilt() const { return levels_.empty() ? 0.0 : bodyTilt(levels_.back().body); }

    Vec3 leanVector() const {
        return bodyPosition(levels_.back().body) - bodyPosition(levels_.front().body);
    }

    static double angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

    static double smoothStep(double s) {
        s = std::clamp(s, 0.0, 1.0);
        return s * s * (3.0 - 2.0 * s);
    }

    /// Where the carried object's centre of mass should be `since` seconds after pickup.
    Vec3 carryPath(const Level& level, double since) const {
        const Vec3 lifted(level.pickup.x(), level.pickup.y(), level.clearance);
        const Vec3 over(level.target.x(), level.target.y(), level.clearance);
        const Vec3 release(level.target.x(), level.target.y(), level.releaseHeight);
        if (since < kLift) return level.pickup + smoothStep(since / kLift) * (lifted - level.pickup);
        if (since < kLift + kCarry) return lifted + smoothStep((since - kLift) / kCarry) * (over - lifted);
        return over + smoothStep((since - kLift - kCarry) / kLower) * (release - over);
    }

    void runBuilder() {
        const double t = time();
        if (placed_ >= kLevels || t < kFirstPickup - 1e-9) return;
        Level& level = levels_[placed_];
        const double pickupTime = kFirstPickup + placed_ * kPerObject;
        const double since = t - pickupTime;
        if (since < -1e-9) return;
        const double dt = solver().dt;
        if (!dBodyIsKinematic(level.body)) {
            if (since > kLift + kCarry + kLower) return;  // already let go; waiting for the next pickup
            // Pick up: remember where from, and plan a path above everything to the tower top.
            double towerTop = 0.0;
            for (int k = 0; k < placed_; ++k) towerTop = std::max(towerTop, heightRange(levels_[k].body).second);
            const auto [low, high] = heightRange(level.body);
            const Vec3 position = bodyPosition(level.body);
            level.pickup = position;
            level.releaseHeight = towerTop + kReleaseGap + (position.z() - low);
            level.clearance = std::max(level.releaseHeight, towerTop + (position.z() - low)) + (high - low) + 0.15;
            const dReal* r = dBodyGetRotation(level.body);
            // Keep its heading but hold it upright while carried.
            const double heading = std::atan2(r[4], r[0]);
            level.carryRotation = Eigen::AngleAxisd(heading, Vec3::UnitZ()).toRotationMatrix();
            dMatrix3 rotation;
            for (int row = 0; row < 3; ++row) {
                for (int column = 0; column < 3; ++column) rotation[row * 4 + column] = level.carryRotation(row, column);
                rotation[row * 4 + 3] = 0;
            }
            dBodySetRotation(level.body, rotation);
            dBodySetKinematic(level.body);
            dBodySetAngularVel(level.body, 0, 0, 0);
        }
        if (since + dt >= kLift + kCarry + kLower - 1e-9) {
            // Let go: exactly at the release point, at rest.
            const Vec3 release = carryPath(level, kLift + kCarry + kLower);
            dBodySetPosition(level.body, release.x(), release.y(), release.z());
            dBodySetLinearVel(level.body, 0, 0, 0);
            dBodySetAngularVel(level.body, 0, 0, 0);
            dBodySetDynamic(level.body);
            level.target.z() = release.z();
            ++placed_;
            return;
        }
        // Kinematic bodies move by their velocity: aim at where the path is one step ahead.
        const Vec3 velocity = (carryPath(level, since + dt) - bodyPosition(level.body)) / dt;
        dBodySetLinearVel(level.body, velocity.x(), velocity.y(), velocity.z());
    }

    void script() override {
        pushInLastStep_ = pushApplied_;  // applyPush() before a step acts in that step
        pushApplied_ = 0.0;
        const double t = time();
        if (scripted()) runBuilder();
        if (!atRest()) {
            if (t >= kRestTime - 1e-9 && (placed_ == kLevels || !scripted())) {
                markRest();
                restLean_ = leanVector();
                stackedBeforePush_ = stackedLevels();
            }
            return;
        }
        if (!scripted()) return;
        if (t < kPushEnd - 1e-9) {
            // Forces act in the next step: ramp up, hold.
            const double ramp = std::min(1.0, (t - kRestTime + solver().dt) / kPushRamp);
            applyPush(ramp * towerWeight_);
            maxTopTiltDuringPush_ = std::max(maxTopTiltDuringPush_, topTilt());
            const Vec3 lean = leanVector();
            const double change = angleBetween(lean, restLean_);
            maxLeanChangeDuringPush_ = std::max(maxLeanChangeDuringPush_, change);
        }
    }

    std::vector<double> extraValues() const override {
        double leanChange = 0.0;
        if (atRest()) {
            const Vec3 lean = leanVector();
            leanChange = angleBetween(lean, restLean_);
        }
        return {static_cast<double>(placed_), static_cast<double>(stackedLevels()), topTilt(), leanChange,
                pushInLastStep_};
    }

    std::vector<Level> levels_;
    int placed_ = 0;
    int stackedBeforePush_ = 0;
    double towerWeight_ = 0.0;
    double pushApplied_ = 0.0;
    double pushInLastStep_ = 0.0;
    double maxTopTiltDuringPush_ = 0.0;
    double maxLeanChangeDuringPush_ = 0.0;
    Vec3 restLean_ = Vec3::UnitZ();
    Vec3 pushPoint_ = Vec3::Zero();
};

}  // namespace

std::unique_ptr<Scene> makeTower(const SceneOptions& options) { return std::make_unique<Tower>(options); }

}  // namespace gdc::scenes
