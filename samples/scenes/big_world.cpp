// Big world (issue 15): thousands of bodies in one ODE world, collided by gdc::ode::spaceCollide
// (ODE's broad phase, gdcontact's narrow phase on a pool of threads). Two structures side by side:
//   - a pile: boxes and convex hulls of six kinds (~0.3 m) dropped in layers onto the ground;
//   - a brick wall in running bond (dBox bricks, dConvex with --convex) that a heavy hull, held
//     still in front of it, is fired into once the wall has stood for a second.
// `--bodies N` (SceneOptions::bodies, default 2000) sets the total: 30 % bricks, the rest the pile
// and the projectile. The verdict: nothing left the world or turned NaN, no body fell through the
// ground (its centre below it) nor sank a vertex more than 10 cm into it once at rest, the wall
// stood (no brick moved 2 cm from its rest pose) until the projectile first touched it, and the hit
// knocked bricks out. In the viewer "push" fires.
//
// QuickStep with 20 iterations at 60 Hz, as bench/big_world.cpp measures it: the exact LCP of
// dWorldStep is out of reach at this size.
#include "scene_registry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_set>

namespace gdc::scenes {
namespace {

class BigWorld final : public Scene {
public:
    explicit BigWorld(const SceneOptions& options) : Scene("big_world", options, solverDefaults()) {
        setWholeStepCollision(true);
    }

    static constexpr int kDefaultBodies = 2000;

    double duration() const override { return kLaunchTime + 2.0; }
    double pushForce() const override { return 1.0; }  // any positive value: applyPush fires

    /// The viewer's push (and the script at kLaunchTime): fires the projectile, once.
    void applyPush(double newtons) override {
        if (launched_ || !(newtons > 0.0) || !projectile_) return;
        dBodySetDynamic(projectile_);
        // Upward by half of what gravity takes away on the way: it meets the wall at the height it
        // starts from, the wall's mid-height.
        const double flight = kLaunchDistance / kLaunchSpeed;
        dBodySetLinearVel(projectile_, 0.0, kLaunchSpeed, 0.5 * solver().gravity * flight);
        dBodySetAngularVel(projectile_, 0.0, 0.0, 0.0);
        launched_ = true;
        launchTime_ = time();
    }

    std::vector<std::string> extraColumns() const override {
        return {"wall_drift", "knocked_bricks", "ground_penetration", "hit"};
    }

