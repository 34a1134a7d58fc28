#include "interaction.hpp"

#include <geometry.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>

namespace gdc::viewer {
namespace {

// Colours of added bodies: saturated, so they stand out from the scenes' own and the grey ground.
constexpr Colour kSpawnColours[] = {{0.95f, 0.75f, 0.1f}, {0.3f, 0.45f, 0.95f}, {0.9f, 0.3f, 0.8f}, {0.5f, 0.9f, 0.2f}};
// Clearance above what a dropped body would otherwise touch, as a fraction of its radius: it
// falls a little, so its first contact is a landing, not an overlap.
constexpr double kDropGap = 0.05;

scenes::PlacedPart boxPart(const Vec3& halfExtents, const Vec3& centre) {
    scenes::PlacedPart part;
    part.shape = scenes::makeBox(halfExtents);
    part.offset.position = centre;
    part.isBox = true;  // may become an ODE dBox, as the scene's own boxes do
    part.halfExtents = halfExtents;
    return part;
}

std::string bodyName(const scenes::Scene& scene, dBodyID body) {
    for (const auto& candidate : scene.bodies())
        if (candidate.body == body) return candidate.name;
    return "static";
}

}  // namespace

const char* spawnKindName(SpawnKind kind) {
    switch (kind) {
        case SpawnKind::Box: return "box";
        case SpawnKind::Rock: return "rock";
        case SpawnKind::Composite: return "composite";
        case SpawnKind::Obj: return "OBJ file";
        case SpawnKind::Cylinder: return "cylinder";
        case SpawnKind::Capsule: return "capsule";
    }
    return "?";
}

SpawnShape centredShape(std::string name, std::vector<scenes::PlacedPart> parts) {
    for (auto& part : parts) {
        if (part.isBox || part.round != scenes::RoundKind::None) continue;  // centred already
        auto [centred, centroid] = scenes::centredOnCentroid(*part.shape);
        part.shape = centred;
        part.offset.position += part.offset.rotation * centroid;
    }
    double mass = 0.0;
    Vec3 centre = Vec3::Zero();
    for (const auto& part : parts) {
        const scenes::MassProperties properties = scenes::massProperties(part);
        mass += properties.volume;
        centre += properties.volume * part.offset.apply(properties.centroid);
    }
    centre /= mass;
    SpawnShape shape{std::move(name), std::move(parts), 0.0};
    for (auto& part : shape.parts) {
        part.offset.position -= centre;
        for (const Vec3& v : part.shape->vertices()) shape.radius = std::max(shape.radius, part.offset.apply(v).norm());
    }
    return shape;
}

SpawnShape makeSpawnBox(double radius) {
    const Vec3 proportions(1.0, 0.8, 0.6);
    return centredShape("box", {boxPart(radius / proportions.norm() * proportions, Vec3::Zero())});
}

SpawnShape makeSpawnRock(double radius, std::uint64_t seed) {
    scenes::Random random(seed);
    std::vector<Vec3> points;
    while (points.size() < 16) {
        // A uniform direction by rejection from the cube, then a random distance: lumpy, never flat.
        const Vec3 d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
        const double length = d.norm();
        if (length < 0.1 || length > 1.0) continue;
        points.push_back(radius * random.uniform(0.55, 1.0) / length * d);
    }
    scenes::PlacedPart part;
    part.shape = std::make_shared<const Polytope>(Polytope::fromPoints(points));
    return centredShape("rock", {part});
}

SpawnShape makeSpawnComposite(double radius) {
    // A T: a bar on a post, so it lands and tips in ways no single convex body does.
    const double s = radius / 1.2;
    return centredShape("composite", {boxPart(Vec3(0.9 * s, 0.25 * s, 0.2 * s), Vec3(0, 0, 0.75 * s)),
                                      boxPart(Vec3(0.2 * s, 0.2 * s, 0.55 * s), Vec3(0, 0, 0))});
}

SpawnShape makeSpawnCylinder(double radius) {
    return centredShape("cylinder", {scenes::makeCylinderPart(0.6 * radius, 1.6 * radius)});
}

SpawnShape makeSpawnCapsule(double radius) {
    scenes::PlacedPart part = scenes::makeCapsulePart(0.4 * radius, 1.2 * radius);
    // ODE's capsule axis is its z; turned onto x, so a dropped capsule lands lying on its side.
    part.offset.rotation = Eigen::AngleAxisd(0.5 * scenes::kPi, Vec3::UnitY()).toRotationMatrix();
    return centredShape("capsule", {part});
}

SpawnShape spawnShapeFromObj(const scenes::ObjShape& obj, std::string name) {
    return SpawnShape{std::move(name), obj.parts, obj.radius};
}

std::optional<Vec3> dropPosition(const SceneShapes& shapes, const Ray& cursorRay, double radius,
                                 double maxDistance) {
    const auto hit = shapes.pick(cursorRay);
    if (!hit || hit->distance > maxDistance) return std::nullopt;
    const Vec3 low = hit->point - Vec3(radius, radius, 0.0), high = hit->point + Vec3(radius, radius, 0.0);
    double bottom = hit->point.z();  // lowest height the body's bounding box may start at
    for (const auto& [shapeLow, shapeHigh] : shapeBounds(shapes.shapes())) {
        const bool overlapsColumn = shapeLow.x() < high.x() && shapeHigh.x() > low.x() && shapeLow.y() < high.y() &&
                                    shapeHigh.y() > low.y();
        if (overlapsColumn) bottom = std::max(bottom, shapeHigh.z());
    }
    return Vec3(hit->point.x(), hit->point.y(), bottom + (1.0 + kDropGap) * radius);
}

Launch launchAlong(const Ray& cursorRay, double radius, double speed) {
    return Launch{cursorRay.at(2.0 * radius), speed * cursorRay.direction};
}

void FlickTracker::begin(double x, double y, double seconds) {
    samples_.clear();
    move(x, y, seconds);
}

void FlickTracker::move(double x, double y, double seconds) {
    samples_.push_back({Eigen::Vector2d(x, y), seconds});
    // Keep one sample older than the window, so the window is always spanned.
    while (samples_.size() > 2 && samples_[1].seconds <= seconds - window) samples_.pop_front();
}

Eigen::Vector2d FlickTracker::velocity() const {
    if (samples_.size() < 2) return Eigen::Vector2d::Zero();
    const double elapsed = samples_.back().seconds - samples_.front().seconds;
    if (!(elapsed > 0.0)) return Eigen::Vector2d::Zero();
    return (samples_.back().pixel - samples_.front().pixel) / elapsed;
}

double flickSpeed(const OrbitCamera& camera, int windowHeight, const Eigen::Vector2d& pixelsPerSecond) {
    const double metresPerPixel = 2.0 * camera.distance() * std::tan(0.5 * camera.fieldOfViewY()) / std::max(windowHeight, 1);
    return pixelsPerSecond.norm() * metresPerPixel;
}

std::optional<Inspection> inspectBody(const scenes::Scene& scene, dBodyID body) {
    const auto it = std::find_if(scene.bodies().begin(), scene.bodies().end(),
                                 [&](const scenes::Body& candidate) { return candidate.body == body; });
    if (body == nullptr || it == scene.bodies().end()) return std::nullopt;
    Inspection result;
    result.body = body;
    result.name = it->name;
    dMass mass;
    dBodyGetMass(body, &mass);
    result.mass = mass.mass;
    const dReal* p = dBodyGetPosition(body);
    const dReal* v = dBodyGetLinearVel(body);
    const dReal* w = dBodyGetAngularVel(body);
    result.position = Vec3(p[0], p[1], p[2]);
    result.linearVelocity = Vec3(v[0], v[1], v[2]);
    result.angularVelocity = Vec3(w[0], w[1], w[2]);
    for (const scenes::ContactSample& contact : scene.lastContacts()) {
        const dBodyID first = dGeomGetBody(contact.g1), second = dGeomGetBody(contact.g2);
        if (first != body && second != body) continue;
        // ODE's normal points from g2 into g1: it pushes g1. Turned to push the inspected body.
        const bool isFirst = first == body;
        result.contacts.push_back({contact.position, isFirst ? contact.normal : Vec3(-contact.normal), contact.depth,
                                   bodyName(scene, isFirst ? second : first)});
    }
    return result;
}

std::optional<Inspection> inspectAlong(const scenes::Scene& scene, const SceneShapes& shapes, const Ray& cursorRay) {
    const auto hit = shapes.pick(cursorRay);
    if (!hit) return std::nullopt;
    return inspectBody(scene, shapes.shapes()[hit->shape].body);
}

std::optional<scenes::ContactSample> contactNearPixel(const scenes::Scene& scene, const OrbitCamera& camera, double x,
                                                      double y, int width, int height, double maxPixels) {
    std::optional<scenes::ContactSample> nearest;
    double best = maxPixels;
    const Vec3 forward = (camera.target() - camera.eye()).normalized();
    for (const scenes::ContactSample& contact : scene.lastContacts()) {
        if ((contact.position - camera.eye()).dot(forward) <= camera.nearPlane()) continue;  // behind the eye
        const double distance = (camera.project(contact.position, width, height) - Eigen::Vector2d(x, y)).norm();
        if (distance <= best) {
            best = distance;
            nearest = contact;
        }
    }
    return nearest;
}

std::vector<std::pair<Vec3, Vec3>> shapeBounds(const std::vector<DrawShape>& shapes) {
    std::vector<std::pair<Vec3, Vec3>> bounds;
    for (const DrawShape& shape : shapes) {
        if (shape.isPlane()) continue;
        Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
        for (const Vec3& v : shape.mesh->vertices) {
            const Vec3 world = shape.pose.apply(v);
            low = low.cwiseMin(world);
            high = high.cwiseMax(world);
        }
        bounds.emplace_back(low, high);
    }
    return bounds;
}

bool Interaction::loadObj(const std::string& path, scenes::ObjLayout layout, double scale) {
    try {
        const scenes::ObjShape shape = scenes::loadObjShape(path, layout, scale);
        const std::string file = path.substr(path.find_last_of('/') + 1);
        obj_ = spawnShapeFromObj(shape, file);
        kind = SpawnKind::Obj;
        char text[160];
        std::snprintf(text, sizeof text, "%zu part%s, %.3g m across, %.3g m³", shape.parts.size(),
                      shape.parts.size() == 1 ? "" : "s", 2.0 * shape.radius, shape.volume);
        objStatus_ = file + ": " + text;
        objFailed_ = false;
        return true;
    } catch (const std::exception& e) {  // ObjError, and anything else a bad file provokes
        objStatus_ = e.what();
        objFailed_ = true;
        return false;
    }
}

SpawnShape Interaction::nextShape(const scenes::Scene& scene) {
    std::vector<double> radii;
    for (const auto& body : scene.bodies())
        if (body.measured && body.radius > 0.0) radii.push_back(body.radius);
    double radius = 0.2;  // a scene without bodies of its own: a body of 40 cm
    if (!radii.empty()) {
        std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
        radius = radii[radii.size() / 2];
    }
    ++spawned_;
    switch (kind) {
        case SpawnKind::Box: return makeSpawnBox(radius);
        case SpawnKind::Rock: return makeSpawnRock(radius, spawned_);
        case SpawnKind::Composite: return makeSpawnComposite(radius);
        case SpawnKind::Cylinder: return makeSpawnCylinder(radius);
        case SpawnKind::Capsule: return makeSpawnCapsule(radius);
        case SpawnKind::Obj: break;
    }
    return obj_ ? *obj_ : makeSpawnBox(radius);  // no file loaded yet: a box rather than nothing
}

dBodyID addSpawn(scenes::Scene& scene, const Spawn& spawn) {
    return scene.spawnBody(spawn.name, spawn.shape.parts, spawn.density, spawn.pose, spawn.velocity, spawn.colour);
}

std::optional<Spawn> Interaction::planDrop(const scenes::Scene& scene, const SceneShapes& shapes,
                                           const Ray& cursorRay, double maxDistance) {
    SpawnShape shape = nextShape(scene);
    const auto position = dropPosition(shapes, cursorRay, shape.radius, maxDistance);
    if (!position) return std::nullopt;
    Spawn spawn;
    spawn.name = shape.name + " " + std::to_string(spawned_);
    spawn.shape = std::move(shape);
    spawn.pose.position = *position;
    spawn.density = density;
    spawn.colour = kSpawnColours[spawned_ % std::size(kSpawnColours)];
    return spawn;
}

Spawn Interaction::planThrow(const scenes::Scene& scene, const Ray& cursorRay, double speed) {
    SpawnShape shape = nextShape(scene);
    const Launch launch = launchAlong(cursorRay, shape.radius, speed);
    Spawn spawn;
    spawn.name = shape.name + " " + std::to_string(spawned_);
    spawn.shape = std::move(shape);
    spawn.pose.position = launch.position;
    spawn.velocity = launch.velocity;
    spawn.density = density;
    spawn.colour = kSpawnColours[spawned_ % std::size(kSpawnColours)];
    return spawn;
}

dBodyID Interaction::drop(scenes::Scene& scene, const SceneShapes& shapes, const Ray& cursorRay, double maxDistance) {
    const auto spawn = planDrop(scene, shapes, cursorRay, maxDistance);
    return spawn ? addSpawn(scene, *spawn) : nullptr;
}

dBodyID Interaction::throwAlong(scenes::Scene& scene, const Ray& cursorRay, double speed) {
    return addSpawn(scene, planThrow(scene, cursorRay, speed));
}

}  // namespace gdc::viewer
