// The interactive viewer: a GLFW window with an OpenGL 2.1 context and a Dear ImGui panel around
// one of the paper's scenes (samples/scenes).
//
// Side by side, the same scene runs in two worlds at once — one with the primary contact method
// (gdcontact by default), one with a second (ODE's native colliders by default) — drawn in two
// viewports with one shared camera. Every action of the user (drag, remove, push, reset, solver
// settings, a dropped or thrown body) is applied to the corresponding body in both worlds, so the
// difference between the two pictures is the contacts' doing. Bodies correspond by their index in
// Scene::bodies(): both worlds are built by the same deterministic build(), every removal is
// applied to both, and a body a person adds is appended to both at the same pose and velocity.
//
// Interactively the simulation runs on its own thread, in fixed steps paced by a wall-clock
// accumulator. The window thread holds the scene lock only to handle input, build the panel and
// copy what it will draw (poses, contacts); OpenGL drawing and buffer swaps happen outside the
// lock, so the GPU (or software rasteriser) never blocks a simulation step. A slow frame costs
// frames, not simulated time; a machine too slow for real time runs the simulation slower instead
// of queueing ever more steps.
#pragma once

#include "camera.hpp"
#include "image.hpp"
#include "interaction.hpp"
#include "renderer.hpp"
#include "scene_shapes.hpp"
#include "spring_drag.hpp"

#include <scene.hpp>

#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

struct GLFWwindow;

