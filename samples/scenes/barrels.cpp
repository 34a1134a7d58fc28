// Barrels (issue 33): ODE's curved geoms at rest. Standing barrels (dCylinder) on the ground and on
// a crate (dBox), a lying barrel and a wheel on their sides, and lying capsules (dCapsule) on the
// ground and on the crate. Every body starts a centimetre above what it lands on; the measures
// after 2 s show whether each contact method holds them where they came to rest — a lying capsule or
// cylinder on one contact point sinks or rocks, a standing barrel on an octagon of contacts creeps.
//
// The geometric penetration measure and the tracking baseline see each round part as its
// tessellation (scenes::makeCylinderPart / makeCapsulePart), whose vertices lie on the surface:
// they judge the real shape up to the tessellation's sagitta (under 1 % of the radius).
#include "resting_scene.hpp"
#include "scene_registry.hpp"

#include <array>
#include <cstdio>

namespace gdc::scenes {
namespace {

constexpr double kGap = 0.01;  // m: each body starts this far above what it lands on

/// The frame rotation that lays a part's z axis along the world's `axis` (x or y).
Mat3 lying(const Vec3& axis) {
    return Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis).toRotationMatrix();
}

Pose placed(const Vec3& position, const Mat3& rotation = Mat3::Identity()) {
    Pose pose;
    pose.position = position;
    pose.rotation = rotation;
    return pose;
}

class Barrels final : public RestingScene {
public:
    explicit Barrels(const SceneOptions& options) : RestingScene("barrels", options) {}

private:
    void build() override {
        addGroundPlane();
        const Vec3 crateHalf(0.5, 0.35, 0.2);
        addBox("crate", crateHalf, 600.0, placed(Vec3(0, 0, crateHalf.z() + kGap)), {0.6f, 0.45f, 0.3f});
        const double crateTop = 2.0 * crateHalf.z() + kGap;
        addStandingBarrels(crateTop);
        addLyingCylinders();
        addCapsulePile();
    }

    void addStandingBarrels(double crateTop) {
        const std::array<float, 3> colour{0.75f, 0.35f, 0.2f};
        const double radius = 0.15, height = 0.4;
        const double z = 0.5 * height + kGap;
        for (const Vec3& at : {Vec3(-1.0, 0.45, z), Vec3(-1.0, -0.05, z), Vec3(0.2, 0.05, crateTop + z)})
            addBody("barrel", {makeCylinderPart(radius, height)}, 700.0, placed(at), colour);
    }

    void addLyingCylinders() {
        // A barrel on its side, its axis along y, and a narrow wheel on its tread, axis along x.
        addBody("lying barrel", {makeCylinderPart(0.15, 0.4)}, 700.0, placed(Vec3(1.0, 0.6, 0.15 + kGap), lying(Vec3::UnitY())),
                {0.8f, 0.55f, 0.2f});
        addBody("wheel", {makeCylinderPart(0.22, 0.1)}, 900.0, placed(Vec3(1.1, -0.6, 0.22 + kGap), lying(Vec3::UnitX())),
                {0.25f, 0.25f, 0.28f});
    }

    void addCapsulePile() {
        // Capsules lying on the ground in a row, turned a little from each other, and one lying on
        // the crate's top beside the barrel there. (A capsule across two others is a wedge that
        // rolls them apart at μ = 0.6: not a scene at rest.)
        const std::array<float, 3> colour{0.35f, 0.6f, 0.85f};
        const double radius = 0.07, length = 0.45;
        const double low = radius + kGap;
        for (int i = 0; i < 3; ++i) {
            const Mat3 heading = Eigen::AngleAxisd(0.15 * (i - 1), Vec3::UnitZ()).toRotationMatrix();
            addBody("capsule", {makeCapsulePart(radius, length)}, 1000.0,
                    placed(Vec3(-0.1, -0.65 - 0.25 * i, low), heading * lying(Vec3::UnitX())), colour);
        }
        addBody("capsule", {makeCapsulePart(radius, length)}, 1000.0, placed(Vec3(-0.15, -0.2, 0.4 + kGap + low),
                                                                               lying(Vec3::UnitX())),
                colour);
    }
};

}  // namespace

std::unique_ptr<Scene> makeBarrels(const SceneOptions& options) { return std::make_unique<Barrels>(options); }

}  // namespace gdc::scenes