    Outcome outcome() const override {
        Outcome result;
        const double deepest = deepestSinceRest_;
        const int knocked = knockedBricks();
        result.values = {{"bodies", static_cast<double>(bodies().size())},
                         {"wall_bricks", static_cast<double>(wallBricks_)},
                         {"wall_drift_before_hit", wallDriftBeforeHit_},
                         {"hit_time", hit_ ? hitTime_ : NAN},
                         {"knocked_bricks", static_cast<double>(knocked)},
                         {"max_ground_penetration_after_rest", deepest},
                         {"fell_through", fellThrough_ ? 1.0 : 0.0}};
        if (exploded()) {
            result.text = "big world exploded (a body left the world or turned NaN)";
            return result;
        }
        const bool aboveGround = !fellThrough_ && deepest <= kGroundTolerance;
        const bool stood = atRest() && wallDriftBeforeHit_ < kStandsBelow;
        // Unscripted (the viewer), the projectile waits for the push: judge what has happened.
        const bool hitJudged = scripted() && time() >= duration() - 1e-9;
        const bool knockedDown = hit_ && knocked >= kKnockedAtLeast;
        result.success = aboveGround && stood && (!hitJudged || knockedDown);
        char text[320];
        std::snprintf(text, sizeof text,
                      "%zu bodies (%d bricks); wall %s until hit (max drift %.3g m)%s; %d bricks knocked out; "
                      "deepest vertex after rest %.3g m below ground%s",
                      bodies().size(), wallBricks_, stood ? "stands" : "does NOT stand", wallDriftBeforeHit_,
                      hit_ ? "" : (launched_ ? ", projectile has not reached it" : ", projectile not fired"),
                      knocked, deepest, aboveGround ? "" : fellThrough_ ? " (A BODY FELL THROUGH)" : " (TOO DEEP)");
        result.text = text;
        return result;
    }

private:
    static constexpr double kRestTime = 1.5;       // s: the pile has landed; rest poses taken here
    static constexpr double kLaunchTime = 2.5;     // s: the wall has stood for a second
    static constexpr double kLaunchSpeed = 12.0;   // m/s towards the wall (+y)
    static constexpr double kLaunchDistance = 3.5; // m from the wall's centre line
    static constexpr double kProjectileRadius = 0.3;  // m
    static constexpr double kBrickDensity = 2000.0;  // kg/m³, clay
    static constexpr double kPileDensity = 600.0;    // kg/m³, wood
    static constexpr double kProjectileDensity = 3000.0;  // kg/m³, stone: ~200 kg, it goes through bricks
    static constexpr double kWallY = 5.0;          // m: the wall's centre line
    static constexpr double kPileSpacing = 0.42;   // m: larger than any pile body's diameter
    // QuickStep's 20 iterations let a resting wall creep by about a centimetre a second (as with
    // ODE's own dBoxBox, bench/scenes.cpp); a brick that moved 10 % of its height has not stood.
    static constexpr double kStandsBelow = 0.02;   // m
    static constexpr double kKnockedBy = 0.2;      // m: a brick this far from rest was knocked out
    static constexpr int kKnockedAtLeast = 2;
    // QuickStep's penalty-like correction (ERP 0.2 a step) lets the bottom of a heavy pile, or the
    // projectile landing, sink a few centimetres for a moment; a collider failing shows as more.
    static constexpr double kGroundTolerance = 0.1;  // m
    inline static const Vec3 kBrick{0.2, 0.15, 0.1};  // half extents: 0.40 × 0.30 × 0.20 m

    static SolverSettings solverDefaults() {
        SolverSettings solver;
        solver.stepper = SolverSettings::Stepper::Quick;
        solver.iterations = 20;
        solver.dt = 1.0 / 60.0;
        solver.maxContactsPerPair = 4;  // spans a face contact; keeps QuickStep's rows down
        return solver;
    }

    int requestedBodies() const { return options().bodies > 0 ? options().bodies : kDefaultBodies; }

    void build() override {
        launched_ = hit_ = false;
        launchTime_ = hitTime_ = 0.0;
        wallDriftBeforeHit_ = 0.0;
        deepestSinceRest_ = 0.0;
        fellThrough_ = false;
        wallGeoms_.clear();
        wallIndices_.clear();
        projectile_ = nullptr;
        projectileGeom_ = nullptr;
        addGroundPlane();

        const int total = std::max(3, requestedBodies());
        wallBricks_ = std::max(2, static_cast<int>(std::lround(0.3 * total)));
        const int pileBodies = std::max(1, total - wallBricks_ - 1);
        buildWall();
        buildPile(pileBodies);
        buildProjectile();
    }

