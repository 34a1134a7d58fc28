// The paper's scenes (box drop, tower, brick wall, composites) as ODE worlds that the headless
// samples, the CTest scene tests and the interactive viewer all drive through this one API.
//
// A Scene owns its ODE world, space and bodies. step() runs one collision pass with the current
// contact method and one world step; the method can be switched between steps (the near-callback
// dispatches per pair, so nothing is installed into ODE globally). Each scene declares only its own
// bodies, shapes and solver settings; a scripted "user" (the tower builder, the brick remover) runs
// inside step() unless SceneOptions::scripted is false (the viewer then lets a person do it).
//
// Quality measures follow docs/measures.md ("Quality measures"): penetration error, alignment error,
// drift, twist, sag and oscillation, over the bodies the scene marks as measured, from the moment
// the scene declares them at rest (for the box drop: after 2 s).
//
// Requires dInitODE2() before a scene is made (the samples and tests do it once in main).
#pragma once

#include "geometry.hpp"

#include <gdcontact/ode.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>
#include <gdcontact/types.hpp>

#include <ode/ode.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace gdc::scenes {

/// Which code makes the contacts of a pair.
enum class Method {
    Gdcontact,  ///< gdc::ode::collide (the paper's method)
    Tracking,   ///< gdc::tracking persistent manifold (the paper's baseline)
    Ode,        ///< ODE 0.16.2's own colliders via dCollide
};
const char* methodName(Method method);                          // "gdc", "tracking", "ode"
std::optional<Method> parseMethod(const std::string& name);     // inverse of methodName

/// ODE's own default CFM for the precision it was built with, as dWorldCreate sets it: 1e-10 in
/// double precision, 1e-5 in single (a float Dantzig solver at 1e-10 meets degenerate pivots —
/// "LCP internal error" — on a heap of resting contacts, whichever collider made them).
inline constexpr double kOdeDefaultCfm = sizeof(dReal) == sizeof(double) ? 1e-10 : 1e-5;

/// The ODE solver a scene runs with. Every field maps to one ODE call.
struct SolverSettings {
    enum class Stepper { World, Quick };  ///< dWorldStep (exact LCP) / dWorldQuickStep (iterative)
    Stepper stepper = Stepper::World;
    int iterations = 20;          ///< dWorldSetQuickStepNumIterations (QuickStep only; count)
    double dt = 0.01;             ///< time step (s)
    double erp = 0.2;             ///< dWorldSetERP: fraction of penetration corrected per step
    double cfm = kOdeDefaultCfm;  ///< dWorldSetCFM: constraint force mixing (softness); ODE's default
    double mu = 0.6;              ///< Coulomb friction of every contact (dContactApprox1 pyramid)
    double surfaceLayer = 0.0;    ///< dWorldSetContactSurfaceLayer (m); penetration error is measured above it
    int maxContactsPerPair = 8;   ///< contacts asked of the collider for one pair of geoms
    double gravity = 9.81;        ///< m/s², along −z
};
const char* stepperName(SolverSettings::Stepper stepper);       // "world", "quick"

/// The solver of the stacking scenes (tower, composites): the exact LCP stepper, so that what the
/// bodies do is the contacts' doing and not an iterative solver's (docs/measures.md: absolute claims
/// under dWorldStep). Four contacts per pair of parts span a face contact and keep the LCP small
/// enough for interactive rates (a gear touches with up to nine parts); the same cap applies to
/// every method.
SolverSettings exactStackingSolver();

/// Construction options every scene understands. Scenes with a box-shaped body let `convexBoxes`
/// choose whether it is an ODE dBox or a dConvex of the same box (ODE's native collider differs).
struct SceneOptions {
    Method method = Method::Gdcontact;
    std::optional<SolverSettings> solver;  ///< absent: the scene's own settings
    bool convexBoxes = false;             ///< boxes as dConvex (gdc::ode::createConvex) instead of dBox
    bool scripted = true;                 ///< run the scene's scripted user (builder / remover / push)
    int bodies = 0;                       ///< big_world: how many bodies (0: the scene's own count)
};