namespace gdc::viewer {

struct ViewerOptions {
    std::string scene = "brick_wall";
    int width = 1280, height = 720;
    /// 0: interactive until the window closes. N > 0: draw N frames, then exit (headless use).
    int frames = 0;
    /// With frames > 0: advance the simulation by wall-clock time as the interactive loop does
    /// and print the frame rate (for measuring). Without: every frame advances exactly 1/60 s of
    /// simulated time, so a screenshot is reproducible.
    bool realtime = false;
    std::string screenshot;  // PNG written after the last frame (frames > 0)
    bool panel = true;       // the ImGui panel
    bool contacts = true;    // contact overlay
    std::optional<scenes::Method> method;
    bool scripted = false;   // let the scene's scripted user act (builder, remover, push)
    bool visible = true;     // show the window (false for tests)
    bool fit = false;        // frame the bodies as they are at the end before the screenshot
    bool sideBySide = false; // a second world with `compareMethod`, drawn beside the first
    scenes::Method compareMethod = scenes::Method::Ode;
    bool convexBoxes = false;     // box-shaped bodies as dConvex (gdc::ode::createConvex), not dBox
    bool contactsThrough = false; // contact marks drawn over the bodies in front of them
    bool labels = true;      // method, verdict and contact legend drawn over the picture
    std::string obj;         // OBJ file whose shape the drop and throw add (--obj)
    bool objHull = false;    // the whole file as one convex hull, not one part per object
    double objScale = 1.0;   // OBJ coordinates × this = metres
};

/// A rectangle of the window in window coordinates (pixels, top-left origin, as the mouse).
struct Viewport {
    int x = 0, y = 0, width = 0, height = 0;
    bool contains(double px, double py) const { return px >= x && px < x + width && py >= y && py < y + height; }
};

/// The scene's own check (Scene::outcome(), what the headless scene programs print), read as a
/// person watching needs it: no pass or fail while the scene is still settling or being built.
struct Verdict {
    enum class State { Pending, Pass, Fail } state = State::Pending;
    std::string text;  // Scene::outcome().text
};

/// Per-frame timings of the loop (seconds of wall-clock time).
struct FrameTimes {
    int frames = 0;
    int steps = 0;
    double wallSeconds = 0.0;
    double simulateSeconds = 0.0;  // scene.step() and the spring, all steps of all frames
    double drawSeconds = 0.0;      // GL drawing of scene and panel, and the buffer swap
    double snapshotSeconds = 0.0;  // input, panel and the copy of the scene, under the scene lock
    double collisionSeconds = 0.0;  // the scenes' own measure, summed over steps
    double solverSeconds = 0.0;
    double simulatedSeconds = 0.0;
};

class Viewer {
public:
    /// Opens the window and loads the scene. Throws std::runtime_error when no window or GL
    /// context can be made (no X server), std::invalid_argument for an unknown scene name.
    explicit Viewer(const ViewerOptions& options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    /// Runs as the options say (interactive, or N frames then the screenshot). Returns an exit code.
    int run();

    // --- the pieces run() is made of, public for the tests and for scripted use ---
    void loadScene(const std::string& name);
    scenes::Scene& scene() { return *scene_; }
    /// View 0: the primary world (scene()); view 1, side by side only: the comparison world.
    int viewCount() const { return compare_ ? 2 : 1; }
    scenes::Scene& scene(int view) { return view == 0 ? *scene_ : *compare_->scene; }
    const SceneShapes& shapes(int view) const { return view == 0 ? shapes_ : compare_->shapes; }
    const SpringDrag& drag(int view) const { return view == 0 ? drag_ : compare_->drag; }
    /// Where view `view` is drawn in the window (right of the panel when it is shown).
    Viewport viewport(int view) const;
    Verdict verdict(int view);
    /// The state of a view as the panel and the picture show it: "settling, not judged yet", "PASS", "FAIL".
    static const char* verdictLabel(Verdict::State state);

    /// Side by side on: both worlds are rebuilt from the start so they begin identical.
    void setSideBySide(bool on);
    bool sideBySide() const { return compare_ != nullptr; }
    /// The second world's method (takes effect at its next step, as the panel's switch does).
    void setCompareMethod(scenes::Method method);
    /// Boxes as dBox or dConvex: rebuilds the scene in every world (camera kept).
    void setConvexBoxes(bool convex);
    bool convexBoxes() const { return options_.convexBoxes; }
    void setContactsThrough(bool through) { contactsThrough_ = through; }
    bool contactsThrough() const { return contactsThrough_; }
    /// Both worlds back to their start.
    void resetScene();
    /// Advance the simulation by whole steps covering `seconds` (at least one step when > 0).
    void simulate(double seconds);
    /// Draw one frame (scene, overlays, panel) into the back buffer.
    void draw();
    /// What draw() would draw of view `view` (shapes, colours, contacts, spring), as a copy.
    FrameInput snapshot(int view = 0);
    /// The back buffer as an image (call after draw(), before presenting).
    Image capture();
    void present();

    /// Mouse interaction in window coordinates (pixels, top-left origin), as a person does it, in
    /// whichever view is under the cursor; side by side, the corresponding body of the other world
    /// is dragged or removed too.
    /// grab: picks the nearest shape under the cursor; true if it is a dynamic body (now dragged).
    bool grab(double x, double y);
    void dragTo(double x, double y);
    void release();
    /// Removes the body under the cursor if the scene lets it be removed (a brick).
    bool removeAt(double x, double y);
    /// The paper's downward push on the top object, for `seconds` of simulated time.
    void push(double seconds = 0.5);
    /// Adds a body of interaction().kind over the point under the cursor (key d), or in front of
    /// the camera flying along the cursor ray at `speed` m/s (key t, shift+right flick), placed by
    /// the view under the cursor. Side by side, the same body (shape, pose, velocity, name) is
    /// added to both worlds. Returns the new body of the view under the cursor; null when the
    /// cursor is on no view, or (drop) nothing is under it to drop onto.
    dBodyID dropAt(double x, double y);
    dBodyID throwAt(double x, double y, double speed);
    /// The body under the cursor, in the view under it, with its mass, velocities and contacts
    /// (the inspector window).
    std::optional<Inspection> inspectAt(double x, double y);
    Interaction& interaction() { return interaction_; }

    const OrbitCamera& camera() const { return camera_; }
    OrbitCamera& camera() { return camera_; }
    const SceneShapes& shapes() const { return shapes_; }
    const SpringDrag& drag() const { return drag_; }
    int windowWidth() const;
    int windowHeight() const;
    const FrameTimes& times() const { return times_; }

private:
    /// The second world of the side-by-side view.
    struct CompareWorld {
        std::unique_ptr<scenes::Scene> scene;
        SceneShapes shapes;
        SpringDrag drag;
    };
    std::unique_ptr<scenes::Scene> makeWorld(const std::string& name, scenes::Method method) const;
    /// (Re)makes the world(s) of scene `name` as the options say; `keepSettings` carries the
    /// current solver and contact settings over (a geom or view toggle is not a new scene).
    void buildWorlds(const std::string& name, bool keepSettings);
    void clearWindow();
    void render(const std::vector<FrameInput>& frames);
    void stepOnce();
    void refreshShapes();
    void refreshShapes(int view);
    SceneShapes& mutableShapes(int view) { return view == 0 ? shapes_ : compare_->shapes; }
    SpringDrag& mutableDrag(int view) { return view == 0 ? drag_ : compare_->drag; }
    /// The view under a window point, or -1 (the panel, a gap).
    int viewAt(double x, double y) const;
    Ray rayThrough(int view, double x, double y) const;
    /// The body of world `to` that is body `body` of world `from` (same index in bodies()).
    dBodyID correspondingBody(int from, dBodyID body, int to);
    /// Adds `spawn` to every world; returns the body added to world `view`.
    dBodyID addToWorlds(const Spawn& spawn, int view);
    dBodyID throwFrom(int view, double x, double y, double speed);
    /// With the inspector on: the body under the cursor and its twin, highlighted in each view.
    void findInspected();
    void drawOverlay();
    void drawVerdictPanel();
    void fitCamera();
    void drawPanel();
    void interactiveLoop(int frameLimit, bool vsync);
    void simulationLoop();
    void buildPanel();
    void headlessLoop();
    static void onMouseButton(GLFWwindow* window, int button, int action, int mods);
    static void onCursor(GLFWwindow* window, double x, double y);
    static void onScroll(GLFWwindow* window, double dx, double dy);
    static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);

