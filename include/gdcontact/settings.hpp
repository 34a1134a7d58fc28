// Every tunable of gdcontact, with its unit, the trade-off it controls and the bounds
// gdc::validate checks (install() and gdcInstall refuse settings outside them).
#pragma once

#include <gdcontact/export.hpp>

namespace gdc {

struct Settings;

/// Checks every field of `settings` against the bounds stated at the field. Throws InvalidInput
/// naming the first field out of bounds, its value and its bounds. NaN is out of every bound.
GDCONTACT_API void validate(const Settings& settings);

/// The order in which the solver meets one pair's contacts (Settings::contactOrder), by depth.
/// ODE's dJointAttach puts each new contact joint at the head of its bodies' joint lists and the
/// island walk follows those lists, so dWorldQuickStep meets a pair's contacts in the REVERSE of
/// the order a near callback creates them from dCollide's array; the ODE adapter writes its array
/// so that the solver meets them in the order named here. (The core's own array, gdc::collide,
/// is always in the order of importance: the deepest point first, then each point that adds the
/// most support, so that every prefix is the best set of its length.)
enum class ContactOrder {
    /// The solver meets the shallowest point first and the deepest last (the adapter's array is
    /// deepest first, as gdcontact wrote it before DeepestFirstWhenLoaded became the default): the
    /// least drift and twist in stacks of equal bodies; a column of light bodies under a heavy one
    /// collapses more often than with ODE's dBox colliders.
    DeepestLast,
    /// The solver meets the deepest point first and the shallowest last: resting piles fall
    /// asleep a little sooner, tall stacks drift more (still less than with ODE's dBox colliders);
    /// a column carrying a heavy body stands far more often.
    DeepestFirst,
    /// DeepestFirst where the pair is loaded — its deepest point deeper than
    /// Settings::loadedDepthFraction times the pair's size (the larger of the two shapes'
    /// diameters, twice the bounding radius; a plane or a mesh has none) — and DeepestLast
    /// elsewhere (default). Under dWorldQuickStep a resting pair sinks to a depth its load, ERP,
    /// CFM and the iterations set, not its size: a pair a hundredth of its size deep carries a load
    /// the solver's cut-off sweep cannot settle (a heavy body on a column of light ones), and met
    /// deepest first it holds — the loaded columns collapse far less often than with DeepestLast or
    /// ODE's dBox colliders — while stacks, walls, thin plates and hulls, which rest far shallower,
    /// keep DeepestLast's rows and its small drift (docs/algorithm.md, "The contact set the solver
    /// gets").
    DeepestFirstWhenLoaded,
};

/// How the contact normal is found (stage 1). The paper's method is GrowthDistance; the others
/// exist to measure the speed/accuracy trade against it.
enum class NormalMethod {
    GrowthDistance,  ///< GJK ray cast on A − B along the line through the contraction points (paper)
    /// The exact minimum-translation normal: a separating-axis test over the face normals of both
    /// bodies and the edge pairs whose Gauss-map arcs cross. Exact for any pose (no overhang
    /// check needed), but its cost grows with (edges of A) × (edges of B): fine for boxes and small
    /// hulls, slow for large ones.
    SeparatingAxis,
};

struct Settings {
    /// Stage 1 — GJK ray-cast convergence, as a fraction of the pair's size (sum of the two
    /// bounding radii; unitless). Smaller: a more exact normal and hit point, a few more GJK
    /// iterations. Relative, so a scene behaves the same at 1 mm and 1 km.
    /// Bounds [1e-15, 1e-3]: below 1e-15 it asks for less than double rounding on a pair's size
    /// (the ray cast would only run into maxRayCastIterations); above 1e-3 the normal and the
    /// hit point are off by a visible part of the shapes.
    double rayCastTolerance = 1e-10;

    /// Stage 1 — cap on GJK ray-cast iterations (count). Reached only on grazing rays or huge
    /// hulls; the best normal so far is used. Lower: bounded worst-case time, possibly a coarser normal.
    /// Bounds [1, 10000]: at least one iteration; beyond 10000 a grazing ray costs milliseconds
    /// per pair while the normal stopped improving long before (converged rays take ~10).
    int maxRayCastIterations = 64;

    /// Stage 2 — Gauss-map angular tolerance (radians). A face whose normal is within this angle
    /// of the contact normal is taken as the contact feature (face > edge > vertex). Larger: flat
    /// resting contacts are recognised earlier (stabler stacks) at the price of reporting a face
    /// for a slightly tilted body (its far points then carry negative depth and are dropped).
    /// Bounds [0, 0.5] rad: 0 recognises only exactly aligned faces; above 0.5 rad (≈ 29°) a
    /// face far from the contact normal would be taken as the contact feature, and most of its
    /// points dropped as negative depth — ODE would get one or two points for a tilted body.
    double angularTolerance = 0.05;  // ≈ 2.9°