    void buildWall() {
        // Courses about a tenth of the length in bricks, at most 8 (a taller wall creeps more than
        // kStandsBelow a second under QuickStep, with ODE's dBoxBox too): 600 bricks, 8 courses of 75.
        const int courses = std::clamp(static_cast<int>(std::lround(std::sqrt(wallBricks_ / 10.0))), 1, 8);
        const int perCourse = (wallBricks_ + courses - 1) / courses;
        const double joint = 0.002, gap = 1e-4;  // m: neighbours apart, courses just above each other
        const double pitch = 2 * kBrick.x() + joint;
        int made = 0;
        for (int course = 0; course < courses && made < wallBricks_; ++course) {
            // Odd courses shifted by a quarter brick: every brick rests on two below, none on an edge.
            const double shift = (course % 2) ? 0.5 * kBrick.x() : 0.0;
            const std::array<float, 3> colour = course % 2 ? std::array<float, 3>{0.72f, 0.33f, 0.25f}
                                                           : std::array<float, 3>{0.78f, 0.40f, 0.30f};
            for (int i = 0; i < perCourse && made < wallBricks_; ++i, ++made) {
                Pose pose;
                pose.position = Vec3((i - 0.5 * (perCourse - 1)) * pitch + shift, kWallY,
                                     kBrick.z() + course * (2 * kBrick.z() + gap));
                Body& brick = addBox("brick" + std::to_string(made), kBrick, kBrickDensity, pose, colour);
                wallGeoms_.insert(brick.parts.front().geom);
                wallIndices_.push_back(bodies().size() - 1);
            }
        }
        wallBricks_ = made;
        wallHeight_ = std::min(courses, (made + perCourse - 1) / perCourse) * (2 * kBrick.z() + gap);
    }

    /// Six kinds of pile body, about 0.3 m across: two boxes (dBox unless --convex) and four hulls.
    static std::vector<PlacedPart> pileKinds() {
        std::vector<PlacedPart> kinds;
        for (const Vec3& half : {Vec3(0.15, 0.1, 0.075), Vec3(0.12, 0.12, 0.06)})
            kinds.push_back(PlacedPart{makeBox(half), Pose{}, true, half});
        auto hull = [&](std::shared_ptr<const Polytope> shape) { kinds.push_back(PlacedPart{std::move(shape), Pose{}}); };
        hull(makePrism(6, 0.13, 0.08));
        hull(makePrism(3, 0.16, 0.07));
        hull(std::make_shared<const Polytope>(Polytope::fromPoints(
            {{0.15, 0, 0}, {-0.15, 0, 0}, {0, 0.12, 0}, {0, -0.12, 0}, {0, 0, 0.1}, {0, 0, -0.1}})));
        Random random(15);
        std::vector<Vec3> rock;  // 24 points on a lumpy sphere
        for (int i = 0; i < 24; ++i) {
            const double z = random.uniform(-1.0, 1.0), phi = random.uniform(0.0, 2 * kPi);
            const double r = std::sqrt(1.0 - z * z), radius = random.uniform(0.11, 0.15);
            rock.push_back(radius * Vec3(r * std::cos(phi), r * std::sin(phi), z));
        }
        hull(std::make_shared<const Polytope>(Polytope::fromPoints(rock)));
        return kinds;
    }

    void buildPile(int count) {
        const std::vector<PlacedPart> kinds = pileKinds();
        // About four layers: a pile, not a carpet, whose top layer does not fall far; its near edge
        // a metre short of the launch point.
        const int side = std::max(1, static_cast<int>(std::ceil(std::sqrt(count / 4.0))));
        const double centreY = -1.0 - 0.5 * side * kPileSpacing;
        Random random(2026);
        for (int made = 0, layer = 0; made < count; ++layer)
            for (int i = 0; i < side && made < count; ++i)
                for (int j = 0; j < side && made < count; ++j, ++made) {
                    const Vec3 axis = Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
                    const double angle = random.uniform(0.0, kPi);
                    Pose pose;
                    if (axis.norm() > 1e-6) pose.rotation = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
                    pose.position = Vec3((i - 0.5 * (side - 1)) * kPileSpacing, centreY + (j - 0.5 * (side - 1)) * kPileSpacing,
                                         0.25 + layer * kPileSpacing);
                    const int kind = made % static_cast<int>(kinds.size());
                    const float shade = 0.45f + 0.08f * static_cast<float>(kind);
                    Body& body = addBody("pile" + std::to_string(made), {kinds[kind]}, kPileDensity, pose,
                                         {0.35f, shade, 0.8f - 0.5f * shade});
                    body.measured = false;  // the measures judge the wall
                }
    }

