#include "scene.hpp"

#include "terrain_ground.hpp"

#include <gdcontact/ode.hpp>
#include <gdcontact/tracking.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <stdexcept>
#include <unordered_map>

namespace gdc::scenes {
namespace {

constexpr int kContactBuffer = 64;
constexpr double kPlaneProxyHalfSize = 2.0;  // m: larger than any body of the scenes
const double kNaN = std::numeric_limits<double>::quiet_NaN();

Pose poseOfGeom(dGeomID geom) {
    const dReal* p = dGeomGetPosition(geom);
    const dReal* r = dGeomGetRotation(geom);  // 3×4 row-major
    Pose pose;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) pose.rotation(row, column) = r[row * 4 + column];
    pose.position = Vec3(p[0], p[1], p[2]);
    return pose;
}

Pose poseOfBody(dBodyID body) {
    const dReal* p = dBodyGetPosition(body);
    const dReal* r = dBodyGetRotation(body);
    Pose pose;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) pose.rotation(row, column) = r[row * 4 + column];
    pose.position = Vec3(p[0], p[1], p[2]);
    return pose;
}

void toOdeRotation(const Mat3& rotation, dMatrix3 out) {
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) out[row * 4 + column] = rotation(row, column);
        out[row * 4 + 3] = 0;
    }
}

bool isDynamic(dBodyID body) { return body != nullptr && !dBodyIsKinematic(body); }

/// Rotation about the vertical of `now` relative to `rest` (swing-twist decomposition about z).
double twistAngle(const Mat3& rest, const Mat3& now) {
    const Eigen::Quaterniond relative(now * rest.transpose());
    double angle = 2.0 * std::atan2(relative.z(), relative.w());
    while (angle > M_PI) angle -= 2.0 * M_PI;
    while (angle < -M_PI) angle += 2.0 * M_PI;
    return std::abs(angle);
}

}  // namespace

const char* methodName(Method method) {
    switch (method) {
        case Method::Gdcontact: return "gdc";
        case Method::Tracking: return "tracking";
        case Method::Ode: return "ode";
    }
    return "?";
}

std::optional<Method> parseMethod(const std::string& name) {
    for (Method method : {Method::Gdcontact, Method::Tracking, Method::Ode})
        if (name == methodName(method)) return method;
    return std::nullopt;
}

const char* stepperName(SolverSettings::Stepper stepper) {
    return stepper == SolverSettings::Stepper::World ? "world" : "quick";
}

SolverSettings exactStackingSolver() {
    SolverSettings solver;
    solver.stepper = SolverSettings::Stepper::World;
    solver.maxContactsPerPair = 4;
    solver.dt = 0.01;
    return solver;
}

Vec3 bodyPosition(dBodyID body) {
    const dReal* p = dBodyGetPosition(body);
    return Vec3(p[0], p[1], p[2]);
}

Vec3 bodyUpAxis(dBodyID body) {
    const dReal* r = dBodyGetRotation(body);
    return Vec3(r[2], r[6], r[10]);
}

double bodyTilt(dBodyID body) { return angleFromVertical(bodyUpAxis(body)); }

double worldHeight(const Part& part, const Vec3& vertex) {
    const dReal* p = dGeomGetPosition(part.geom);
    const dReal* r = dGeomGetRotation(part.geom);
    return r[8] * vertex.x() + r[9] * vertex.y() + r[10] * vertex.z() + p[2];
}