    ViewerOptions options_;
    GLFWwindow* window_ = nullptr;
    bool imguiReady_ = false;
    std::unique_ptr<scenes::Scene> scene_;
    std::unique_ptr<CompareWorld> compare_;  // side by side only
    SceneShapes shapes_;
    OrbitCamera camera_;
    SpringDrag drag_;
    Renderer renderer_;
    double groundTile_ = 0.5;

    // Interactive mode: the simulation thread and the lock that guards the scene against it.
    std::mutex sceneMutex_;
    std::atomic<bool> stopSimulation_{false};

    // run state
    bool paused_ = false;
    bool stepRequested_ = false;
    double speed_ = 1.0;
    double accumulator_ = 0.0;
    double pushRemaining_ = 0.0;
    bool showContacts_ = true;
    bool showPanel_ = true;
    double normalLength_ = 0.1;
    double depthExaggeration_ = 10.0;
    int method_ = 0;
    FrameTimes times_;

    // what a drop or throw adds, the inspector and the debug drawing (wireframe, bounding boxes)
    Interaction interaction_;

    // mouse state for camera gestures
    FlickTracker flick_;
    enum class Gesture { None, Orbit, Pan, Drag, Flick } gesture_ = Gesture::None;
    double lastX_ = 0.0, lastY_ = 0.0;
    int gestureView_ = 0;  // the view a drag or flick began in: its viewport maps the cursor to rays
    std::vector<dBodyID> inspected_;  // per view, the inspector's body (null: none)
    bool contactsThrough_ = false;

    // live plots (last few seconds of each measure)
    struct Series {
        std::deque<float> values;
        void push(double v);
    };
    Series penetration_, alignment_, drift_, collisionMs_, solverMs_, contactCount_;
};

}  // namespace gdc::viewer