    void buildProjectile() {
        // An icosahedron, held still (kinematic) in front of the wall at its mid-height.
        const double t = (1.0 + std::sqrt(5.0)) / 2.0, scale = kProjectileRadius / std::sqrt(1.0 + t * t);
        std::vector<Vec3> points;
        for (double a : {-1.0, 1.0})
            for (double b : {-t, t}) {
                points.push_back(scale * Vec3(0, a, b));
                points.push_back(scale * Vec3(a, b, 0));
                points.push_back(scale * Vec3(b, 0, a));
            }
        Pose pose;
        pose.position = Vec3(0.0, kWallY - kLaunchDistance, std::max(kProjectileRadius + 0.05, 0.5 * wallHeight_));
        Body& body = addBody("projectile", {PlacedPart{std::make_shared<const Polytope>(Polytope::fromPoints(points)), Pose{}}},
                             kProjectileDensity, pose, {0.25f, 0.25f, 0.3f});
        body.pushable = true;
        body.measured = false;
        projectile_ = body.body;
        projectileGeom_ = body.parts.front().geom;
        dBodySetKinematic(projectile_);
    }

    void script() override {
        if (!atRest()) {
            if (time() >= kRestTime - 1e-9) markRest();
            return;
        }
        // While the pile lands QuickStep lets bodies sink into the ground for a moment (and recover):
        // the ground is judged from rest on.
        for (const Body& body : bodies()) fellThrough_ = fellThrough_ || bodyPosition(body.body).z() < 0.0;
        deepestSinceRest_ = std::max(deepestSinceRest_, measures().penetration);
        if (!hit_) {
            for (const ContactSample& contact : lastContacts()) {
                const dGeomID other = contact.g1 == projectileGeom_ ? contact.g2
                                      : contact.g2 == projectileGeom_ ? contact.g1 : nullptr;
                if (other && wallGeoms_.count(other)) {
                    hit_ = true;
                    hitTime_ = time();
                    break;
                }
            }
            // Until the hit the wall must stand: its drift counts up to the step before the one
            // whose contacts touched it (that step's solve already pushed bricks).
            if (!hit_) wallDriftBeforeHit_ = std::max(wallDriftBeforeHit_, wallDrift());
        }
        if (scripted() && !launched_ && time() >= kLaunchTime - 1e-9) applyPush(pushForce());
    }

    std::vector<double> extraValues() const override {
        return {atRest() ? wallDrift() : 0.0, static_cast<double>(knockedBricks()), measures().penetration,
                hit_ ? 1.0 : 0.0};
    }

    double wallDrift() const {
        double worst = 0.0;
        for (std::size_t index : wallIndices_) {
            const Body& brick = bodies()[index];
            worst = std::max(worst, (bodyPosition(brick.body) - brick.restPose.position).norm());
        }
        return worst;
    }

    int knockedBricks() const {
        if (!atRest()) return 0;
        int knocked = 0;
        for (std::size_t index : wallIndices_) {
            const Body& brick = bodies()[index];
            knocked += (bodyPosition(brick.body) - brick.restPose.position).norm() > kKnockedBy;
        }
        return knocked;
    }

    int wallBricks_ = 0;
    double wallHeight_ = 0.0;
    std::vector<std::size_t> wallIndices_;  // into bodies(): no body is removed in this scene
    std::unordered_set<dGeomID> wallGeoms_;
    dBodyID projectile_ = nullptr;
    dGeomID projectileGeom_ = nullptr;
    bool launched_ = false, hit_ = false;
    double launchTime_ = 0.0, hitTime_ = 0.0;
    double wallDriftBeforeHit_ = 0.0;
    double deepestSinceRest_ = 0.0;  // m, deepest vertex below the ground since rest
    bool fellThrough_ = false;       // some body's centre went below the ground
};

}  // namespace

std::unique_ptr<Scene> makeBigWorld(const SceneOptions& options) { return std::make_unique<BigWorld>(options); }

}  // namespace gdc::scenes