/// What the collision pass needs to know about a geom, and the per-step scratch.
struct Scene::Impl {
    struct GeomInfo {
        std::shared_ptr<const Polytope> shape;  // null for the ground plane and a terrain
        bool isPlane = false;
        HalfSpace plane;
        std::uint64_t serial = 0;  // creation order: a pair's order must not depend on addresses
        const TerrainGround* terrain = nullptr;  // set for a terrain (addTerrain)
    };
    std::uint64_t nextSerial = 0;
    struct Pair {
        std::uint64_t first, second;
        dGeomID geom1, geom2;
        bool operator<(const Pair& other) const {
            return first != other.first ? first < other.first : second < other.second;
        }
    };
    std::vector<Pair> pairs;  // this step's broad-phase pairs
    std::unordered_map<dGeomID, GeomInfo> geoms;
    /// Tracking only knows polytopes, so it sees a plane as a box whose top face lies in the
    /// plane. MPR aims along the line between the two centres, so the box is put right under the
    /// body when their contact begins (a fixed box far to the side would give MPR a slanted line
    /// and a wrong normal); it then stays fixed while the contact lasts, so the anchors that
    /// tracking stores on it mean what they mean on a plane.
    struct PlaneProxy {
        Pose pose;
        std::uint64_t lastSeen = 0;
    };
    std::shared_ptr<const Polytope> planeProxyShape = makeBox(Vec3::Constant(kPlaneProxyHalfSize));
    std::map<std::pair<dGeomID, dGeomID>, PlaneProxy> planeProxies;
    std::uint64_t stepNumber = 0;
    tracking::PairCache trackingCache;
    double stepPenetration = 0.0;
    double stepContactPenetration = 0.0;
    int stepInvalid = 0;
    std::array<dContactGeom, kContactBuffer> buffer{};
    // The whole-step path (setWholeStepCollision): each touching pair as spaceCollide's handler
    // passed it, turned to creation order, and its contacts; sorted before the joints are made.
    struct TouchingPair {
        std::uint64_t first, second;
        dGeomID geom1, geom2;
        std::size_t offset;  // into wholeStepContacts
        int count;
        bool operator<(const TouchingPair& other) const {
            return first != other.first ? first < other.first : second < other.second;
        }
    };
    std::vector<TouchingPair> touching;
    std::vector<dContactGeom> wholeStepContacts;
    // The gdcontact method with a body-pair budget (Settings::maxBodyPairContacts): each pair's
    // contacts, in the pairs' order, held until every pair is collided, so that the pairs between
    // the same two bodies are reduced together (gdc::ode::reduceBodyPair) before joints are made.
    struct HeldPair {
        dGeomID geom1, geom2;
        std::size_t offset;  // into heldContacts
        int count;
    };
    std::vector<HeldPair> held;
    std::vector<dContactGeom> heldContacts;
    // Terrains (addTerrain): destroyed with this Impl, after destroyWorld() destroyed their geoms.
    std::vector<std::unique_ptr<TerrainGround>> terrains;
};

Scene::Scene(std::string name, const SceneOptions& options, const SolverSettings& defaults)
    : name_(std::move(name)), options_(options), solver_(options.solver.value_or(defaults)),
      method_(options.method) {}

Scene::~Scene() { destroyWorld(); }

void Scene::destroyWorld() {
    if (contactGroup_) dJointGroupDestroy(contactGroup_);
    if (space_) dSpaceDestroy(space_);  // destroys its geoms (cleanup mode is on by default)
    if (world_) dWorldDestroy(world_);  // destroys bodies and joints
    contactGroup_ = nullptr;
    space_ = nullptr;
    world_ = nullptr;
    bodies_.clear();
    staticGeoms_.clear();
    contacts_.clear();
}

void Scene::reset() {
    destroyWorld();
    impl_ = std::make_unique<Impl>();
    // dWorldQuickStep shuffles its constraints with ODE's process-wide random generator; seeding
    // it here makes a reset scene replay exactly (the reports and the tests rely on that).
    dRandSetSeed(0);
    world_ = dWorldCreate();
    space_ = dHashSpaceCreate(nullptr);
    contactGroup_ = dJointGroupCreate(0);
    time_ = 0.0;
    steps_ = 0;
    atRest_ = false;
    exploded_ = false;
    current_ = Measures{};
    history_.clear();
    extraHistory_.clear();
    applySolverSettings();
    build();
}