/// One convex part of a body: an ODE geom and the polytope it is (in the geom's local frame).
struct Part {
    dGeomID geom = nullptr;
    std::shared_ptr<const gdc::Polytope> shape;
};

/// World position of a body's centre of mass.
gdc::Vec3 bodyPosition(dBodyID body);
/// The body's local +z axis in the world frame.
gdc::Vec3 bodyUpAxis(dBodyID body);
/// Angle (rad) between the body's local +z axis and the world's.
double bodyTilt(dBodyID body);
/// World height (z) of a vertex given in a part's geom frame.
double worldHeight(const Part& part, const gdc::Vec3& vertex);

/// A body of the scene as the viewer and the reports see it.
struct Body {
    dBodyID body = nullptr;
    std::string name;
    std::vector<Part> parts;             ///< one for a convex body, several for a composite
    std::array<float, 3> colour{0.7f, 0.7f, 0.7f};  ///< RGB hint in [0, 1]
    bool removable = false;              ///< removeBody() may take it out (bricks)
    bool pushable = false;               ///< applyPush() acts on it (the tower's top object)
    bool measured = true;                ///< counted in the quality measures
    double radius = 0.0;                 ///< bounding radius about the body's origin (m)
    gdc::Pose restPose;                  ///< pose when the scene declared it at rest
};

/// A contact made in the last step, in ODE's convention (normal from g2 into g1).
struct ContactSample {
    gdc::Vec3 position;
    gdc::Vec3 normal;
    double depth = 0.0;
    dGeomID g1 = nullptr, g2 = nullptr;
};

/// The quality measures at one step (units: m, rad, m/s). Drift, twist and sag are NaN until the
/// scene is at rest (they are measured from the rest poses); the others are kept from the start.
struct Measures {
    double time = 0.0;
    double penetration = 0.0;         ///< geometric: deepest overlap (exact, by SAT) of any pair the broad phase reports, above the surface layer
    double contactPenetration = 0.0;  ///< max over this step's contacts of max(0, depth − surface layer)
    double alignment = 0.0;           ///< max over measured bodies of the angle between its lowest face and the horizontal
    double drift = 0.0;               ///< max horizontal displacement since rest
    double twist = 0.0;               ///< max rotation about the vertical since rest
    double sag = 0.0;                 ///< max |vertical displacement| since rest
    double speed = 0.0;               ///< max over measured bodies of |v| + |ω|·radius (fastest point's speed bound)
    int contacts = 0;                 ///< contact joints made this step
    int invalidContacts = 0;          ///< contacts dropped because the collider gave a NaN or non-unit normal
    double collisionSeconds = 0.0;    ///< wall-clock time of the collision pass
    double solverSeconds = 0.0;       ///< wall-clock time of the world step
};

/// Max and mean of each measure after rest (oscillation = RMS of `speed`).
struct Summary {
    int samples = 0;
    double maxPenetration = 0, meanPenetration = 0;
    double maxContactPenetration = 0;
    double maxAlignment = 0, meanAlignment = 0;
    double maxDrift = 0, maxTwist = 0, maxSag = 0;
    double oscillation = 0;
    double meanCollisionSeconds = 0, meanSolverSeconds = 0;
};

/// The scene's own verdict on its task (the tests assert it, the report prints it).
struct Outcome {
    bool success = false;
    std::string text;                                  ///< one line, e.g. "wall stands; max displacement 0.3 mm"
    std::vector<std::pair<std::string, double>> values;  ///< named numbers behind the verdict
};

class Scene {
public:
    virtual ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    const std::string& name() const { return name_; }

    /// Destroys and rebuilds the world exactly as constructed (same method and solver settings).
    void reset();
    /// One collision pass with the current method, then one world step, then the script and the measures.
    void step();
    /// Runs until `seconds` of simulated time have passed since reset().
    void runUntil(double seconds);

