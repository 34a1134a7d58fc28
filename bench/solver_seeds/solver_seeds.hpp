// The solver benchmark over seeds (issue 22, item 1): scenes that stress ODE's solvers (stacks,
// heavy on light, a pyramid, a brick wall, thin plates, hull stacks, composites, a 1000-box pile,
// card houses; cans, tins, logs and a pipe of ODE's dCylinder and dCapsule geoms), each run under
// dWorldQuickStep (10, 20, 50 iterations) and dWorldStep over many seeds (dRandSetSeed plus a
// small seeded jitter of the start poses, the same for every contender), with gdcontact, ODE's
// own colliders on dConvex shapes and ODE on dBox shapes side by side. Per run: whether it failed
// (the limits of failureLimits()), drift, contacts per step, collision and solver time per step,
// when every body fell asleep, ODE's messages. Besides, the cost of one step on identical body
// states (measureCost), which free-running worlds cannot give.
//
// The worlds are built by the scene library of samples/scenes (gdc::scenes::Scene: bodies of convex
// parts, dBox or dConvex, mass properties); the collision pass and the step are this file's own, so
// that their times hold nothing but collision and solver. Requires dInitODE2() first.
#pragma once

#include <gdcontact/ode.hpp>
#include <gdcontact/settings.hpp>

#include <ode/ode.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace gdc::solver_seeds {

// ---- contenders ----------------------------------------------------------------------------------
enum class ColliderKind {
    Gdcontact,  ///< gdc::ode::collide in the near callback, explicit settings; boxes as dBox geoms
    /// ODE's own colliders, boxes as dBox (dBoxBox, dBoxPlane); other hulls as dConvex. In the
    /// curved scenes (SceneSpec::curved) it is ODE's own answer on the scene's own geoms: dBox,
    /// dCylinder, dCapsule through dCollide, nothing installed.
    OdeBox,
    OdeConvex,  ///< ODE's own colliders, every shape a dConvex (libccd's one-point convex collider)
};

/// An experiment on the order the solver meets one geom pair's rows (docs/algorithm.md, "Column
/// and heap"): the contender's contacts of each pair are rearranged before they become joints.
/// The solver meets a pair's joints in the reverse of their creation (docs/algorithm.md, "Order");
/// every name below says the order the solver *meets* them in.
enum class RowOrder {
    AsIs,          ///< the collider's own order
    Reversed,      ///< the collider's array reversed
    DeepestFirst,  ///< by depth, deepest met first (stable)
    DeepestLast,   ///< by depth, deepest met last (stable)
    /// Deepest met first where one body of the pair is heavier than the other by the factor
    /// Contender::massRatio or more (or one side is static), else deepest met last.
    HeavyDeepestFirst,
    /// Deepest met first where the pair's deepest point is deeper than Contender::massRatio (m),
    /// else deepest met last.
    DeepDeepestFirst,
    // "+order=relative-deep-deepest-first[:FRACTION]" (the same, relative to the pair's size) is
    // gdcontact's own gdc::ContactOrder::DeepestFirstWhenLoaded: parseContender sets it, and the
    // FRACTION as loadedDepthFraction, in the gdc contender's settings; the rows stay AsIs.
};

struct Contender {
    std::string name;  ///< "gdc", "ode-box", "ode-convex", or e.g. "gdc:maxContacts=4"; "+order=NAME" appended
    ColliderKind kind = ColliderKind::Gdcontact;
    gdc::Settings settings = gdc::ode::defaultSettings();  ///< gdcontact's settings (Gdcontact only): "gdc" is install()'s
    RowOrder order = RowOrder::AsIs;  ///< "+order=as-is|reversed|deepest-first|deepest-last|heavy-deepest-first[:RATIO]"
    double massRatio = 4.0;           ///< HeavyDeepestFirst's threshold
};

/// "gdc", "ode-box", "ode-convex", or "gdc:NAME=VALUE[,NAME=VALUE...]" (settings variants, each
/// field by its name in gdc::Settings), any of them followed by "+order=NAME" (RowOrder). Throws
/// std::invalid_argument naming what is wrong.
Contender parseContender(const std::string& spec);

/// Sets the gdc::Settings field called `name` from `value` ("1e-6", "4", "true", "SeparatingAxis").
/// Every field of gdc::Settings is here: a new field needs one line. Throws std::invalid_argument
/// for an unknown name (listing the known ones) or a value that does not parse; the caller checks
/// the whole set with gdc::validate.
void setSetting(gdc::Settings& settings, const std::string& name, const std::string& value);
/// The names setSetting knows, in gdc::Settings's order.
std::vector<std::string> settingNames();