void Scene::applySolverSettings() {
    const bool finite = std::isfinite(solver_.dt) && std::isfinite(solver_.erp) && std::isfinite(solver_.cfm) &&
                        std::isfinite(solver_.mu) && std::isfinite(solver_.surfaceLayer) &&
                        std::isfinite(solver_.gravity);
    if (!finite || !(solver_.dt > 0.0) || solver_.iterations < 1 || solver_.maxContactsPerPair < 1 ||
        solver_.maxContactsPerPair > kContactBuffer || !(solver_.erp >= 0.0) || !(solver_.cfm >= 0.0) ||
        !(solver_.mu >= 0.0) || !(solver_.surfaceLayer >= 0.0))
        throw std::invalid_argument("solver settings out of range (finite; dt > 0, iterations >= 1, "
                                    "1 <= contacts <= 64, erp, cfm, mu, surface layer >= 0)");
    dWorldSetGravity(world_, 0, 0, -solver_.gravity);
    dWorldSetERP(world_, solver_.erp);
    dWorldSetCFM(world_, solver_.cfm);
    dWorldSetQuickStepNumIterations(world_, solver_.iterations);
    dWorldSetContactSurfaceLayer(world_, solver_.surfaceLayer);
    dWorldSetAutoDisableFlag(world_, 0);  // bodies must keep being judged; nothing sleeps
}

void Scene::setMethod(Method method) {
    method_ = method;
    if (impl_) {
        impl_->trackingCache.clear();
        impl_->planeProxies.clear();
    }
}

void Scene::setSolver(const SolverSettings& settings) {
    const SolverSettings previous = solver_;
    solver_ = settings;
    if (!world_) return;
    try {
        applySolverSettings();
    } catch (...) {
        solver_ = previous;
        throw;
    }
}

void Scene::addGroundPlane() {
    dGeomID plane = dCreatePlane(space_, 0, 0, 1, 0);
    staticGeoms_.push_back(plane);
    Impl::GeomInfo info;
    info.isPlane = true;
    info.plane = HalfSpace{Vec3::UnitZ(), 0.0};
    info.serial = impl_->nextSerial++;
    impl_->geoms[plane] = info;
}

dGeomID Scene::addTerrain(std::vector<Vec3> vertices, std::vector<std::array<int, 3>> triangles) {
    auto terrain = std::make_unique<TerrainGround>(space_, std::move(vertices), std::move(triangles));
    staticGeoms_.push_back(terrain->geom());
    Impl::GeomInfo info;
    info.terrain = terrain.get();
    info.serial = impl_->nextSerial++;
    impl_->geoms[terrain->geom()] = info;
    impl_->terrains.push_back(std::move(terrain));
    return staticGeoms_.back();
}

Body& Scene::addBody(const std::string& name, const std::vector<PlacedPart>& parts, double density,
                     const Pose& pose, std::array<float, 3> colour) {
    if (parts.empty() || !(density > 0.0)) throw std::invalid_argument("addBody: needs parts and a positive density");
    // Common centre of mass and summed inertia in the composite's frame.
    double totalMass = 0.0;
    Vec3 centreOfMass = Vec3::Zero();
    std::vector<MassProperties> properties;
    for (const PlacedPart& part : parts) {
        properties.push_back(massProperties(part));
        const double mass = density * properties.back().volume;
        totalMass += mass;
        centreOfMass += mass * part.offset.apply(properties.back().centroid);
    }
    centreOfMass /= totalMass;
    Mat3 inertia = Mat3::Zero();
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const double mass = density * properties[i].volume;
        const Mat3& rotation = parts[i].offset.rotation;
        const Vec3 shift = parts[i].offset.apply(properties[i].centroid) - centreOfMass;
        inertia += density * rotation * properties[i].inertiaAboutCentroid * rotation.transpose() +
                   mass * (shift.squaredNorm() * Mat3::Identity() - shift * shift.transpose());  // parallel axis
    }

    dBodyID body = dBodyCreate(world_);
    dMass mass;
    dMassSetParameters(&mass, totalMass, 0, 0, 0, inertia(0, 0), inertia(1, 1), inertia(2, 2), inertia(0, 1),
                       inertia(0, 2), inertia(1, 2));
    dBodySetMass(body, &mass);
    const Vec3 origin = pose.apply(centreOfMass);
    dBodySetPosition(body, origin.x(), origin.y(), origin.z());
    dMatrix3 rotation;
    toOdeRotation(pose.rotation, rotation);
    dBodySetRotation(body, rotation);

    Body result;
    result.body = body;
    result.name = name;
    result.colour = colour;
    for (const PlacedPart& part : parts) {
        dGeomID geom = createGeom(part);
        dGeomSetBody(geom, body);
        const Vec3 offset = part.offset.position - centreOfMass;
        dGeomSetOffsetPosition(geom, offset.x(), offset.y(), offset.z());
        dMatrix3 offsetRotation;
        toOdeRotation(part.offset.rotation, offsetRotation);
        dGeomSetOffsetRotation(geom, offsetRotation);
        impl_->geoms[geom] = Impl::GeomInfo{part.shape, false, {}, impl_->nextSerial++};
        result.parts.push_back({geom, part.shape});
        for (const Vec3& v : part.shape->vertices())
            result.radius = std::max(result.radius, (part.offset.apply(v) - centreOfMass).norm());
    }
    result.restPose = poseOfBody(body);
    bodies_.push_back(std::move(result));
    return bodies_.back();
}