    Method method() const { return method_; }
    /// Takes effect at the next step(); persistent tracking state is cleared.
    void setMethod(Method method);
    const SolverSettings& solver() const { return solver_; }
    /// Applies at the next step (ERP, CFM, stepper, iterations, dt, mu, ...).
    void setSolver(const SolverSettings& settings);
    /// gdcontact's own accuracy/speed settings, used by the gdcontact method (maxContacts is
    /// overridden by SolverSettings::maxContactsPerPair). Applies at the next step.
    const gdc::Settings& contactSettings() const { return contactSettings_; }
    void setContactSettings(const gdc::Settings& settings) { contactSettings_ = settings; }

    dWorldID world() const { return world_; }
    dSpaceID space() const { return space_; }
    const std::vector<Body>& bodies() const { return bodies_; }
    /// Static geoms (ground plane, walls) — for drawing.
    const std::vector<dGeomID>& staticGeoms() const { return staticGeoms_; }

    double time() const { return time_; }
    int stepCount() const { return steps_; }

    /// The paper's downward push on the top object (tower); no-op in scenes without a pushable body.
    /// Applies `newtons` downward at an off-centre point of the top face, for this step only.
    virtual void applyPush(double newtons);
    /// The push the scene's script uses (N); a sensible default for an interactive push.
    virtual double pushForce() const { return 0.0; }
    /// Removes a removable body (brick) and its geoms. Returns false if it is not one.
    bool removeBody(dBodyID body);
    /// Adds a dynamic body while the scene runs (a person dropping or throwing one in the viewer).
    /// Made as the scene makes its own (addBody), so it collides by whichever method the scene
    /// runs; it is removable, not counted in the quality measures, and starts with
    /// `linearVelocity` (m/s). reset() rebuilds the scene without it. Returns the new body.
    dBodyID spawnBody(const std::string& name, const std::vector<PlacedPart>& parts, double density,
                      const gdc::Pose& pose, const gdc::Vec3& linearVelocity, std::array<float, 3> colour);

    const std::vector<ContactSample>& lastContacts() const { return contacts_; }
    double lastCollisionSeconds() const { return current_.collisionSeconds; }
    double lastSolverSeconds() const { return current_.solverSeconds; }

    /// Is the scene past its settling phase (measures meaningful)?
    bool atRest() const { return atRest_; }
    /// A body left the world (non-finite or > 1 km away): stepping stopped, the outcome fails.
    bool exploded() const { return exploded_; }
    const Measures& measures() const { return current_; }
    const std::vector<Measures>& history() const { return history_; }
    Summary summary() const;
    virtual Outcome outcome() const = 0;
    /// Simulated seconds of a full run: the scene's script done and its effect observed.
    virtual double duration() const = 0;

    /// Extra per-step numbers of the scene (e.g. tower tilt); CSV columns after the measures.
    virtual std::vector<std::string> extraColumns() const { return {}; }
    const std::vector<std::vector<double>>& extraHistory() const { return extraHistory_; }

    /// Writes history() (+ extra columns) as CSV. Throws std::runtime_error if it cannot.
    void writeCsv(const std::string& path) const;

protected:
    Scene(std::string name, const SceneOptions& options, const SolverSettings& defaults);

    // --- for the concrete scenes ---
    /// Called by reset(): create the bodies into world()/space(). Must be deterministic.
    virtual void build() = 0;
    /// Called after every world step with the new time (the scripted user lives here).
    virtual void script() {}
    /// Per-step extra values (same order as extraColumns()).
    virtual std::vector<double> extraValues() const { return {}; }

    bool scripted() const { return options_.scripted; }
    bool convexBoxes() const { return options_.convexBoxes; }
    const SceneOptions& options() const { return options_; }

    /// For scenes of thousands of bodies (big_world), called in the constructor. The gdcontact
    /// method then collides through gdc::ode::spaceCollide (ODE's broad phase, gdcontact's narrow
    /// phase on setThreadCount's threads, with install()'s settings: contactSettings() are not
    /// used), and the geometric penetration measure is the deepest vertex below the ground plane
    /// (an exact separating-axis test per pair would cost more than the whole step).
    void setWholeStepCollision(bool enabled) { wholeStepCollision_ = enabled; }