// ---- steppers ------------------------------------------------------------------------------------
struct Stepper {
    std::string name;  ///< "quick10", "quick20", "quick50", "world", each optionally with "/cfm=X/mu=X/maxc=N"
    bool quick = true;  ///< dWorldQuickStep (else dWorldStep)
    int iterations = 20;
    double cfm = sizeof(dReal) == sizeof(double) ? 1e-10 : 1e-5;  ///< SolverConstants::cfm unless "/cfm=X"
    double mu = 0.6;         ///< every contact's friction (SolverConstants::mu unless "/mu=X")
    int contactsAsked = 16;  ///< maxc of every collider call (SolverConstants::contactsAsked unless "/maxc=N")
};
std::vector<Stepper> allSteppers();
/// "quick10" | "quick20" | "quick50" | "world", optionally followed by solver variants
/// "/cfm=1e-5", "/mu=0.8", "/maxc=4" (any of them, in any order). Throws std::invalid_argument.
Stepper parseStepper(const std::string& name);

// ---- scenes --------------------------------------------------------------------------------------
struct SceneSpec {
    std::string name;
    std::string description;
    double duration = 3.0;       ///< simulated seconds of a run
    bool hasBoxes = true;        ///< every shape is a box: the ode-box contender applies
    bool heap = false;           ///< bodies fall into a heap: only the heap limits apply
    bool worldStep = true;       ///< dWorldStep is run (its step takes well under a second)
    std::string worldSkipReason; ///< why not, when not
    int defaultSeeds = 50;       ///< seeds of the default mode (scripts/run); the full mode runs ≥ 50 everywhere
    int defaultWorldSeeds = 50;  ///< seeds of the default mode under dWorldStep (big islands cost seconds per run)
    /// Heaps let go one by one: body k waits, disabled and out of the way, until k × this (s), then
    /// starts from its place (0: every body starts at once).
    double releaseInterval = 0.0;
    int fullSeeds = 50;          ///< seeds of the full mode (cheap scenes run more)
    /// Such a heap is taken as settled this long (s) after the last body was let go; from then on
    /// a body's horizontal displacement is its creep (the heap's limits).
    double settleTime = 0.0;
    /// Multiplies the start jitter (Jitter) for this scene: the columns use a new user's ±1 cm and
    /// ±0.1 rad about the vertical (10).
    double jitterScale = 1.0;
    /// ODE's auto-disable is never on in this scene, whatever RunOptions::sleep says (the columns:
    /// a world as a new user makes it; a column that sleeps can no longer fall).
    bool neverSleeps = false;
    /// The scene family the overview groups it in ("" for the classic scenes, "column", "heap").
    std::string family = "";
    /// Made of ODE's curved geoms (dCylinder, dCapsule) and boxes (issue 33). ode-box applies: ODE's
    /// own colliders on these same geoms, its own answer for them; ode-convex does not (it would
    /// turn only the boxes into dConvex). The collapse also counts a body that fell over or rolled
    /// away (collapseLimits()), which a can on its side or a log off the pile need.
    bool curved = false;
};
/// Every scene, in the report's order.
const std::vector<SceneSpec>& sceneSpecs();
const SceneSpec& findScene(const std::string& name);  ///< throws std::invalid_argument

/// The solver every scene runs with (besides the stepper): dt, ERP, CFM (ODE's default for its
/// precision: 1e-10 in double, 1e-5 in single, as dWorldCreate sets it), friction, contacts asked
/// per geom pair.
struct SolverConstants {
    static constexpr double dt = 0.01;          // s
    static constexpr double erp = 0.2;
    static constexpr double cfm = sizeof(dReal) == sizeof(double) ? 1e-10 : 1e-5;
    static constexpr double mu = 0.6;           // dContactApprox1 friction pyramid
    static constexpr int contactsAsked = 16;    // flags & 0xffff of every collider call
};

/// The start jitter of every dynamic body, from its seed (the same for every contender).
struct Jitter {
    static constexpr double position = 1e-3;  // m, uniform in ±, horizontal
    static constexpr double yaw = 0.01;       // rad, uniform in ±, about the vertical
    static constexpr double tilt = 0.002;     // rad, uniform in ±, about x and about y
};

// ---- failure limits ------------------------------------------------------------------------------
enum class Failure : int { None = 0, Exploded, Tunnelled, Flung, Drift, Tilt, Drop, Crashed, Creep };
const char* failureName(Failure failure);
/// One row per limit: its name, which scenes it applies to, and its rule (for the report).
struct FailureLimit {
    Failure failure;
    const char* scenes;
    const char* rule;
};
const std::vector<FailureLimit>& failureLimits();
/// The gross criterion beside the fine limits (SeedResult::collapsed): the structure fell. Scenes
/// where every contender crosses the fine limits still tell contenders apart by it.
const std::vector<FailureLimit>& collapseLimits();

