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
constexpr double kPanelWidth = 340.0;  // pixels, margin included
constexpr double kSlowestFlick = 0.5;  // m/s: slower, a shift+right release is no throw
constexpr double kFastestThrow = 40.0;  // m/s: the throw speed slider's top
const scenes::Method kMethods[] = {scenes::Method::Gdcontact, scenes::Method::Tracking, scenes::Method::Ode};
const char* const kMethodLabels[] = {"gdcontact", "contact tracking", "ODE native"};

// The collider's own accuracy/speed settings (gdc::Settings), edited live.
void contactSettingsWidgets(scenes::Scene& scene) {
    gdc::Settings settings = scene.contactSettings();
    bool changed = false;
    float angle = float(settings.angularTolerance * 180.0 / M_PI);
    if (ImGui::SliderFloat("angular tol. (deg)", &angle, 0.0f, 15.0f, "%.2f")) {
        settings.angularTolerance = angle * M_PI / 180.0;
        changed = true;
    }
    float exponent = float(std::log10(settings.rayCastTolerance));
    if (ImGui::SliderFloat("ray-cast tol. (log10)", &exponent, -14.0f, -2.0f, "%.1f")) {
        settings.rayCastTolerance = std::pow(10.0, double(exponent));
        changed = true;
    }
    changed |= ImGui::SliderInt("GJK iterations", &settings.maxRayCastIterations, 4, 128);
    float margin = float(settings.margin * 1e3);
    if (ImGui::SliderFloat("margin (mm)", &margin, 0.0f, 10.0f, "%.2f")) {
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

void Viewer::loadScene(const std::string& name) {
    scenes::SceneOptions sceneOptions;
    sceneOptions.scripted = options_.scripted;
    if (options_.method) sceneOptions.method = *options_.method;
    drag_.forget();
    shapes_.clear();
    scene_ = scenes::makeScene(name, sceneOptions);
    options_.scene = name;
    method_ = int(std::find(std::begin(kMethods), std::end(kMethods), scene_->method()) - std::begin(kMethods));
    accumulator_ = 0.0;
    pushRemaining_ = 0.0;
    for (Series* s : {&penetration_, &alignment_, &drift_, &collisionMs_, &solverMs_, &contactCount_}) s->values.clear();
    refreshShapes();
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

void Viewer::fitCamera() {
    Vec3 low, high;
    if (!shapes_.bounds(low, high)) return;
    camera_.frame(low, high);
    // Centre the bodies in the part of the window the panel leaves free.
    if (showPanel_) camera_.pan(-0.5 * kPanelWidth / std::max(windowHeight(), 1), 0.0);
}

void Viewer::refreshShapes() {
    // ODE keeps no way to read a dConvex back: the scene knows its bodies' parts, the gdcontact
    // adapter knows every hull made by gdc::ode::createConvex (static geoms included).
    std::unordered_map<dGeomID, std::shared_ptr<const Polytope>> polytopes;
    for (const auto& body : scene_->bodies())
        for (const auto& part : body.parts) polytopes[part.geom] = part.shape;
    shapes_.setPolytopeLookup([polytopes = std::move(polytopes)](dGeomID geom) {
        auto it = polytopes.find(geom);
        return it != polytopes.end() ? it->second : gdc::ode::polytopeOf(geom);
    });
    shapes_.update(scene_->space());
}

void Viewer::stepOnce() {
    const auto start = Clock::now();
    drag_.apply();
    if (pushRemaining_ > 0.0) {
        scene_->applyPush(scene_->pushForce());
        pushRemaining_ -= scene_->solver().dt;
    }
    scene_->step();
    times_.simulateSeconds += secondsSince(start);
    times_.collisionSeconds += scene_->lastCollisionSeconds();
    times_.solverSeconds += scene_->lastSolverSeconds();
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
    const Ray ray = camera_.rayThroughPixel(x, y, windowWidth(), windowHeight());
    const auto hit = shapes_.pick(ray);
    if (!hit) return false;
    const DrawShape& shape = shapes_.shapes()[hit->shape];
    if (shape.body == nullptr) return false;
    drag_.begin(shape.body, hit->point, hit->distance);
    return true;
}

void Viewer::dragTo(double x, double y) {
    drag_.moveTo(camera_.rayThroughPixel(x, y, windowWidth(), windowHeight()));
}

void Viewer::release() { drag_.end(); }

bool Viewer::removeAt(double x, double y) {
    refreshShapes();
    const auto hit = shapes_.pick(camera_.rayThroughPixel(x, y, windowWidth(), windowHeight()));
    if (!hit) return false;
    dBodyID body = shapes_.shapes()[hit->shape].body;
    if (body == nullptr) return false;
    if (drag_.body() == body) drag_.forget();
    shapes_.clear();  // the body's geoms are destroyed; ODE may hand their addresses out again
    const bool removed = scene_->removeBody(body);
    refreshShapes();
    return removed;
}

void Viewer::push(double seconds) { pushRemaining_ = std::max(pushRemaining_, seconds); }

dBodyID Viewer::dropAt(double x, double y) {
    refreshShapes();
    // Within ten times the camera's distance: farther, the body would land out of sight.
    dBodyID body = interaction_.drop(*scene_, shapes_, camera_.rayThroughPixel(x, y, windowWidth(), windowHeight()),
                                     10.0 * camera_.distance());
    refreshShapes();
    return body;
}

dBodyID Viewer::throwAt(double x, double y, double speed) {
    dBodyID body = interaction_.throwAlong(*scene_, camera_.rayThroughPixel(x, y, windowWidth(), windowHeight()), speed);
    refreshShapes();
    return body;
}

std::optional<Inspection> Viewer::inspectAt(double x, double y) {
    refreshShapes();
    return inspectAlong(*scene_, shapes_, camera_.rayThroughPixel(x, y, windowWidth(), windowHeight()));
}

FrameInput Viewer::snapshot() {
    refreshShapes();
    FrameInput in;
    in.camera = &camera_;
    glfwGetFramebufferSize(window_, &in.width, &in.height);
    in.shapes = &shapes_.shapes();
    std::unordered_map<dBodyID, Colour> colours;
    for (const auto& body : scene_->bodies()) colours[body.body] = body.colour;
    for (const auto& shape : shapes_.shapes()) {
        auto it = shape.body ? colours.find(shape.body) : colours.end();
        in.colours.push_back(it != colours.end() ? it->second : Colour{0.62f, 0.62f, 0.64f});
        in.highlighted.push_back(shape.body != nullptr && shape.body == drag_.body());
    }
    if (showContacts_)
        for (const auto& c : scene_->lastContacts()) in.contacts.push_back({c.position, c.normal, c.depth});
    in.normalLength = normalLength_;
    in.depthExaggeration = depthExaggeration_;
    in.groundTile = groundTile_;
    if (drag_.active()) in.spring = std::make_pair(drag_.anchorWorld(), drag_.target());
    return in;
}

void Viewer::buildPanel() {
    ImGui_ImplOpenGL2_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (showPanel_) drawPanel();
    if (interaction_.inspector)
        interaction_.inspectorWindow(*scene_, shapes_, camera_, lastX_, lastY_, windowWidth(), windowHeight());
    ImGui::Render();  // only builds vertex lists; the GL calls come in RenderDrawData
}

void Viewer::draw() {
    const FrameInput in = snapshot();
    buildPanel();
    std::vector<DrawShape> planes;
    renderer_.render(rendererInput(in, interaction_.debug, planes));
    drawDebugOverlay(in, interaction_.debug);
    ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
}

Image Viewer::capture() {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    glReadBuffer(GL_BACK);
    return readFramebuffer(width, height);
}

void Viewer::present() { glfwSwapBuffers(window_); }

void Viewer::drawPanel() {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth - 10, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("gdcontact");

    // Scene choice
    const auto names = scenes::sceneNames();
    if (ImGui::BeginCombo("scene", options_.scene.c_str())) {
        for (const auto& name : names)
            if (ImGui::Selectable(name.c_str(), name == options_.scene)) {
                loadScene(name);
                ImGui::EndCombo();
                ImGui::End();
                return;  // the old scene's state is gone; draw the panel afresh next frame
            }
        ImGui::EndCombo();
    }
    ImGui::Text("t = %.2f s   steps %d   %s", scene_->time(), scene_->stepCount(), scene_->atRest() ? "at rest" : "settling");

    // Run control
    if (ImGui::Button(paused_ ? "run" : "pause")) paused_ = !paused_;
    ImGui::SameLine();
    if (ImGui::Button("step")) stepRequested_ = true;
    ImGui::SameLine();
    if (ImGui::Button("reset")) {
        drag_.forget();
        shapes_.clear();
        scene_->reset();
        refreshShapes();
    }
    ImGui::SameLine();
    bool anyPushable = false;
    for (const auto& body : scene_->bodies()) anyPushable |= body.pushable;
    if (!anyPushable) ImGui::BeginDisabled();
    if (ImGui::Button("push")) push();
    if (!anyPushable) ImGui::EndDisabled();
    float speed = float(speed_);
    if (ImGui::SliderFloat("speed", &speed, 0.05f, 4.0f, "%.2f x", ImGuiSliderFlags_Logarithmic)) speed_ = speed;

    // Contact method and the settings that trade speed for accuracy
    if (ImGui::Combo("contacts by", &method_, kMethodLabels, IM_ARRAYSIZE(kMethodLabels)))
        scene_->setMethod(kMethods[method_]);
    scenes::SolverSettings solver = scene_->solver();
    bool changed = false;
    changed |= ImGui::SliderInt("max contacts", &solver.maxContactsPerPair, 1, 16);
    int stepper = solver.stepper == scenes::SolverSettings::Stepper::World ? 0 : 1;
    const char* steppers[] = {"dWorldStep (exact LCP)", "dWorldQuickStep"};
    if (ImGui::Combo("solver", &stepper, steppers, 2)) {
        solver.stepper = stepper == 0 ? scenes::SolverSettings::Stepper::World : scenes::SolverSettings::Stepper::Quick;
        changed = true;
    }
    if (stepper == 1) changed |= ImGui::SliderInt("iterations", &solver.iterations, 1, 100);
    float mu = float(solver.mu), erp = float(solver.erp), layer = float(solver.surfaceLayer * 1e3);
    if (ImGui::SliderFloat("friction", &mu, 0.0f, 2.0f)) { solver.mu = mu; changed = true; }
    if (ImGui::SliderFloat("ERP", &erp, 0.0f, 1.0f)) { solver.erp = erp; changed = true; }
    if (ImGui::SliderFloat("surface layer (mm)", &layer, 0.0f, 5.0f)) { solver.surfaceLayer = layer * 1e-3; changed = true; }
    if (changed) scene_->setSolver(solver);
    if (kMethods[method_] == scenes::Method::Gdcontact) contactSettingsWidgets(*scene_);

    // Overlays
    ImGui::Checkbox("contacts", &showContacts_);
    ImGui::SameLine();
    float exaggeration = float(depthExaggeration_);
    ImGui::SetNextItemWidth(120);
    if (ImGui::SliderFloat("depth x", &exaggeration, 1.0f, 100.0f, "%.0f", ImGuiSliderFlags_Logarithmic))
        depthExaggeration_ = exaggeration;

    // Measures
    const scenes::Measures& m = scene_->measures();
    ImGui::Text("contacts %d   collision %.2f ms   solver %.2f ms", m.contacts, m.collisionSeconds * 1e3, m.solverSeconds * 1e3);
    auto plot = [](const char* label, const Series& s, const char* unit) {
        std::vector<float> v(s.values.begin(), s.values.end());
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "%.3g %s", v.empty() ? 0.0 : double(v.back()), unit);
        ImGui::PlotLines(label, v.data(), int(v.size()), 0, overlay, 0.0f, FLT_MAX, ImVec2(0, 40));
    };
    plot("penetration", penetration_, "mm");
    plot("alignment", alignment_, "deg");
    plot("drift", drift_, "mm");
    plot("collision", collisionMs_, "ms");
    plot("solver", solverMs_, "ms");
    interaction_.panelSection();
    ImGui::TextDisabled("drag: pull body   ctrl+click: remove brick");
    ImGui::TextDisabled("right drag: orbit   middle: pan   wheel: zoom");
    ImGui::TextDisabled("space pause  s step  r reset  p push");
    ImGui::TextDisabled("c contacts  f fit view  h hide panel");
    ImGui::End();
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
        FrameInput in;
        const auto frameStart = Clock::now();
        {
            std::lock_guard<std::mutex> lock(sceneMutex_);
            glfwPollEvents();  // input callbacks touch the scene: under the lock
            in = snapshot();
            buildPanel();      // panel widgets change settings: under the lock
        }
        const auto drawStart = Clock::now();
        times_.snapshotSeconds += std::chrono::duration<double>(drawStart - frameStart).count();
        // Drawing reads only the copies made above.
        std::vector<DrawShape> planes;
        renderer_.render(rendererInput(in, interaction_.debug, planes));
        drawDebugOverlay(in, interaction_.debug);
        ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
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
    std::printf("scene %s, method %s, %dx%d%s%s: %d frames in %.2f s = %.1f fps\n", options_.scene.c_str(),
                scenes::methodName(scene_->method()), options_.width, options_.height, showPanel_ ? ", panel" : "",
                showContacts_ ? ", contacts" : "", t.frames, t.wallSeconds, t.frames / wall);
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
            const double speed = flickSpeed(v.camera_, v.windowHeight(), v.flick_.velocity());
            if (speed >= kSlowestFlick) v.throwAt(x, y, std::min(speed, kFastestThrow));
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
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT && (mods & GLFW_MOD_SHIFT)) {
        v.gesture_ = Gesture::Flick;  // a throw: the cursor's speed at release sets the body's
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
    const double height = std::max(v.windowHeight(), 1);
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
        case GLFW_KEY_R:
            v.drag_.forget();
            v.shapes_.clear();
            v.scene_->reset();
            v.refreshShapes();
            break;
        case GLFW_KEY_P: v.push(); break;
        case GLFW_KEY_C: v.showContacts_ = !v.showContacts_; break;
        case GLFW_KEY_H: v.showPanel_ = !v.showPanel_; break;
        case GLFW_KEY_F: v.fitCamera(); break;
        case GLFW_KEY_D: v.dropAt(v.lastX_, v.lastY_); break;
        case GLFW_KEY_T: v.throwAt(v.lastX_, v.lastY_, v.interaction_.throwSpeed); break;
        case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: case GLFW_KEY_4:
            v.interaction_.kind = kSpawnKinds[key - GLFW_KEY_1];
            break;
        case GLFW_KEY_I: v.interaction_.inspector = !v.interaction_.inspector; break;
        case GLFW_KEY_W: v.interaction_.debug.wireframe = !v.interaction_.debug.wireframe; break;
        case GLFW_KEY_B: v.interaction_.debug.bounds = !v.interaction_.debug.bounds; break;
        default: break;
    }
}

}  // namespace gdc::viewer