dGeomID Scene::createGeom(const PlacedPart& part) {
    if (part.round == RoundKind::Cylinder) return dCreateCylinder(space_, part.roundRadius, part.roundLength);
    if (part.round == RoundKind::Capsule) return dCreateCapsule(space_, part.roundRadius, part.roundLength);
    if (part.isBox && !options_.convexBoxes)
        return dCreateBox(space_, 2 * part.halfExtents.x(), 2 * part.halfExtents.y(), 2 * part.halfExtents.z());
    std::vector<dReal> points;
    for (const Vec3& v : part.shape->vertices()) points.insert(points.end(), {v.x(), v.y(), v.z()});
    return gdc::ode::createConvex(space_, points.data(), static_cast<unsigned>(part.shape->vertices().size()));
}

Body& Scene::addBox(const std::string& name, const Vec3& halfExtents, double density, const Pose& pose,
                    std::array<float, 3> colour) {
    return addBody(name, {PlacedPart{makeBox(halfExtents), Pose{}, true, halfExtents}}, density, pose, colour);
}

Body* Scene::findBody(dBodyID body) {
    for (Body& candidate : bodies_)
        if (candidate.body == body) return &candidate;
    return nullptr;
}

bool Scene::removeBody(dBodyID body) {
    auto it = std::find_if(bodies_.begin(), bodies_.end(), [&](const Body& b) { return b.body == body; });
    if (it == bodies_.end() || !it->removable) return false;
    for (const Part& part : it->parts) {
        impl_->geoms.erase(part.geom);
        dGeomDestroy(part.geom);
    }
    dBodyDestroy(body);
    bodies_.erase(it);
    // Contacts of the last step may name the destroyed geoms; drop them so nobody reads them.
    contacts_.clear();
    return true;
}

dBodyID Scene::spawnBody(const std::string& name, const std::vector<PlacedPart>& parts, double density,
                         const Pose& pose, const Vec3& linearVelocity, std::array<float, 3> colour) {
    if (!world_) reset();
    if (!pose.isFinite() || !linearVelocity.allFinite())
        throw std::invalid_argument("spawnBody: pose and velocity must be finite");
    Body& body = addBody(name, parts, density, pose, colour);
    body.removable = true;
    body.measured = false;  // the scene's verdict is about its own bodies, not a visitor's
    dBodySetLinearVel(body.body, linearVelocity.x(), linearVelocity.y(), linearVelocity.z());
    return body.body;
}

void Scene::applyPush(double) {}

void Scene::markRest() {
    for (Body& body : bodies_) body.restPose = poseOfBody(body.body);
    atRest_ = true;
}

void Scene::nearCallback(void* data, dGeomID o1, dGeomID o2) {
    // Only collect: the broad phase reports pairs in an order that follows memory addresses,
    // and both the tracking state and the solvers' results depend on the order of the contacts.
    // step() sorts the pairs by creation order first, so that every run replays exactly.
    Impl& impl = *static_cast<Scene*>(data)->impl_;
    auto info1 = impl.geoms.find(o1), info2 = impl.geoms.find(o2);
    if (info1 == impl.geoms.end() || info2 == impl.geoms.end()) return;
    if (info1->second.serial < info2->second.serial) impl.pairs.push_back({info1->second.serial, info2->second.serial, o1, o2});
    else impl.pairs.push_back({info2->second.serial, info1->second.serial, o2, o1});
}