    /// Stage 3 — contacts are kept where the shapes overlap by at least −margin (metres, the
    /// scene's length unit). 0: only touching/overlapping points. Positive: speculative contacts
    /// for points that are about to touch (fewer missed contacts at large time steps, more points).
    /// Bounds [0, 1] (scene length unit): negative would drop touching contacts; ODE takes every
    /// contact as active, so the ODE adapter passes on only points with depth ≥ 0 and a margin
    /// matters there only with spanContactRegion. A margin of a whole length unit (a metre)
    /// means every pair within a metre makes speculative points: a unit or a typing mistake.
    double margin = 0.0;

    /// Stage 3 — also report where the contact region ends: where an edge of the intersection runs
    /// from contact into a gap, the point where its depth crosses −margin is added (a contact of
    /// depth −margin). On: the points span the exact contact region of a slightly tilted face
    /// (area ratio 1 instead of ~0.56, docs/benchmarks.md). Off (default), as ODE's dBoxBox and
    /// Bullet's clipping do: only overlapping vertices. Off by default because the extra rows made
    /// ODE's solvers less steady in the paper's scenes (docs/results.md).
    bool spanContactRegion = false;

    /// Reduction — the contact budget: most contact points returned for one geom pair (count, 1…16).
    /// Points beyond it are dropped by importance (the deepest, the farthest from it, then the
    /// largest added area, keeping the bodies' centroids inside; docs/algorithm.md, "The contact
    /// set the solver gets"); every prefix of the returned points is the best of its length, so a
    /// caller's smaller limit gets the best points. Fewer: fewer rows for the solver (cheaper,
    /// above all under dWorldStep), at a support region held by fewer points — under
    /// dWorldQuickStep's cut-off Gauss–Seidel a stack is held less firmly with fewer rows per
    /// pair. 6 (default) is the fewest that stands wherever 8 and ODE's dBox stand in the solver
    /// benchmark over seeds; 8 keeps a box–box octagon whole; 4 is what Bullet, PhysX and Box3D
    /// keep and suffices under dWorldStep; 1 keeps the deepest point, 2 a segment, 3 a triangle.
    /// Why 6: docs/algorithm.md, "The budget over every scene: why 6"; the tables in
    /// docs/benchmarks.md, "The budget over every scene". The ODE adapter's defaults
    /// (gdc::ode::defaultSettings) make it 8 against a single-precision ODE, whose Dantzig LCP
    /// meets fewer ties with a face pair's octagon whole (docs/install.md, "Single precision: 8
    /// points a face").
    /// Bounds [1, 16]: 16 is the size of a Manifold (kMaxManifoldPoints).
    int maxContacts = 6;

    /// Stage 3, curved shapes — points per whole turn of a cylinder's rim (count): the points
    /// placed on an arc of a cap's rim inside the other feature are at most 2π/this apart, and
    /// the reduction then keeps maxContacts of them. More: the kept points hug the disc closer
    /// (the support polygon of a standing cylinder, which sets the force that tips it, is that of
    /// the points the reduction keeps), at more candidates to rank. 16 places a point every 22.5°.
    /// Bounds [4, 64].
    int rimPointsPerTurn = 16;

    /// Support mapping — polytopes with at most this many vertices are searched by brute force,
    /// larger ones by hill climbing over vertex adjacency (count). Measured cross-over: see
    /// docs/benchmarks.md.
    /// Bounds [0, 65536]: 0 always climbs; above 65536 vertices a brute-force support costs
    /// more than 100 µs per call — every polytope gdcontact handles well is below it.
    int bruteForceSupportLimit = 32;

    /// Polytope construction — faces whose normals differ by less than this angle (radians) are
    /// merged into one face. Larger: hulls from noisy points get clean faces; too large merges
    /// genuinely distinct faces (curved hulls lose their shape).
    /// Bounds [0, 0.1] rad: 0 merges only exactly coplanar faces; above 0.1 rad (≈ 5.7°) a
    /// 32-sided prism's sides (0.2 rad apart) would start to merge — no longer rounding noise.
    double coplanarTolerance = 1e-6;

    /// One of the NormalMethod values (checked: a value cast from an integer may be neither).
    NormalMethod normalMethod = NormalMethod::GrowthDistance;

    /// Pair cache (only where a PairCache is passed: collide(..., cache), and the ODE adapter's
    /// own cache) — how far the pair may have moved since its last full query and still get that
    /// query's contacts again, carried along with the two bodies, their depths re-measured
    /// (metres, the scene's length unit; the bound is on every point of B, relative to A, so a
    /// turn counts by the distance it moves B's farthest vertex). 0 (default): exact — the cache
    /// answers without a query only when nothing moved, and its answer is then the query's, bit
    /// for bit. Larger: resting and slowly moving pairs skip the query (a carried manifold costs
    /// a few hundred instructions instead of thousands), at an error in depth and position of at
    /// most about this distance, and new contact features are noticed only once the pair has
    /// moved this far (Jolt's default is 1 mm and 2°). docs/benchmarks.md's trade table measures both.
    /// Bounds [0, 1] (scene length unit), as margin: a whole length unit is a unit mistake.
    double manifoldReuseDistance = 0.0;

