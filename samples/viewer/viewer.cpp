#include "viewer.hpp"

#include <gdcontact/ode.hpp>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>
#include <unordered_map>

namespace gdc::viewer {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

constexpr double kHeadlessFrameSeconds = 1.0 / 60.0;  // simulated time per headless frame
constexpr double kMaxBacklogSteps = 5.0;  // behind by more, the simulation runs slower than real time
constexpr std::size_t kPlotSamples = 400;
// The panel is a fixed column at the left of the window; the views take the rest. Wide enough for
// a 160-pixel label column beside every slider (ImGui's default 35 % cut labels off).
constexpr int kPanelWidth = 400;     // pixels
constexpr float kLabelColumn = 160.0f;
constexpr int kViewGap = 2;          // pixels between the two views side by side
constexpr double kSlowestFlick = 0.5;  // m/s: slower, a shift+right release is no throw
constexpr double kFastestThrow = 40.0;  // m/s: the throw speed slider's top
const scenes::Method kMethods[] = {scenes::Method::Gdcontact, scenes::Method::Tracking, scenes::Method::Ode};
const char* const kMethodLabels[] = {"gdcontact", "contact tracking", "ODE native"};

int methodIndex(scenes::Method method) {
    return int(std::find(std::begin(kMethods), std::end(kMethods), method) - std::begin(kMethods));
}

// Verdict colours: green pass, red fail, light grey while the scene settles.
ImU32 verdictColour(Verdict::State state) {
    switch (state) {
        case Verdict::State::Pass: return IM_COL32(90, 210, 100, 255);
        case Verdict::State::Fail: return IM_COL32(240, 90, 80, 255);
        case Verdict::State::Pending: break;
    }
    return IM_COL32(215, 215, 215, 255);
}

// A small per-body change of brightness (±12 %, by index, the same in both worlds) so that
// neighbours of one colour — the bricks of a course — are told apart.
Colour tinted(const Colour& colour, std::size_t index) {
    const float factor = 0.88f + 0.06f * float((index * 3) % 5);
    Colour out;
    for (int c = 0; c < 3; ++c) out[c] = std::min(1.0f, colour[c] * factor);
    return out;
}

// The collider's own accuracy/speed settings (gdc::Settings), edited live.
void contactSettingsWidgets(scenes::Scene& scene) {
    gdc::Settings settings = scene.contactSettings();
    bool changed = false;
    float angle = float(settings.angularTolerance * 180.0 / M_PI);
    if (ImGui::SliderFloat("angular tol.", &angle, 0.0f, 15.0f, "%.2f deg")) {
        settings.angularTolerance = angle * M_PI / 180.0;
        changed = true;
    }
    // The tolerance spans twelve decades: the slider moves its log10; it is relative to the pair's size.
    float exponent = float(std::log10(settings.rayCastTolerance));
    if (ImGui::SliderFloat("ray-cast tol. (log10)", &exponent, -14.0f, -3.0f, "10^%.1f x pair size")) {
        settings.rayCastTolerance = std::pow(10.0, double(exponent));
        changed = true;
    }
    changed |= ImGui::SliderInt("GJK iteration cap", &settings.maxRayCastIterations, 4, 128, "%d iterations");
    float margin = float(settings.margin * 1e3);
    if (ImGui::SliderFloat("margin", &margin, 0.0f, 10.0f, "%.2f mm")) {
        settings.margin = margin * 1e-3;
        changed = true;
    }
    if (changed) scene.setContactSettings(settings);
}

Viewer* self(GLFWwindow* window) { return static_cast<Viewer*>(glfwGetWindowUserPointer(window)); }

void reportGlfwError(int code, const char* text) { std::fprintf(stderr, "GLFW error %d: %s\n", code, text); }

}  // namespace

void Viewer::Series::push(double v) {
    values.push_back(std::isfinite(v) ? float(v) : 0.0f);
    if (values.size() > kPlotSamples) values.pop_front();
}