void Scene::collidePair(dGeomID o1, dGeomID o2) {
    // o1 was created before o2 (see nearCallback).
    auto info1 = impl_->geoms.find(o1), info2 = impl_->geoms.find(o2);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (b1 == b2) return;                           // parts of one composite, or two static geoms
    if (!isDynamic(b1) && !isDynamic(b2)) return;   // carried (kinematic) body against the ground
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;

    // The geometric penetration of every pair the broad phase reports, whatever the method says
    // (big worlds measure against the ground instead: groundPenetration()).
    const Impl::GeomInfo& g1 = info1->second;
    const Impl::GeomInfo& g2 = info2->second;
    if (!wholeStepCollision_) {
        double overlap = 0.0;
        if (g1.terrain && g2.shape) overlap = g1.terrain->penetration(*g2.shape, poseOfGeom(o2));
        else if (g2.terrain && g1.shape) overlap = g2.terrain->penetration(*g1.shape, poseOfGeom(o1));
        else if (g1.isPlane && !g2.isPlane) overlap = penetrationDepth(*g2.shape, poseOfGeom(o2), g1.plane);
        else if (g2.isPlane && !g1.isPlane) overlap = penetrationDepth(*g1.shape, poseOfGeom(o1), g2.plane);
        else if (g1.shape && g2.shape) overlap = penetrationDepth(*g1.shape, poseOfGeom(o1), *g2.shape, poseOfGeom(o2));
        impl_->stepPenetration = std::max(impl_->stepPenetration, overlap - solver_.surfaceLayer);
    }

    const int wanted = solver_.maxContactsPerPair;
    dContactGeom* out = impl_->buffer.data();
    int count = 0;
    switch (method_) {
        case Method::Gdcontact: {
            // The pairs install() leaves to ODE (docs/ode.md): dCollide, as an installed ODE would.
            if (!gdc::ode::handles(dGeomGetClass(o1), dGeomGetClass(o2))) {
                count = dCollide(o1, o2, wanted, out, sizeof(dContactGeom));
                break;
            }
            // Explicit settings rather than install()'s global ones: the method is per scene.
            gdc::Settings settings = contactSettings_;
            settings.maxContacts = std::min(wanted, kMaxManifoldPoints);
            count = gdc::ode::collide(o1, o2, wanted, out, sizeof(dContactGeom), settings);
            break;
        }
        case Method::Ode:
            count = dCollide(o1, o2, wanted, out, sizeof(dContactGeom));
            break;
        case Method::Tracking: {
            if (g1.terrain || g2.terrain) {  // MPR needs convex shapes: ODE's trimesh colliders
                count = dCollide(o1, o2, wanted, out, sizeof(dContactGeom));
                break;
            }
            auto proxyPose = [&](dGeomID plane, const HalfSpace& halfSpace, dGeomID other) {
                auto [entry, created] = impl_->planeProxies.try_emplace({o1, o2});
                if (created) {
                    // Right under the other geom, top face in the plane (ground planes are z-up).
                    const Vec3 above = poseOfGeom(other).position;
                    const Vec3 normal = halfSpace.normal.normalized();
                    entry->second.pose.rotation = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), normal).toRotationMatrix();
                    const Vec3 onPlane = above - (normal.dot(above) - halfSpace.offset) * normal;
                    entry->second.pose.position = onPlane - kPlaneProxyHalfSize * normal;
                }
                (void)plane;
                entry->second.lastSeen = impl_->stepNumber;
                return entry->second.pose;
            };
            const Polytope& shape1 = g1.isPlane ? *impl_->planeProxyShape : *g1.shape;
            const Polytope& shape2 = g2.isPlane ? *impl_->planeProxyShape : *g2.shape;
            const Pose pose1 = g1.isPlane ? proxyPose(o1, g1.plane, o2) : poseOfGeom(o1);
            const Pose pose2 = g2.isPlane ? proxyPose(o2, g2.plane, o1) : poseOfGeom(o2);
            tracking::PersistentManifold& persistent = impl_->trackingCache.manifoldFor(o1, o2);
            const Manifold manifold = persistent.update(shape1, pose1, shape2, pose2);
            for (int i = 0; i < manifold.pointCount && count < wanted; ++i) {
                if (manifold.points[i].depth < 0.0) continue;  // ODE needs depth ≥ 0
                dContactGeom& c = out[count++];
                for (int k = 0; k < 3; ++k) {
                    c.pos[k] = manifold.points[i].position[k];
                    c.normal[k] = -manifold.normal[k];  // core: A→B; ODE: from o2 into o1
                }
                c.depth = manifold.points[i].depth;
                c.g1 = o1;
                c.g2 = o2;
                c.side1 = c.side2 = -1;
            }
            break;
        }
    }
    if (method_ == Method::Gdcontact && contactSettings_.maxBodyPairContacts > 0) {
        impl_->held.push_back({o1, o2, impl_->heldContacts.size(), count});
        impl_->heldContacts.insert(impl_->heldContacts.end(), out, out + count);
        return;
    }
    addContactJoints(o1, o2, out, count);
}

