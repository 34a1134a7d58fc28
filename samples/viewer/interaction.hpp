// What a person does to a scene besides dragging: drop a body at the cursor, throw one from the
// camera, load their own shape from an OBJ file, and inspect the body or contact under the cursor.
// The maths (where a drop lands, a throw's start and velocity, what is under the cursor) is free of
// windows and OpenGL so the tests check it directly; the viewer only calls it from its key and
// mouse handlers and its panel. Up is +z, as in every scene (gravity along −z).
#pragma once

#include "camera.hpp"
#include "renderer.hpp"
#include "scene_shapes.hpp"

#include <obj_shape.hpp>
#include <scene.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gdc::viewer {

enum class SpawnKind { Box, Rock, Composite, Obj, Cylinder, Capsule };
/// In the panel's and the number keys' order (1 box … 6 capsule): the kinds added later come last,
/// so the older keys keep their meaning.
inline constexpr SpawnKind kSpawnKinds[] = {SpawnKind::Box, SpawnKind::Rock,     SpawnKind::Composite,
                                            SpawnKind::Obj, SpawnKind::Cylinder, SpawnKind::Capsule};
const char* spawnKindName(SpawnKind kind);  // "box", "rock", "composite", "OBJ file", "cylinder", "capsule"

/// A body ready to add: convex parts in a frame whose origin is their common centre of mass
/// (uniform density), so the body's centre of mass lands where the frame is put.
struct SpawnShape {
    std::string name;
    std::vector<scenes::PlacedPart> parts;
    double radius = 0.0;  ///< bounding radius about the origin (m)
};
/// Recentres `parts` on their common centre of mass and measures their bounding radius (cylinder
/// and capsule parts are centred on their own centre already, and measured by their tessellation,
/// whose vertices lie on their surface).
SpawnShape centredShape(std::string name, std::vector<scenes::PlacedPart> parts);
/// A box whose corners lie `radius` from its centre (proportions 1 : 0.8 : 0.6).
SpawnShape makeSpawnBox(double radius);
/// A rock: the convex hull of 16 points at 0.55–1 × `radius` in random directions, the same for
/// the same seed.
SpawnShape makeSpawnRock(double radius, std::uint64_t seed);
/// A composite of two boxes, a T (one body, two convex parts), about `radius` across.
SpawnShape makeSpawnComposite(double radius);
/// A standing cylinder (a real dCylinder, axis vertical) whose rim lies `radius` from its centre:
/// radius 0.6 × `radius`, height 1.6 × `radius`.
SpawnShape makeSpawnCylinder(double radius);
/// A lying capsule (a real dCapsule, axis along the body's x) reaching `radius` from its centre:
/// ball radius 0.4 × `radius`, 1.2 × `radius` between the ball centres.
SpawnShape makeSpawnCapsule(double radius);
SpawnShape spawnShapeFromObj(const scenes::ObjShape& obj, std::string name);

/// Where a body of bounding radius `radius` is dropped for a cursor ray: over the point where the
/// ray first meets a shape (the ground included), raised until its bounding box clears the
/// bounding box of every shape below it, so it falls onto whatever is there instead of starting
/// inside it. Nothing when the ray meets no shape within `maxDistance` (the cursor is on the sky,
/// or on ground so far away that the body would land out of sight, where the scene may count it
/// as having left the world).
std::optional<Vec3> dropPosition(const SceneShapes& shapes, const Ray& cursorRay, double radius,
                                 double maxDistance);

struct Launch {
    Vec3 position;
    Vec3 velocity;
};
/// A throw from the camera: the body starts on the cursor ray two radii from the eye (just in
/// front of the camera) and moves along the ray at `speed` (m/s).
Launch launchAlong(const Ray& cursorRay, double radius, double speed);

/// The cursor's recent motion during a throwing gesture: its velocity when the button is let go.
class FlickTracker {
public:
    /// Motion older than this (s) before the latest sample does not count: a flick is its last
    /// tenth of a second, not the whole drag.
    double window = 0.1;
    void begin(double x, double y, double seconds);
    void move(double x, double y, double seconds);
    void end() { samples_.clear(); }
    bool active() const { return !samples_.empty(); }
    /// Pixels per second over the window (zero with fewer than two samples or no elapsed time).
    Eigen::Vector2d velocity() const;

private:
    struct Sample {
        Eigen::Vector2d pixel;
        double seconds;
    };
    std::deque<Sample> samples_;
};
/// The speed (m/s) a flick of `pixelsPerSecond` stands for: the cursor's speed carried to the
/// camera target's distance, where a pixel spans 2·d·tan(fov/2)/height metres.
double flickSpeed(const OrbitCamera& camera, int windowHeight, const Eigen::Vector2d& pixelsPerSecond);