Viewer::Viewer(const ViewerOptions& options) : options_(options), camera_(Vec3::UnitZ()) {
    showPanel_ = options.panel;
    showContacts_ = options.contacts;
    contactsThrough_ = options.contactsThrough;
    if (options.width < 64 || options.height < 64) throw std::invalid_argument("window must be at least 64×64 pixels");
    // Before any window: a bad file is reported as such, with or without an X server.
    if (!options.obj.empty() &&
        !interaction_.loadObj(options.obj, options.objHull ? scenes::ObjLayout::Hull : scenes::ObjLayout::PartPerObject,
                              options.objScale))
        throw std::runtime_error(interaction_.objStatus());
    glfwSetErrorCallback(reportGlfwError);
    if (!glfwInit()) throw std::runtime_error("cannot initialise GLFW (no X server? set DISPLAY or run under xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SAMPLES, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 8);  // the ground shadows darken each pixel once (Renderer)
    window_ = glfwCreateWindow(options.width, options.height, "gdcontact viewer", nullptr, nullptr);
    if (window_ == nullptr) {
        glfwTerminate();
        throw std::runtime_error("cannot create an OpenGL 2.1 window");
    }
    glfwMakeContextCurrent(window_);
    glfwSetWindowUserPointer(window_, this);
    // Our callbacks first: ImGui's backend chains to them after updating its own state.
    glfwSetMouseButtonCallback(window_, onMouseButton);
    glfwSetCursorPosCallback(window_, onCursor);
    glfwSetScrollCallback(window_, onScroll);
    glfwSetKeyCallback(window_, onKey);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini littering the working directory
    ImGui::StyleColorsDark();
    // Anti-aliased shapes double the panel's triangles for edge fringes; a software rasteriser
    // pays for every one of them each frame.
    ImGui::GetStyle().AntiAliasedLines = false;
    ImGui::GetStyle().AntiAliasedFill = false;
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL2_Init();
    imguiReady_ = true;

    loadScene(options.scene);
}

Viewer::~Viewer() {
    scene_.reset();
    if (imguiReady_) {
        ImGui_ImplOpenGL2_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

int Viewer::windowWidth() const {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    return w;
}

int Viewer::windowHeight() const {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    return h;
}

std::unique_ptr<scenes::Scene> Viewer::makeWorld(const std::string& name, scenes::Method method) const {
    scenes::SceneOptions sceneOptions;
    sceneOptions.method = method;
    sceneOptions.scripted = options_.scripted;
    sceneOptions.convexBoxes = options_.convexBoxes;
    return scenes::makeScene(name, sceneOptions);
}

void Viewer::buildWorlds(const std::string& name, bool keepSettings) {
    std::optional<scenes::SolverSettings> solver;
    std::optional<gdc::Settings> contactSettings;
    if (keepSettings && scene_) {
        solver = scene_->solver();
        contactSettings = scene_->contactSettings();
    }
    // Made before the old worlds go, so an unknown name leaves the viewer as it was.
    auto primary = makeWorld(name, options_.method.value_or(scenes::Method::Gdcontact));
    std::unique_ptr<CompareWorld> second;
    if (options_.sideBySide) {
        second = std::make_unique<CompareWorld>();
        second->scene = makeWorld(name, options_.compareMethod);
    }
    drag_.forget();
    shapes_.clear();
    inspected_.clear();  // bodies of the old worlds
    scene_ = std::move(primary);
    compare_ = std::move(second);
    options_.scene = name;
    for (int view = 0; view < viewCount(); ++view) {
        if (solver) scene(view).setSolver(*solver);
        if (contactSettings) scene(view).setContactSettings(*contactSettings);
    }
    method_ = methodIndex(scene_->method());
    accumulator_ = 0.0;
    pushRemaining_ = 0.0;
    for (Series* s : {&penetration_, &alignment_, &drift_, &collisionMs_, &solverMs_, &contactCount_}) s->values.clear();
    refreshShapes();
}

void Viewer::loadScene(const std::string& name) {
    buildWorlds(name, false);
    camera_ = OrbitCamera(Vec3::UnitZ());
    fitCamera();
    Vec3 low, high;
    if (shapes_.bounds(low, high)) {
        const double extent = (high - low).maxCoeff();
        groundTile_ = std::pow(10.0, std::round(std::log10(std::max(extent, 1e-3) / 6.0)));
    }
    // Normals drawn about as long as a typical body is wide: visible, not a hedgehog.
    std::vector<double> radii;
    for (const auto& body : scene_->bodies())
        if (body.radius > 0.0) radii.push_back(body.radius);
    if (!radii.empty()) {
        std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
        normalLength_ = 0.5 * radii[radii.size() / 2];
    }
}

void Viewer::setSideBySide(bool on) {
    options_.sideBySide = on;
    buildWorlds(options_.scene, true);
    fitCamera();  // the view's shape changed
}

void Viewer::setCompareMethod(scenes::Method method) {
    options_.compareMethod = method;
    if (compare_) compare_->scene->setMethod(method);
}

void Viewer::setConvexBoxes(bool convex) {
    options_.convexBoxes = convex;
    buildWorlds(options_.scene, true);
}

void Viewer::resetScene() {
    inspected_.clear();
    for (int view = 0; view < viewCount(); ++view) {
        mutableDrag(view).forget();
        mutableShapes(view).clear();
        scene(view).reset();
    }
    pushRemaining_ = 0.0;
    refreshShapes();
}

Viewport Viewer::viewport(int view) const {
    const int width = windowWidth(), height = windowHeight();
    const int left = showPanel_ ? std::clamp(kPanelWidth, 0, std::max(width - 64, 0)) : 0;
    const Viewport area{left, 0, width - left, height};
    if (!compare_) return area;
    const int half = std::max((area.width - kViewGap) / 2, 1);
    return view == 0 ? Viewport{area.x, 0, half, height} : Viewport{area.x + area.width - half, 0, half, height};
}

int Viewer::viewAt(double x, double y) const {
    for (int view = 0; view < viewCount(); ++view)
        if (viewport(view).contains(x, y)) return view;
    return -1;
}

Ray Viewer::rayThrough(int view, double x, double y) const {
    const Viewport v = viewport(view);
    return camera_.rayThroughPixel(x - v.x, y - v.y, v.width, v.height);
}

dBodyID Viewer::correspondingBody(int from, dBodyID body, int to) {
    const auto& source = scene(from).bodies();
    const auto& target = scene(to).bodies();
    for (std::size_t i = 0; i < source.size(); ++i)
        if (source[i].body == body)
            return i < target.size() && target[i].name == source[i].name ? target[i].body : nullptr;
    return nullptr;
}

const char* Viewer::verdictLabel(Verdict::State state) {
    switch (state) {
        case Verdict::State::Pass: return "PASS";
        case Verdict::State::Fail: return "FAIL";
        case Verdict::State::Pending: break;
    }
    // The scenes' checks read "does NOT ..." until they are at rest: say that it is not a verdict yet.
    return "settling, not judged yet";
}

Verdict Viewer::verdict(int view) {
    scenes::Scene& s = scene(view);
    const scenes::Outcome outcome = s.outcome();
    Verdict result;
    result.text = outcome.text;
    // Every scene's check requires it at rest; before that a failure means "not yet", not "no".
    if (s.exploded() || s.atRest()) result.state = outcome.success ? Verdict::State::Pass : Verdict::State::Fail;
    return result;
}

void Viewer::fitCamera() {
    Vec3 low, high;
    if (!shapes_.bounds(low, high)) return;
    // The ground the bodies stand or land on belongs in the picture (the box drop starts 1 m up).
    for (const auto& shape : shapes_.shapes())
        if (shape.isPlane() && shape.planeNormal.z() > 0.99) low.z() = std::min(low.z(), shape.planeOffset);
    camera_.frame(low, high);
    // frame() fits the vertical field of view; a view narrower than tall needs more distance.
    const Viewport v = viewport(0);
    const double aspect = double(v.width) / std::max(v.height, 1);
    if (aspect < 1.0) camera_.zoom(1.0 / aspect);
}

void Viewer::refreshShapes() {
    for (int view = 0; view < viewCount(); ++view) refreshShapes(view);
}

void Viewer::refreshShapes(int view) {
    // ODE keeps no way to read a dConvex back: the scene knows its bodies' parts, the gdcontact
    // adapter knows every hull made by gdc::ode::createConvex (static geoms included).
    std::unordered_map<dGeomID, std::shared_ptr<const Polytope>> polytopes;
    for (const auto& body : scene(view).bodies())
        for (const auto& part : body.parts) polytopes[part.geom] = part.shape;
    SceneShapes& shapes = mutableShapes(view);
    shapes.setPolytopeLookup([polytopes = std::move(polytopes)](dGeomID geom) {
        auto it = polytopes.find(geom);
        return it != polytopes.end() ? it->second : gdc::ode::polytopeOf(geom);
    });
    shapes.update(scene(view).space());
}

void Viewer::stepOnce() {
    const auto start = Clock::now();
    // The user's actions reach every world alike; only the contact method differs.
    for (int view = 0; view < viewCount(); ++view) {
        drag(view).apply();
        if (pushRemaining_ > 0.0) scene(view).applyPush(scene(view).pushForce());
    }
    if (pushRemaining_ > 0.0) pushRemaining_ -= scene_->solver().dt;
    for (int view = 0; view < viewCount(); ++view) {
        scene(view).step();
        times_.collisionSeconds += scene(view).lastCollisionSeconds();
        times_.solverSeconds += scene(view).lastSolverSeconds();
    }
    times_.simulateSeconds += secondsSince(start);
    times_.simulatedSeconds += scene_->solver().dt;
    ++times_.steps;
    const scenes::Measures& m = scene_->measures();
    penetration_.push(m.penetration * 1e3);
    alignment_.push(m.alignment * 180.0 / M_PI);
    drift_.push(m.drift * 1e3);
    collisionMs_.push(m.collisionSeconds * 1e3);
    solverMs_.push(m.solverSeconds * 1e3);
    contactCount_.push(m.contacts);
}

void Viewer::simulate(double seconds) {
    const double dt = scene_->solver().dt;
    const int steps = std::max(seconds > 0.0 ? 1 : 0, int(std::lround(seconds / dt)));
    for (int i = 0; i < steps; ++i) stepOnce();
}

bool Viewer::grab(double x, double y) {
    refreshShapes();
    const int view = viewAt(x, y);
    if (view < 0) return false;
    const Ray ray = rayThrough(view, x, y);
    const auto hit = shapes(view).pick(ray);
    if (!hit) return false;
    dBodyID body = shapes(view).shapes()[hit->shape].body;
    if (body == nullptr) return false;
    mutableDrag(view).begin(body, hit->point, hit->distance);
    gestureView_ = view;
    // The other world's twin is held at the same point of the body, pulled towards the same cursor
    // point (the views share the camera, so one cursor ray serves both).
    dVector3 local;
    dBodyGetPosRelPoint(body, hit->point.x(), hit->point.y(), hit->point.z(), local);
    for (int other = 0; other < viewCount(); ++other) {
        if (other == view) continue;
        dBodyID twin = correspondingBody(view, body, other);
        if (twin == nullptr) {
            mutableDrag(other).forget();
            continue;
        }
        dVector3 world;
        dBodyGetRelPointPos(twin, local[0], local[1], local[2], world);
        mutableDrag(other).begin(twin, Vec3(world[0], world[1], world[2]), hit->distance);
    }
    return true;
}

void Viewer::dragTo(double x, double y) {
    const Ray ray = rayThrough(gestureView_, x, y);
    for (int view = 0; view < viewCount(); ++view) mutableDrag(view).moveTo(ray);
}

void Viewer::release() {
    for (int view = 0; view < viewCount(); ++view) mutableDrag(view).end();
}

bool Viewer::removeAt(double x, double y) {
    refreshShapes();
    const int view = viewAt(x, y);
    if (view < 0) return false;
    const auto hit = shapes(view).pick(rayThrough(view, x, y));
    if (!hit) return false;
    dBodyID body = shapes(view).shapes()[hit->shape].body;
    if (body == nullptr) return false;
    std::vector<dBodyID> targets(viewCount(), nullptr);  // found before any removal shifts the indices
    for (int other = 0; other < viewCount(); ++other)
        targets[other] = other == view ? body : correspondingBody(view, body, other);
    bool removed = false;
    for (int other = 0; other < viewCount(); ++other) {
        if (targets[other] == nullptr) continue;
        if (drag(other).body() == targets[other]) mutableDrag(other).forget();
        mutableShapes(other).clear();  // the body's geoms are destroyed; ODE may hand their addresses out again
        if (other < int(inspected_.size()) && inspected_[other] == targets[other]) inspected_[other] = nullptr;
        const bool gone = scene(other).removeBody(targets[other]);
        if (other == view) removed = gone;
    }
    refreshShapes();
    return removed;
}

void Viewer::push(double seconds) { pushRemaining_ = std::max(pushRemaining_, seconds); }

dBodyID Viewer::addToWorlds(const Spawn& spawn, int view) {
    // Appended to every world alike: the new body has the same index in each world's bodies(), and
    // the same name, so correspondingBody() pairs it as it pairs the scene's own.
    dBodyID added = nullptr;
    for (int world = 0; world < viewCount(); ++world) {
        dBodyID body = addSpawn(scene(world), spawn);
        if (world == view) added = body;
    }
    refreshShapes();
    return added;
}

dBodyID Viewer::dropAt(double x, double y) {
    refreshShapes();
    const int view = viewAt(x, y);
    if (view < 0) return nullptr;
    // Placed on what the view under the cursor shows (side by side, the other world gets the body
    // at the same pose, whatever its bodies have done since). Within ten times the camera's
    // distance: farther, the body would land out of sight.
    const auto spawn = interaction_.planDrop(scene(view), shapes(view), rayThrough(view, x, y), 10.0 * camera_.distance());
    return spawn ? addToWorlds(*spawn, view) : nullptr;
}

dBodyID Viewer::throwAt(double x, double y, double speed) {
    const int view = viewAt(x, y);
    return view < 0 ? nullptr : throwFrom(view, x, y, speed);
}

dBodyID Viewer::throwFrom(int view, double x, double y, double speed) {
    return addToWorlds(interaction_.planThrow(scene(view), rayThrough(view, x, y), speed), view);
}

std::optional<Inspection> Viewer::inspectAt(double x, double y) {
    refreshShapes();
    const int view = viewAt(x, y);
    if (view < 0) return std::nullopt;
    return inspectAlong(scene(view), shapes(view), rayThrough(view, x, y));
}

void Viewer::findInspected() {
    inspected_.assign(viewCount(), nullptr);
    if (!interaction_.inspector) return;
    const int view = viewAt(lastX_, lastY_);
    if (view < 0) return;
    refreshShapes();
    const auto hit = shapes(view).pick(rayThrough(view, lastX_, lastY_));
    if (!hit || shapes(view).shapes()[hit->shape].body == nullptr) return;
    const dBodyID body = shapes(view).shapes()[hit->shape].body;
    for (int other = 0; other < viewCount(); ++other)
        inspected_[other] = other == view ? body : correspondingBody(view, body, other);
}

FrameInput Viewer::snapshot(int view) {
    refreshShapes(view);
    const SceneShapes& drawn = shapes(view);
    const SpringDrag& spring = drag(view);
    const dBodyID inspected = view < int(inspected_.size()) ? inspected_[view] : nullptr;
    FrameInput in;
    in.camera = &camera_;
    // Window coordinates (top-left origin) to framebuffer pixels (bottom-left origin, maybe HiDPI).
    int framebufferWidth = 0, framebufferHeight = 0;
    glfwGetFramebufferSize(window_, &framebufferWidth, &framebufferHeight);
    const double sx = double(framebufferWidth) / std::max(windowWidth(), 1);
    const double sy = double(framebufferHeight) / std::max(windowHeight(), 1);
    const Viewport v = viewport(view);
    in.x = int(std::lround(v.x * sx));
    in.width = int(std::lround(v.width * sx));
    in.height = int(std::lround(v.height * sy));
    in.y = framebufferHeight - int(std::lround((v.y + v.height) * sy));
    in.shapes = &drawn.shapes();
    std::unordered_map<dBodyID, Colour> colours;
    const auto& bodies = scene(view).bodies();
    for (std::size_t i = 0; i < bodies.size(); ++i) colours[bodies[i].body] = tinted(bodies[i].colour, i);
    for (const auto& shape : drawn.shapes()) {
        auto it = shape.body ? colours.find(shape.body) : colours.end();
        in.colours.push_back(it != colours.end() ? it->second : Colour{0.62f, 0.62f, 0.64f});
        // The dragged body, and with the inspector on the inspected one (in each view its own twin).
        in.highlighted.push_back(shape.body != nullptr && (shape.body == spring.body() || shape.body == inspected));
    }
    if (showContacts_)
        for (const auto& c : scene(view).lastContacts()) in.contacts.push_back({c.position, c.normal, c.depth});
    in.contactsThrough = contactsThrough_;
    in.normalLength = normalLength_;
    in.depthExaggeration = depthExaggeration_;
    in.groundTile = groundTile_;
    if (spring.active()) in.spring = std::make_pair(spring.anchorWorld(), spring.target());
    return in;
}

void Viewer::buildPanel() {
    ImGui_ImplOpenGL2_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (showPanel_) drawPanel();
    if (options_.labels) drawOverlay();
    findInspected();
    if (interaction_.inspector) {
        const int view = viewAt(lastX_, lastY_);
        if (view < 0) {
            interaction_.inspectorWindow(nullptr, shapes_, camera_, 0.0, 0.0, 1, 1);
        } else {
            const Viewport v = viewport(view);
            std::string label;
            if (viewCount() > 1)
                label = std::string(view == 0 ? "left view, " : "right view, ") +
                        kMethodLabels[methodIndex(scene(view).method())];
            interaction_.inspectorWindow(&scene(view), shapes(view), camera_, lastX_ - v.x, lastY_ - v.y, v.width,
                                         v.height, label);
        }
    }
    ImGui::Render();  // only builds vertex lists; the GL calls come in RenderDrawData
}

void Viewer::draw() {
    buildPanel();  // first: its widgets may rebuild or drop a world the snapshots would point into
    std::vector<FrameInput> frames;
    for (int view = 0; view < viewCount(); ++view) frames.push_back(snapshot(view));
    render(frames);
}

void Viewer::clearWindow() {
    // The gap between the views and the panel's column are no view's: clear them once per frame.
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    glDisable(GL_SCISSOR_TEST);
    glViewport(0, 0, width, height);
    glClearColor(0.16f, 0.16f, 0.18f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void Viewer::render(const std::vector<FrameInput>& frames) {
    clearWindow();
    // Each view as the renderer draws it, then its debug overlay (wireframe, bounding boxes) with
    // that view's world, camera and viewport; the panel over all of them.
    std::vector<DrawShape> planes;
    for (const FrameInput& frame : frames) {
        renderer_.render(rendererInput(frame, interaction_.debug, planes));
        drawDebugOverlay(frame, interaction_.debug);
    }
    ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
}

Image Viewer::capture() {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    glReadBuffer(GL_BACK);
    return readFramebuffer(width, height);
}

void Viewer::present() { glfwSwapBuffers(window_); }

void Viewer::drawVerdictPanel() {
    for (int view = 0; view < viewCount(); ++view) {
        const Verdict v = verdict(view);
        ImGui::PushStyleColor(ImGuiCol_Text, verdictColour(v.state));
        ImGui::TextWrapped("%s%s: %s - %s", viewCount() > 1 ? (view == 0 ? "left, " : "right, ") : "",
                           kMethodLabels[methodIndex(scene(view).method())], verdictLabel(v.state), v.text.c_str());
        ImGui::PopStyleColor();
    }
}

void Viewer::drawPanel() {
    // A fixed column left of the views: nothing of the picture hides behind it.
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(float(kPanelWidth), float(windowHeight())), ImGuiCond_Always);
    ImGui::Begin("gdcontact", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-kLabelColumn);  // negative: the widget leaves this much room for its label

    // Scene choice and what is compared
    const auto names = scenes::allSceneNames();
    if (ImGui::BeginCombo("scene", options_.scene.c_str())) {
        for (const auto& name : names)
            if (ImGui::Selectable(name.c_str(), name == options_.scene)) {
                loadScene(name);
                ImGui::EndCombo();
                ImGui::PopItemWidth();
                ImGui::End();
                return;  // the old scene's state is gone; draw the panel afresh next frame
            }
        ImGui::EndCombo();
    }
    bool sideBySide = this->sideBySide();
    if (ImGui::Checkbox("side by side (v)", &sideBySide)) setSideBySide(sideBySide);
    if (sideBySide) {
        int second = methodIndex(options_.compareMethod);
        if (ImGui::Combo("right view", &second, kMethodLabels, IM_ARRAYSIZE(kMethodLabels)))
            setCompareMethod(kMethods[second]);
    }
    bool convex = options_.convexBoxes;
    if (ImGui::Checkbox("boxes as dConvex (g)", &convex)) setConvexBoxes(convex);
    ImGui::SameLine();
    bool scripted = options_.scripted;
    if (ImGui::Checkbox("scripted user", &scripted)) {
        options_.scripted = scripted;
        buildWorlds(options_.scene, true);
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("The scene's own builder, remover and push act (its check assumes them); rebuilds");

    ImGui::Text("t = %.2f s   steps %d", scene_->time(), scene_->stepCount());
    drawVerdictPanel();

    // Run control
    if (ImGui::Button(paused_ ? "run" : "pause")) paused_ = !paused_;
    ImGui::SameLine();
    if (ImGui::Button("step")) stepRequested_ = true;
    ImGui::SameLine();
    if (ImGui::Button("reset")) resetScene();
    ImGui::SameLine();
    bool anyPushable = false;
    for (const auto& body : scene_->bodies()) anyPushable |= body.pushable;
    if (!anyPushable) ImGui::BeginDisabled();
    if (ImGui::Button("push")) push();
    if (!anyPushable) ImGui::EndDisabled();
    float speed = float(speed_);
    if (ImGui::SliderFloat("speed", &speed, 0.05f, 4.0f, "%.2f x real time", ImGuiSliderFlags_Logarithmic)) speed_ = speed;

    // Contact method and the settings that trade speed for accuracy (solver: both worlds alike)
    if (ImGui::Combo(sideBySide ? "left view" : "contacts by", &method_, kMethodLabels, IM_ARRAYSIZE(kMethodLabels))) {
        scene_->setMethod(kMethods[method_]);
        options_.method = kMethods[method_];
    }
    scenes::SolverSettings solver = scene_->solver();
    bool changed = false;
    changed |= ImGui::SliderInt("max contacts", &solver.maxContactsPerPair, 1, 16, "%d per pair");
    int stepper = solver.stepper == scenes::SolverSettings::Stepper::World ? 0 : 1;
    const char* steppers[] = {"dWorldStep (exact LCP)", "dWorldQuickStep"};
    if (ImGui::Combo("solver", &stepper, steppers, 2)) {
        solver.stepper = stepper == 0 ? scenes::SolverSettings::Stepper::World : scenes::SolverSettings::Stepper::Quick;
        changed = true;
    }
    if (stepper == 1) changed |= ImGui::SliderInt("QuickStep", &solver.iterations, 1, 100, "%d iterations");
    float mu = float(solver.mu), erp = float(solver.erp), layer = float(solver.surfaceLayer * 1e3);
    if (ImGui::SliderFloat("friction", &mu, 0.0f, 2.0f, "mu = %.2f (ratio)")) { solver.mu = mu; changed = true; }
    if (ImGui::SliderFloat("ERP", &erp, 0.0f, 1.0f, "%.2f of depth / step")) { solver.erp = erp; changed = true; }
    if (ImGui::SliderFloat("surface layer", &layer, 0.0f, 5.0f, "%.2f mm")) { solver.surfaceLayer = layer * 1e-3; changed = true; }
    if (changed)
        for (int view = 0; view < viewCount(); ++view) scene(view).setSolver(solver);
    bool anyGdcontact = false;
    for (int view = 0; view < viewCount(); ++view) anyGdcontact |= scene(view).method() == scenes::Method::Gdcontact;
    if (anyGdcontact) {
        contactSettingsWidgets(*scene_);
        for (int view = 1; view < viewCount(); ++view) scene(view).setContactSettings(scene_->contactSettings());
    }

    // Overlays
    ImGui::Checkbox("contacts (c)", &showContacts_);
    ImGui::SameLine();
    ImGui::Checkbox("through bodies (x)", &contactsThrough_);
    float exaggeration = float(depthExaggeration_);
    if (ImGui::SliderFloat("depth drawn", &exaggeration, 1.0f, 100.0f, "x%.0f (magnified)", ImGuiSliderFlags_Logarithmic))
        depthExaggeration_ = exaggeration;

    // Measures (left view)
    const scenes::Measures& m = scene_->measures();
    ImGui::Text("contacts %d", m.contacts);
    ImGui::Text("collision %.2f ms, solver %.2f ms", m.collisionSeconds * 1e3, m.solverSeconds * 1e3);
    if (compare_) {
        const scenes::Measures& r = compare_->scene->measures();
        ImGui::TextDisabled("right view: contacts %d, collision %.2f ms", r.contacts, r.collisionSeconds * 1e3);
    }
    auto plot = [](const char* label, const Series& s, const char* unit) {
        std::vector<float> v(s.values.begin(), s.values.end());
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "%.3g %s", v.empty() ? 0.0 : double(v.back()), unit);
        ImGui::PlotLines(label, v.data(), int(v.size()), 0, overlay, 0.0f, FLT_MAX, ImVec2(0, 34));
    };
    plot("penetration", penetration_, "mm");
    plot("alignment", alignment_, "deg");
    plot("drift", drift_, "mm");
    plot("collision", collisionMs_, "ms");
    plot("solver", solverMs_, "ms");
    interaction_.panelSection();
    ImGui::TextDisabled("drag: pull body   ctrl+click: remove brick/added");
    ImGui::TextDisabled("right drag: orbit   middle: pan   wheel: zoom");
    ImGui::TextDisabled("space pause  s step  r reset  p push  f fit");
    ImGui::TextDisabled("v side by side  g dBox/dConvex  h panel");
    ImGui::TextDisabled("c contacts  x contacts through bodies");
    ImGui::PopItemWidth();
    ImGui::End();
}

void Viewer::drawOverlay() {
    // Drawn into ImGui's background list: over the 3-D views, under the panel.
    ImDrawList* list = ImGui::GetBackgroundDrawList();
    const float pad = 6.0f;
    for (int view = 0; view < viewCount(); ++view) {
        const Viewport v = viewport(view);
        const Verdict verdict = this->verdict(view);
        char title[128];
        std::snprintf(title, sizeof title, "%s, boxes as %s", kMethodLabels[methodIndex(scene(view).method())],
                      options_.convexBoxes ? "dConvex" : "dBox");
        char line[400];
        std::snprintf(line, sizeof line, "%s: %s", verdictLabel(verdict.state), verdict.text.c_str());
        const float wrap = std::max(float(v.width) - 4.0f * pad, 40.0f);
        const ImVec2 titleSize = ImGui::CalcTextSize(title);
        const ImVec2 lineSize = ImGui::CalcTextSize(line, nullptr, false, wrap);
        const ImVec2 corner(float(v.x) + pad, float(v.y) + pad);
        list->AddRectFilled(corner, ImVec2(corner.x + std::max(titleSize.x, lineSize.x) + 2 * pad,
                                           corner.y + titleSize.y + lineSize.y + 2 * pad),
                            IM_COL32(0, 0, 0, 150), 3.0f);
        list->AddText(ImVec2(corner.x + pad, corner.y + pad), IM_COL32(255, 255, 255, 255), title);
        list->AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(corner.x + pad, corner.y + pad + titleSize.y),
                      verdictColour(verdict.state), line, nullptr, wrap);
    }
    if (!showContacts_) return;
    // The contact legend, once, at the foot of the first view.
    const Viewport v = viewport(0);
    const float h = ImGui::GetFontSize();
    char depthText[64], scaleText[64];
    std::snprintf(depthText, sizeof depthText, "touching ... %.0f mm deep", 5.0);
    std::snprintf(scaleText, sizeof scaleText, "depth x%.0f", depthExaggeration_);
    const char* normalText = contactsThrough_ ? "normal   (through bodies)" : "normal";
    const float bar = 48.0f, swatch = 18.0f;
    const float width = bar + ImGui::CalcTextSize(depthText).x + swatch + ImGui::CalcTextSize(normalText).x +
                        swatch + ImGui::CalcTextSize(scaleText).x + 8 * pad;
    const ImVec2 corner(float(v.x) + pad, float(v.y + v.height) - h - 3 * pad);
    list->AddRectFilled(corner, ImVec2(corner.x + width, corner.y + h + 2 * pad), IM_COL32(0, 0, 0, 150), 3.0f);
    float x = corner.x + pad;
    const float y = corner.y + pad, mid = y + 0.5f * h;
    // The same ramp as the renderer: green (touching) to red (5 mm deep, FrameInput::depthForRed).
    list->AddRectFilledMultiColor(ImVec2(x, y + 2), ImVec2(x + bar, y + h - 2), IM_COL32(0, 255, 25, 255),
                                  IM_COL32(255, 0, 25, 255), IM_COL32(255, 0, 25, 255), IM_COL32(0, 255, 25, 255));
    x += bar + pad;
    list->AddText(ImVec2(x, y), IM_COL32(255, 255, 255, 255), depthText);
    x += ImGui::CalcTextSize(depthText).x + 2 * pad;
    list->AddLine(ImVec2(x, mid), ImVec2(x + swatch, mid), IM_COL32(255, 217, 25, 255), 2.0f);
    x += swatch + pad;
    list->AddText(ImVec2(x, y), IM_COL32(255, 255, 255, 255), normalText);
    x += ImGui::CalcTextSize(normalText).x + 2 * pad;
    list->AddLine(ImVec2(x, mid), ImVec2(x + swatch, mid), IM_COL32(255, 25, 153, 255), 2.0f);
    x += swatch + pad;
    list->AddText(ImVec2(x, y), IM_COL32(255, 255, 255, 255), scaleText);
}

void Viewer::simulationLoop() {
    auto last = Clock::now();
    while (!stopSimulation_) {
        double wait = 0.0;
        {
            std::lock_guard<std::mutex> lock(sceneMutex_);
            const auto now = Clock::now();
            const double elapsed = std::min(std::chrono::duration<double>(now - last).count(), 0.25);
            last = now;
            const double dt = scene_->solver().dt;
            if (!paused_) accumulator_ += elapsed * speed_;
            if (stepRequested_) {
                stepOnce();
                stepRequested_ = false;
            }
            if (!paused_ && accumulator_ >= dt) {
                stepOnce();
                accumulator_ -= dt;
                // Too slow to keep up: forget the backlog (the simulation slows down) rather
                // than spend ever longer catching up.
                accumulator_ = std::min(accumulator_, kMaxBacklogSteps * dt);
            }
            wait = paused_ ? 0.005 : std::max(0.0, (dt - accumulator_) / std::max(speed_, 1e-3));
        }
        // One step per lock: the window thread gets its turn between steps.
        if (wait > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(std::min(wait, 0.005)));
        else std::this_thread::yield();
    }
}

void Viewer::interactiveLoop(int frameLimit, bool vsync) {
    glfwSwapInterval(vsync ? 1 : 0);
    const auto begin = Clock::now();
    stopSimulation_ = false;
    std::thread simulation([this] { simulationLoop(); });
    int frames = 0;
    while (!glfwWindowShouldClose(window_) && (frameLimit <= 0 || frames < frameLimit)) {
        std::vector<FrameInput> views;
        const auto frameStart = Clock::now();
        {
            std::lock_guard<std::mutex> lock(sceneMutex_);
            glfwPollEvents();  // input callbacks touch the scene: under the lock
            buildPanel();      // panel widgets change settings (may rebuild the worlds): under the lock, first
            for (int view = 0; view < viewCount(); ++view) views.push_back(snapshot(view));
        }
        const auto drawStart = Clock::now();
        times_.snapshotSeconds += std::chrono::duration<double>(drawStart - frameStart).count();
        // Drawing reads only the copies made above.
        render(views);
        present();
        times_.drawSeconds += secondsSince(drawStart);
        ++frames;
    }
    stopSimulation_ = true;
    simulation.join();
    times_.frames += frames;
    times_.wallSeconds += secondsSince(begin);
}

void Viewer::headlessLoop() {
    const auto begin = Clock::now();
    for (int frame = 0; frame < options_.frames; ++frame) {
        glfwPollEvents();
        // Whole steps per frame, carried over exactly, so the result does not depend on speed.
        accumulator_ += kHeadlessFrameSeconds;
        const double dt = scene_->solver().dt;
        while (accumulator_ >= dt - 1e-12) {
            stepOnce();
            accumulator_ -= dt;
        }
        const auto drawStart = Clock::now();
        draw();
        if (frame + 1 < options_.frames) present();
        times_.drawSeconds += secondsSince(drawStart);
    }
    times_.frames += options_.frames;
    times_.wallSeconds += secondsSince(begin);
}

int Viewer::run() {
    if (options_.frames <= 0) {
        interactiveLoop(0, true);
        return 0;
    }
    if (options_.realtime) {
        interactiveLoop(options_.frames - 1, false);
        const auto start = Clock::now();
        draw();  // the last frame, kept in the back buffer for the screenshot
        times_.wallSeconds += secondsSince(start);
        ++times_.frames;
    } else {
        headlessLoop();
    }
    if (!options_.screenshot.empty()) {
        if (options_.fit) {
            fitCamera();
            draw();
        }
        writePng(capture(), options_.screenshot);
    }
    const FrameTimes& t = times_;
    const double wall = std::max(t.wallSeconds, 1e-9);
    const int frames = std::max(t.frames, 1);
    std::printf("scene %s, method %s%s%s, boxes %s, %dx%d%s%s: %d frames in %.2f s = %.1f fps\n",
                options_.scene.c_str(), scenes::methodName(scene_->method()), compare_ ? " beside " : "",
                compare_ ? scenes::methodName(compare_->scene->method()) : "", options_.convexBoxes ? "convex" : "box",
                options_.width, options_.height, showPanel_ ? ", panel" : "", showContacts_ ? ", contacts" : "",
                t.frames, t.wallSeconds, t.frames / wall);
    for (int view = 0; view < viewCount(); ++view) {
        const Verdict v = verdict(view);
        std::printf("verdict %s at t = %.2f s: %s: %s\n", scenes::methodName(scene(view).method()), scene(view).time(),
                    verdictLabel(v.state), v.text.c_str());
    }
    std::printf("per frame: snapshot+panel %.2f ms, draw+swap %.2f ms\n", 1e3 * t.snapshotSeconds / frames,
                1e3 * t.drawSeconds / frames);
    std::printf("simulation: %d steps = %.2f s simulated (%.2fx real time); %.2f ms per step "
                "(collision %.2f ms, solver %.2f ms)\n",
                t.steps, t.simulatedSeconds, t.simulatedSeconds / wall, 1e3 * t.simulateSeconds / std::max(t.steps, 1),
                1e3 * t.collisionSeconds / std::max(t.steps, 1), 1e3 * t.solverSeconds / std::max(t.steps, 1));
    return 0;
}

// --- input -------------------------------------------------------------------------------------

void Viewer::onMouseButton(GLFWwindow* window, int button, int action, int mods) {
    Viewer& v = *self(window);
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    v.lastX_ = x;
    v.lastY_ = y;
    if (action == GLFW_RELEASE) {
        if (v.gesture_ == Gesture::Drag) v.release();
        if (v.gesture_ == Gesture::Flick) {
            v.flick_.move(x, y, glfwGetTime());
            // A release without motion is no throw; a wild flick is held to the panel's top speed.
            // From the view the flick began in (side by side: into both worlds), wherever it ends.
            const double speed = flickSpeed(v.camera_, v.viewport(v.gestureView_).height, v.flick_.velocity());
            if (speed >= kSlowestFlick) v.throwFrom(v.gestureView_, x, y, std::min(speed, kFastestThrow));
            v.flick_.end();
        }
        v.gesture_ = Gesture::None;
        return;
    }
    if (v.imguiReady_ && ImGui::GetIO().WantCaptureMouse) return;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        if (mods & (GLFW_MOD_CONTROL | GLFW_MOD_SHIFT)) {
            v.removeAt(x, y);
        } else {
            v.gesture_ = v.grab(x, y) ? Gesture::Drag : Gesture::Orbit;
        }
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT && (mods & GLFW_MOD_SHIFT) && v.viewAt(x, y) >= 0) {
        v.gesture_ = Gesture::Flick;  // a throw: the cursor's speed at release sets the body's
        v.gestureView_ = v.viewAt(x, y);
        v.flick_.begin(x, y, glfwGetTime());
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
        v.gesture_ = Gesture::Orbit;
    } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
        v.gesture_ = Gesture::Pan;
    }
}

void Viewer::onCursor(GLFWwindow* window, double x, double y) {
    Viewer& v = *self(window);
    const double dx = x - v.lastX_, dy = y - v.lastY_;
    v.lastX_ = x;
    v.lastY_ = y;
    const double height = std::max(v.viewport(0).height, 1);
    switch (v.gesture_) {
        case Gesture::Orbit: v.camera_.orbit(-3.0 * dx / height, 3.0 * dy / height); break;
        case Gesture::Pan: v.camera_.pan(-dx / height, dy / height); break;
        case Gesture::Drag: v.dragTo(x, y); break;
        case Gesture::Flick: v.flick_.move(x, y, glfwGetTime()); break;
        case Gesture::None: break;
    }
}

void Viewer::onScroll(GLFWwindow* window, double, double dy) {
    Viewer& v = *self(window);
    if (v.imguiReady_ && ImGui::GetIO().WantCaptureMouse) return;
    v.camera_.zoom(std::pow(0.9, dy));
}

void Viewer::onKey(GLFWwindow* window, int key, int, int action, int) {
    Viewer& v = *self(window);
    if (action != GLFW_PRESS || (v.imguiReady_ && ImGui::GetIO().WantCaptureKeyboard)) return;
    switch (key) {
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
        case GLFW_KEY_SPACE: v.paused_ = !v.paused_; break;
        case GLFW_KEY_S: v.stepRequested_ = true; break;
        case GLFW_KEY_R: v.resetScene(); break;
        case GLFW_KEY_V: v.setSideBySide(!v.sideBySide()); break;
        case GLFW_KEY_G: v.setConvexBoxes(!v.convexBoxes()); break;
        case GLFW_KEY_X: v.contactsThrough_ = !v.contactsThrough_; break;  // x-ray: contacts through bodies
        case GLFW_KEY_P: v.push(); break;
        case GLFW_KEY_C: v.showContacts_ = !v.showContacts_; break;
        case GLFW_KEY_H: v.showPanel_ = !v.showPanel_; break;
        case GLFW_KEY_F: v.fitCamera(); break;
        case GLFW_KEY_D: v.dropAt(v.lastX_, v.lastY_); break;
        case GLFW_KEY_T: v.throwAt(v.lastX_, v.lastY_, v.interaction_.throwSpeed); break;
        case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: case GLFW_KEY_4: case GLFW_KEY_5: case GLFW_KEY_6:
            v.interaction_.kind = kSpawnKinds[key - GLFW_KEY_1];
            break;
        case GLFW_KEY_I: v.interaction_.inspector = !v.interaction_.inspector; break;
        case GLFW_KEY_W: v.interaction_.debug.wireframe = !v.interaction_.debug.wireframe; break;
        case GLFW_KEY_B: v.interaction_.debug.bounds = !v.interaction_.debug.bounds; break;
        default: break;
    }
}

}  // namespace gdc::viewer