void Scene::addHeldContacts() {
    // As a user's own near callback would apply the body-pair budget: every pair's contacts added
    // to a gdc::ode::BodyPairContacts in the pairs' (creation) order, then delivered — the pairs
    // between the same two bodies reduced together, each pair handed its survivors, in that order.
    if (impl_->held.empty()) return;
    gdc::ode::BodyPairContacts collected(contactSettings_);
    for (const Impl::HeldPair& pair : impl_->held)
        collected.add(pair.geom1, pair.geom2, impl_->heldContacts.data() + pair.offset, pair.count);
    collected.deliver(this, [](void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
        static_cast<Scene*>(data)->addContactJoints(o1, o2, contacts, count);
    });
}

void Scene::addContactJoints(dGeomID o1, dGeomID o2, const dContactGeom* out, int count) {
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    for (int i = 0; i < count; ++i) {
        const dContactGeom& c = out[i];
        const Vec3 normal(c.normal[0], c.normal[1], c.normal[2]);
        const Vec3 position(c.pos[0], c.pos[1], c.pos[2]);
        // ODE's own convex collider returns a zero normal for exactly touching shapes, which would
        // make ODE abort; such a contact carries no direction, so it is dropped and counted.
        if (!normal.allFinite() || !position.allFinite() || !std::isfinite(c.depth) ||
            std::abs(normal.norm() - 1.0) > 1e-6) {
            ++impl_->stepInvalid;
            continue;
        }
        dContact contact{};
        contact.surface.mode = dContactApprox1;
        contact.surface.mu = solver_.mu;
        contact.geom = c;
        contact.geom.g1 = o1;
        contact.geom.g2 = o2;
        dJointID joint = dJointCreateContact(world_, contactGroup_, &contact);
        dJointAttach(joint, b1, b2);
        contacts_.push_back({position, normal, c.depth, o1, o2});
        impl_->stepContactPenetration = std::max(impl_->stepContactPenetration, c.depth - solver_.surfaceLayer);
    }
}

void Scene::wholeStepHandler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count) {
    Scene& scene = *static_cast<Scene*>(data);
    Impl& impl = *scene.impl_;
    // The same pairs collidePair skips (spaceCollide has collided them already; few are skipped).
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (b1 == b2 || (!isDynamic(b1) && !isDynamic(b2))) return;
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
    auto info1 = impl.geoms.find(o1), info2 = impl.geoms.find(o2);
    if (info1 == impl.geoms.end() || info2 == impl.geoms.end()) return;
    const std::size_t offset = impl.wholeStepContacts.size();
    impl.wholeStepContacts.insert(impl.wholeStepContacts.end(), contacts, contacts + count);
    if (info1->second.serial < info2->second.serial) {
        impl.touching.push_back({info1->second.serial, info2->second.serial, o1, o2, offset, count});
    } else {
        // Creation order, as the other methods see the pair: the normal (from o2 into o1) turns.
        for (int i = 0; i < count; ++i)
            for (int k = 0; k < 3; ++k) impl.wholeStepContacts[offset + i].normal[k] *= -1;
        impl.touching.push_back({info2->second.serial, info1->second.serial, o2, o1, offset, count});
    }
}