/// A contact of the inspected body, its normal turned to point into that body (the direction the
/// contact pushes it).
struct InspectedContact {
    Vec3 position;
    Vec3 normal;
    double depth = 0.0;
    std::string other;  ///< name of the body on the other side, "static" for the ground and walls
};
struct Inspection {
    dBodyID body = nullptr;
    std::string name;
    double mass = 0.0;  ///< kg
    Vec3 position = Vec3::Zero();         ///< centre of mass (m)
    Vec3 linearVelocity = Vec3::Zero();   ///< m/s
    Vec3 angularVelocity = Vec3::Zero();  ///< rad/s
    std::vector<InspectedContact> contacts;  ///< of the scene's last step
};
/// The body's state and its contacts of the last step; nothing if the scene has no such body.
std::optional<Inspection> inspectBody(const scenes::Scene& scene, dBodyID body);
/// The body the cursor ray meets first; nothing on the sky or on static geometry.
std::optional<Inspection> inspectAlong(const scenes::Scene& scene, const SceneShapes& shapes, const Ray& cursorRay);
/// The contact of the last step drawn nearest to pixel (x, y), if one is within `maxPixels`.
std::optional<scenes::ContactSample> contactNearPixel(const scenes::Scene& scene, const OrbitCamera& camera, double x,
                                                      double y, int width, int height, double maxPixels);

/// Axis-aligned bounds of each finite shape (planes have none), in the order of `shapes`.
std::vector<std::pair<Vec3, Vec3>> shapeBounds(const std::vector<DrawShape>& shapes);

/// Debug drawing on top of the renderer's frame (interaction_draw.cpp).
struct DebugDraw {
    bool wireframe = false;  ///< bodies as edges only, in their colours: see contacts inside a stack
    bool bounds = false;     ///< each convex part's axis-aligned bounding box
};
/// What the renderer should draw under `debug`: in wireframe mode only the planes (the edges come
/// from drawDebugOverlay); `planes` keeps the shapes the returned input points to.
FrameInput rendererInput(const FrameInput& in, const DebugDraw& debug, std::vector<DrawShape>& planes);
/// Draws the wireframe edges and bounding boxes with the camera and into the viewport of `in`
/// (after the renderer has drawn that frame; side by side, once per view with its own world).
void drawDebugOverlay(const FrameInput& in, const DebugDraw& debug);

/// A body about to be added: its shape, where and how fast. Made once and added to every world of
/// the side-by-side view alike, so both get the same body (the same rock, too) at the same pose.
struct Spawn {
    SpawnShape shape;
    std::string name;  ///< unique in the scene: "box 3" (the side-by-side view matches bodies by it)
    Pose pose;
    Vec3 velocity = Vec3::Zero();  ///< m/s
    double density = 1000.0;       ///< kg/m³
    Colour colour{};
};
/// Adds `spawn` to `scene` (Scene::spawnBody); returns the new body.
dBodyID addSpawn(scenes::Scene& scene, const Spawn& spawn);

/// The viewer's interaction state: what a drop or throw adds, the loaded OBJ shape, the
/// inspector and debug-draw switches, and the panel section and inspector window that edit them.
class Interaction {
public:
    SpawnKind kind = SpawnKind::Box;
    double throwSpeed = 8.0;   ///< m/s of the `t` key's throw
    double density = 1000.0;   ///< kg/m³ of what is added
    bool inspector = false;
    DebugDraw debug;

    /// Loads an OBJ shape and makes it the kind to add. On failure the previous shape stays, the
    /// message is kept in objStatus() and false is returned; nothing is thrown.
    bool loadObj(const std::string& path, scenes::ObjLayout layout, double scale);
    bool hasObj() const { return obj_.has_value(); }
    const std::string& objStatus() const { return objStatus_; }

    /// The next body to add: the chosen kind, sized like the scene's own bodies (the median
    /// bounding radius); an OBJ shape keeps its own size. Each rock is a new one.
    SpawnShape nextShape(const scenes::Scene& scene);
    /// The next body, over the point the cursor ray meets within `maxDistance` of `scene`'s
    /// shapes; nothing if it meets nothing there.
    std::optional<Spawn> planDrop(const scenes::Scene& scene, const SceneShapes& shapes, const Ray& cursorRay,
                                  double maxDistance);
    /// The next body, in front of the camera, flying along the cursor ray at `speed` m/s.
    Spawn planThrow(const scenes::Scene& scene, const Ray& cursorRay, double speed);
    /// planDrop / planThrow added to `scene` alone; null if nothing was added.
    dBodyID drop(scenes::Scene& scene, const SceneShapes& shapes, const Ray& cursorRay, double maxDistance);
    dBodyID throwAlong(scenes::Scene& scene, const Ray& cursorRay, double speed);

    // ImGui (interaction_panel.cpp)
    /// The panel section: kind, throw speed, density, OBJ file, inspector and debug switches.
    void panelSection();
    /// The inspector window for the cursor at pixel (x, y) of a width × height view of `scene`
    /// (null: the cursor is on no view); `view` names the view side by side ("left, gdcontact").
    void inspectorWindow(const scenes::Scene* scene, const SceneShapes& shapes, const OrbitCamera& camera, double x,
                         double y, int width, int height, const std::string& view = "") const;

private:
    std::optional<SpawnShape> obj_;
    std::string objStatus_;
    bool objFailed_ = false;  // the last load failed: its message is shown as an error
    std::uint64_t spawned_ = 0;  // names and rock seeds
    // The panel's OBJ fields
    char objPath_[512] = "";
    bool objAsHull_ = false;
    float objScale_ = 1.0f;
};

}  // namespace gdc::viewer