// ---- one run -------------------------------------------------------------------------------------
struct RunOptions {
    bool sleep = true;           ///< ODE auto-disable on, default thresholds (else off; sleep time emulated)
    double durationScale = 1.0;  ///< multiplies every scene's duration
    double jitterScale = 1.0;    ///< multiplies the start jitter (Jitter)
    /// An experiment on the order QuickStep meets the rows *across* pairs (docs/algorithm.md, "Order
    /// across pairs"): before each step, every awake body of a joint-connected group but its lowest
    /// is disabled, so that ODE's island walk (depth-first from the first enabled body of the
    /// world's list: the newest) starts at the lowest body and meets the contacts from the ground
    /// up; the walk enables the rest again. It keeps ODE's auto-disable from sampling those bodies,
    /// so it requires sleep off.
    bool rootIslandsAtLowest = false;
};

/// RunOptions::rootIslandsAtLowest's step: per group of `bodies` connected by enabled joints (ODE's
/// islands, as its walk will find them), every awake body but the lowest is disabled, so that the
/// walk of the next dWorldQuickStep / dWorldStep starts there and enables the others again; a
/// group with no awake body is left asleep, as ODE would leave it. Public API only.
void rootIslandsAtLowest(const std::vector<dBodyID>& bodies);

/// What each contender hands the solver on identical body states (issue 35): runs `reference` free
/// to `time` (seed `seed`), copies that state into every contender's world, collides once and
/// writes to `out` (CSV) every contact row in the order dWorldQuickStep meets them (ODE's island
/// walk: the body list newest first, depth first, each body's joints newest first): the bodies
/// (−1: static), its row within the pair, position, depth, normal and ODE's first friction
/// direction (dPlaneSpace of the normal: the contacts set no dContactFDir1).
void compareContacts(const SceneSpec& scene, const Stepper& stepper, const std::vector<Contender>& contenders,
                     const Contender& reference, int seed, double time, const RunOptions& options, std::FILE* out);

/// The outcome of one scene × stepper × contender × seed. Plain data (workers share it through memory).
struct SeedResult {
    int done = 0;              ///< 1 once filled in
    int failure = 0;           ///< a Failure
    int collapsed = 0;         ///< 1: the structure fell (collapseLimits())
    double creep = 0;          ///< m, heaps let go one by one: max over bodies of the horizontal move since settling
    double failTime = -1;      ///< s, when the first limit was crossed (−1: none)
    double drift = 0;          ///< m, max over bodies of the horizontal distance from the start at the end
    double maxTilt = 0;        ///< rad, max over bodies and steps of the turn of its up axis since the start
    double contactsPerStep = 0;
    double collisionMs = 0;    ///< mean per step
    double solverMs = 0;       ///< mean per step
    double sleepTime = -1;     ///< s, first time every body was asleep (−1: never within the run)
    double asleepAtEnd = 0;    ///< fraction of bodies asleep at the end
    int messages = 0;          ///< ODE messages (dMessage) during the run
    int lcpErrors = 0;         ///< of them "LCP internal error"
    int invalidContacts = 0;   ///< contacts dropped: zero, non-unit or NaN normal (ODE's convex collider)
    int steps = 0;
    int bodies = 0;
};

SeedResult runSeed(const SceneSpec& scene, const Stepper& stepper, const Contender& contender, int seed,
                   const RunOptions& options = {});

/// ODE's messages are counted by a handler this installs (dSetMessageHandler); call once after
/// dInitODE2. Per process (each worker process counts its own).
void installMessageCounter();

// ---- cost on identical states --------------------------------------------------------------------
struct CostResult {
    double collisionMs = 0;  ///< mean per state, the fastest of the repetitions
    double solverMs = 0;
    double contacts = 0;     ///< mean contacts per state
    int states = 0;
};

/// Runs `reference` free (seed `seed`), samples the body states at `states` times spread over the
/// scene's duration, then for each state and each contender (interleaved, `repetitions` times)
/// copies the state into the contender's world (positions, orientations, velocities, every body
/// awake, dRandSetSeed(seed)), steps once untimed (so that the timed step finds its own world in the
/// caches, not the previous contender's), copies the state in again and times one collision pass
/// and one step. Returns one result per contender, in order.
std::vector<CostResult> measureCost(const SceneSpec& scene, const Stepper& stepper, const std::vector<Contender>& contenders,
                                    const Contender& reference, int seed, int states, int repetitions,
                                    const RunOptions& options = {});

}  // namespace gdc::solver_seeds