void Scene::collideWholeStep() {
    impl_->touching.clear();
    impl_->wholeStepContacts.clear();
    gdc::ode::spaceCollide(space_, solver_.maxContactsPerPair, this, &Scene::wholeStepHandler);
    // spaceCollide hands the pairs over in the broad phase's order; joints are made in creation
    // order, as the other methods make them, so that a reset scene replays exactly.
    std::sort(impl_->touching.begin(), impl_->touching.end());
    for (const Impl::TouchingPair& pair : impl_->touching)
        addContactJoints(pair.geom1, pair.geom2, impl_->wholeStepContacts.data() + pair.offset, pair.count);
}

double Scene::groundPenetration() const {
    double deepest = 0.0;  // the ground is z = 0 (addGroundPlane)
    for (const Body& body : bodies_)
        for (const Part& part : body.parts)
            for (const Vec3& vertex : part.shape->vertices())
                deepest = std::max(deepest, -worldHeight(part, vertex));
    return deepest - solver_.surfaceLayer;
}

void Scene::step() {
    if (!world_) reset();
    if (exploded_) return;
    using Clock = std::chrono::steady_clock;
    contacts_.clear();
    impl_->stepPenetration = 0.0;
    impl_->stepContactPenetration = 0.0;
    impl_->stepInvalid = 0;

    const auto collisionStart = Clock::now();
    if (method_ == Method::Tracking) impl_->trackingCache.beginStep();
    if (wholeStepCollision_ && method_ == Method::Gdcontact) {
        collideWholeStep();
    } else {
        impl_->pairs.clear();
        impl_->held.clear();
        impl_->heldContacts.clear();
        dSpaceCollide(space_, this, &Scene::nearCallback);
        std::sort(impl_->pairs.begin(), impl_->pairs.end());
        for (const Impl::Pair& pair : impl_->pairs) collidePair(pair.geom1, pair.geom2);
        addHeldContacts();
    }
    if (wholeStepCollision_) impl_->stepPenetration = groundPenetration();
    if (method_ == Method::Tracking) {
        impl_->trackingCache.endStep();
        // Plane proxies live exactly as long as their pair's tracking state.
        for (auto it = impl_->planeProxies.begin(); it != impl_->planeProxies.end();)
            it = it->second.lastSeen == impl_->stepNumber ? std::next(it) : impl_->planeProxies.erase(it);
    }
    ++impl_->stepNumber;
    const auto solverStart = Clock::now();
    if (solver_.stepper == SolverSettings::Stepper::World) dWorldStep(world_, solver_.dt);
    else dWorldQuickStep(world_, solver_.dt);
    const auto solverEnd = Clock::now();
    dJointGroupEmpty(contactGroup_);

    time_ += solver_.dt;
    ++steps_;
    current_ = Measures{};
    current_.collisionSeconds = std::chrono::duration<double>(solverStart - collisionStart).count();
    current_.solverSeconds = std::chrono::duration<double>(solverEnd - solverStart).count();
    current_.penetration = impl_->stepPenetration;
    current_.contactPenetration = impl_->stepContactPenetration;
    current_.contacts = static_cast<int>(contacts_.size());
    current_.invalidContacts = impl_->stepInvalid;

    for (const Body& body : bodies_) {
        const dReal* p = dBodyGetPosition(body.body);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) ||
            Vec3(p[0], p[1], p[2]).norm() > 1e3)
            exploded_ = true;
    }
    if (exploded_) return;
    script();
    measure();
}

void Scene::runUntil(double seconds) {
    if (!world_) reset();
    while (time_ + 0.5 * solver_.dt < seconds && !exploded_) step();
}