    /// A dynamic body of convex parts, each placed at its offset in the composite's frame; `pose`
    /// places that frame in the world. The ODE body origin is the parts' common centre of mass
    /// (ODE requires it), inertia is summed over the parts (overlaps counted twice: parts of a
    /// composite may overlap). A part marked isBox becomes a dBox unless convexBoxes(); a cylinder or
    /// capsule part becomes a dCylinder / dCapsule with ODE's exact mass properties.
    Body& addBody(const std::string& name, const std::vector<PlacedPart>& parts, double density,
                  const gdc::Pose& pose, std::array<float, 3> colour);
    /// A box body: dBox unless convexBoxes(), then a dConvex of the same box.
    Body& addBox(const std::string& name, const gdc::Vec3& halfExtents, double density,
                 const gdc::Pose& pose, std::array<float, 3> colour);
    /// The ground: the plane z = 0. (The tracking baseline only knows polytopes; it sees the plane
    /// as a 4 m box under the body, top face in the plane, fixed while their contact lasts.)
    void addGroundPlane();
    /// A static triangle-mesh ground (dCreateTriMesh, identity pose): `vertices` in world
    /// coordinates, each triangle counter-clockwise seen from its front, fronts up, a height field
    /// (TerrainGround). The scene keeps the arrays ODE reads alive with the world. The geometric
    /// penetration measure of a body against it is TerrainGround::penetration; the tracking
    /// baseline (convex shapes only) leaves its pairs to ODE's trimesh colliders (dCollide), and
    /// the gdcontact method takes the pairs gdc::ode::handles (box, convex, capsule, cylinder).
    dGeomID addTerrain(std::vector<gdc::Vec3> vertices, std::vector<std::array<int, 3>> triangles);
    /// Declares the current poses as the rest poses; measures count from here.
    void markRest();
    Body* findBody(dBodyID body);

private:
    struct Impl;
    void destroyWorld();
    /// The ODE geom of a part (in space()): dCylinder, dCapsule, dBox, or a gdcontact dConvex.
    dGeomID createGeom(const PlacedPart& part);
    void applySolverSettings();
    static void nearCallback(void* data, dGeomID o1, dGeomID o2);
    void collidePair(dGeomID o1, dGeomID o2);
    void addContactJoints(dGeomID o1, dGeomID o2, const dContactGeom* contacts, int count);
    void addHeldContacts();
    void collideWholeStep();
    static void wholeStepHandler(void* data, dGeomID o1, dGeomID o2, dContactGeom* contacts, int count);
    double groundPenetration() const;
    void measure();

    std::string name_;
    SceneOptions options_;
    SolverSettings solver_;
    gdc::Settings contactSettings_ = gdc::ode::defaultSettings();  // as install() without settings
    Method method_;
    dWorldID world_ = nullptr;
    dSpaceID space_ = nullptr;
    dJointGroupID contactGroup_ = nullptr;
    std::vector<Body> bodies_;
    std::vector<dGeomID> staticGeoms_;
    std::vector<ContactSample> contacts_;
    double time_ = 0.0;
    int steps_ = 0;
    bool atRest_ = false;
    bool exploded_ = false;
    Measures current_;
    std::vector<Measures> history_;
    std::vector<std::vector<double>> extraHistory_;
    std::unique_ptr<Impl> impl_;  // per-step scratch, tracking cache, geom → part lookup
    bool wholeStepCollision_ = false;
};

/// The paper's scenes and the big world, in the report's order.
std::vector<std::string> sceneNames();
/// Scenes makeScene() builds besides: "barrels" (ODE's cylinders and capsules, issue 33) and
/// "terrain" (bodies on a triangle-mesh ground, issue 34). Kept out
/// of sceneNames(), which the report runs and the scene tests pin, until the report has them.
std::vector<std::string> extraSceneNames();
/// Every name makeScene() accepts: sceneNames(), then extraSceneNames() (the viewer lists these).
std::vector<std::string> allSceneNames();
/// Makes a scene by name; throws std::invalid_argument for an unknown name.
std::unique_ptr<Scene> makeScene(const std::string& name, const SceneOptions& options = {});

}  // namespace gdc::scenes