    // ---- The contact set the solver gets (docs/algorithm.md): its budget is maxContacts above;
    // ---- the order of its points and the hysteresis of its choice. ----

    /// The order in which dWorldQuickStep (projected Gauss–Seidel, which solves rows in the order
    /// they arrive) meets one pair's contacts through the ODE adapter: by depth, see ContactOrder.
    /// It trades drift in stacks (DeepestLast: less) against the time resting bodies take to fall
    /// asleep (DeepestFirst: a little sooner) and against columns under a heavy load
    /// (DeepestFirst, DeepestFirstWhenLoaded: far fewer collapses); measured over seeds in
    /// docs/algorithm.md and docs/benchmarks.md. The core's array is always in the order of importance.
    /// Bounds: a ContactOrder value (checked: a value cast from an integer may be none of them).
    ContactOrder contactOrder = ContactOrder::DeepestFirstWhenLoaded;

    /// ContactOrder::DeepestFirstWhenLoaded only — a pair counts as loaded where its deepest
    /// point is deeper than this fraction of the pair's size: the larger of the two shapes'
    /// diameters (twice the bounding radius: a box's diagonal; a plane or a mesh counts for none) —
    /// relative, unitless, so the rule is the same at every scale. Smaller: more pairs met deepest
    /// first (0: every overlapping pair, as DeepestFirst — tall stacks of equal bodies and thin
    /// plates drift more); larger: fewer (above the depth any load reaches: DeepestLast everywhere,
    /// the loaded columns collapse). 0.01 (17 mm on a 1 m cube): where the benchmark's stacks, walls,
    /// plates and hulls stand, they keep DeepestLast's counts and drift within seed noise, and the
    /// columns under a 100× heavier body go beyond it; 0.006 to 0.0115 held the
    /// columns alike, 0.02 let them collapse as often as with dBox (docs/benchmarks.md, "Columns and
    /// heaps"). The depth a load makes depends on ERP, CFM and the iterations, not on size: a world
    /// with other ERP or CFM may want another value.
    /// Bounds [0, 1]: beyond 1 a pair would have to sink deeper than its own diameter (DeepestLast
    /// in effect: a typing mistake).
    double loadedDepthFraction = 0.01;

    /// Reduction — hysteresis without state (relative, unitless): after the deepest point (depths
    /// equal within rounding count as equal), candidates whose gain — the distance from the first
    /// point, then the area added to the kept points — is within this fraction of the best count as
    /// equal, and the tie goes to a fixed identity (the point's position along a fixed generic
    /// world direction), so that a resting pair keeps the same points, in the same order, from step
    /// to step instead of flipping between near-equal corners. Larger: steadier, at a kept set up
    /// to this fraction less wide than the greedy best; 0: always the strict best.
    /// Bounds [0, 0.1]: above 10 % the kept points may span visibly less than the best.
    double reductionHysteresis = 0.01;
    // ---- Per-body-pair contact budget (composites; include/gdcontact/body_pair.hpp) ----

    /// Body-pair reduction — most contacts kept between two bodies for each contact direction
    /// (count; 0: off), where the bodies touch through more than one pair of their geoms (bodies
    /// made of several convex parts). The contacts of all those pairs are clustered by normal
    /// (bodyPairNormalTolerance), near-duplicates merged, and each cluster reduced to this many:
    /// the deepest, the widest support polygon, the carried body's centre of mass kept over it.
    /// Fewer: fewer rows for the solver (dWorldStep's cost grows steeply with them, and redundant
    /// coplanar rows make its LCP nearly singular: "LCP internal error"), a coarser support
    /// polygon. 0 hands the solver every contact of every pair of parts. gdc::ode::spaceCollide and
    /// gdc::ode::reduceBodyPair apply it; a single pair of geoms keeps its own maxContacts.
    /// Bounds [0, 16]: 16 is the size of a Manifold; 4 (the default) is what Jolt, bepuphysics,
    /// Bullet and PhysX keep per manifold, and 3 is the fewest that can hold a centre of mass.
    int maxBodyPairContacts = 4;

    /// Body-pair reduction — contacts whose normals differ by at most this angle (radians) form
    /// one cluster, reduced together. Larger: supports at a small angle to each other are merged
    /// (fewer rows, each point keeps its own normal); smaller: nearly parallel supports each keep
    /// their own budget. Bounds [0, 0.5] rad: 0 clusters only identical normals; above 0.5 rad
    /// (≈ 29°) distinct supports (a body in a V-groove) would share one budget.
    double bodyPairNormalTolerance = 0.0873;  // ≈ 5°
};

/// Whether two settings are the same in every field (a PairCache answers only for the settings it
/// was filled with).
GDCONTACT_API bool operator==(const Settings& a, const Settings& b);
inline bool operator!=(const Settings& a, const Settings& b) { return !(a == b); }

}  // namespace gdc