void Scene::measure() {
    Measures& m = current_;
    m.time = time_;
    m.alignment = 0.0;
    m.drift = m.twist = m.sag = atRest_ ? 0.0 : kNaN;
    m.speed = 0.0;
    for (const Body& body : bodies_) {
        if (!body.measured) continue;
        const Pose pose = poseOfBody(body.body);
        // Alignment: the most downward face of any part is the resting face; its tilt from −z.
        Vec3 lowest = Vec3::UnitZ();
        for (const Part& part : body.parts) {
            const Mat3 rotation = poseOfGeom(part.geom).rotation;
            for (const Polytope::Face& face : part.shape->faces()) {
                const Vec3 normal = rotation * face.normal;
                if (normal.z() < lowest.z()) lowest = normal;
            }
        }
        m.alignment = std::max(m.alignment, angleFromVertical(-lowest));
        const dReal* v = dBodyGetLinearVel(body.body);
        const dReal* w = dBodyGetAngularVel(body.body);
        const double speed = Vec3(v[0], v[1], v[2]).norm() + Vec3(w[0], w[1], w[2]).norm() * body.radius;
        m.speed = std::max(m.speed, speed);
        if (atRest_) {
            const Vec3 displacement = pose.position - body.restPose.position;
            m.drift = std::max(m.drift, displacement.head<2>().norm());
            m.sag = std::max(m.sag, std::abs(displacement.z()));
            m.twist = std::max(m.twist, twistAngle(body.restPose.rotation, pose.rotation));
        }
    }
    history_.push_back(m);
    extraHistory_.push_back(extraValues());
}

Summary Scene::summary() const {
    Summary s;
    double sumPenetration = 0, sumAlignment = 0, sumSquaredSpeed = 0, sumCollision = 0, sumSolver = 0;
    for (const Measures& m : history_) {
        sumCollision += m.collisionSeconds;
        sumSolver += m.solverSeconds;
        if (std::isnan(m.drift)) continue;  // before rest
        ++s.samples;
        s.maxPenetration = std::max(s.maxPenetration, m.penetration);
        s.maxContactPenetration = std::max(s.maxContactPenetration, m.contactPenetration);
        s.maxAlignment = std::max(s.maxAlignment, m.alignment);
        s.maxDrift = std::max(s.maxDrift, m.drift);
        s.maxTwist = std::max(s.maxTwist, m.twist);
        s.maxSag = std::max(s.maxSag, m.sag);
        sumPenetration += m.penetration;
        sumAlignment += m.alignment;
        sumSquaredSpeed += m.speed * m.speed;
    }
    if (s.samples > 0) {
        s.meanPenetration = sumPenetration / s.samples;
        s.meanAlignment = sumAlignment / s.samples;
        s.oscillation = std::sqrt(sumSquaredSpeed / s.samples);
    }
    if (!history_.empty()) {
        s.meanCollisionSeconds = sumCollision / history_.size();
        s.meanSolverSeconds = sumSolver / history_.size();
    }
    return s;
}

void Scene::writeCsv(const std::string& path) const {
    std::ofstream file(path);
    if (!file) throw std::runtime_error("cannot write " + path);
    file << "time,penetration,contact_penetration,alignment,drift,twist,sag,speed,contacts,invalid_contacts,"
            "collision_seconds,solver_seconds";
    for (const std::string& column : extraColumns()) file << ',' << column;
    file << '\n' << std::setprecision(9);
    for (std::size_t i = 0; i < history_.size(); ++i) {
        const Measures& m = history_[i];
        file << m.time << ',' << m.penetration << ',' << m.contactPenetration << ',' << m.alignment << ','
             << m.drift << ',' << m.twist << ',' << m.sag << ',' << m.speed << ',' << m.contacts << ','
             << m.invalidContacts << ',' << m.collisionSeconds << ',' << m.solverSeconds;
        for (double value : extraHistory_[i]) file << ',' << value;
        file << '\n';
    }
    if (!file) throw std::runtime_error("error writing " + path);
}

}  // namespace gdc::scenes
