// The table of pair compositions (pair_table.hpp). Each cell unpacks the shapes and calls the
// composition of the stages for that pair of kinds (pipeline.hpp's composeStages with the kinds'
// hooks); a kind's closed forms apply only under the settings they were derived for (a box's below
// an angular tolerance of π/4, say), so a cell may send a pair on to the general hooks.
#include "contact/pair_table.hpp"

#include "contact/box_box.hpp"
#include "contact/collide_general.hpp"
#include "contact/round_pair.hpp"

#include <string>
#include <utility>

namespace gdc::detail {
namespace {

// Two boxes: the closed forms (box_box.cpp) where the settings allow them.
template <ImportanceOrder order>
void boxWithBox(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, const PairQuery& query,
                Manifold& out) {
    if (boxBoxApplies(*a.polytope, *b.polytope, query.settings))
        return collideBoxBoxInto<order>(*a.polytope, poseA, *b.polytope, poseB, query.settings, out);
    collideGeneralInto<order>(*a.polytope, poseA, *b.polytope, poseB, query.settings, out);
}

// Any two polytopes, one of them a hull: the general hooks (collide.cpp).
template <ImportanceOrder order>
void polytopes(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, const PairQuery& query,
               Manifold& out) {
    collideGeneralInto<order>(*a.polytope, poseA, *b.polytope, poseB, query.settings, out);
}

// A polytope on a half-space: a box's or a small hull's vertex loop (half_space.cpp) where it
// applies, the general polytope-on-plane hooks otherwise (a large hull: the Gauss-map search).
template <ImportanceOrder order>
void polytopeOnHalfSpace(const Shape& a, const Pose& poseA, const Shape& b, const Pose&, const PairQuery& query,
                         Manifold& out) {
    if (halfSpaceFastPathApplies(*a.polytope, query.settings))
        return collideHalfSpaceInto<order>(*a.polytope, poseA, *b.halfSpace, query.settings, query.angularTolerance,
                                           out);
    collideGeneralInto(*a.polytope, poseA, *b.halfSpace, query.settings, out);
}

// B's kind before A's in the table's order: the pair the other way round, mirrored (the normal
// points from A to B; the points lie midway between the surfaces either way).
template <PairFunction swapped>
void mirrored(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, const PairQuery& query,
              Manifold& out) {
    swapped(b, poseB, a, poseA, query, out);
    out.normal = -out.normal;
    std::swap(out.featureA, out.featureB);
}

[[noreturn]] void noCell(const Shape&, const Pose&, const Shape&, const Pose&, const PairQuery&, Manifold&) {
    throw InvalidInput("two half-spaces are not a pair gdcontact collides");
}

// One table per order a caller may ask for: rows A's kind, columns B's (ShapeKind's order). Every
// pair with a curved kind is the curved cells' (on a half-space, its own: nothing to cast); a
// half-space as A is the mirror of its pair.
template <ImportanceOrder order>
constexpr PairCells kCells = {{
    /* Box */ {boxWithBox<order>, polytopes<order>, collideRoundInto, collideRoundInto, collideRoundInto,
               polytopeOnHalfSpace<order>},
    /* Hull */ {polytopes<order>, polytopes<order>, collideRoundInto, collideRoundInto, collideRoundInto,
                polytopeOnHalfSpace<order>},
    /* Sphere */ {collideRoundInto, collideRoundInto, collideRoundInto, collideRoundInto, collideRoundInto,
                  collideRoundOnPlaneInto},
    /* Capsule */ {collideRoundInto, collideRoundInto, collideRoundInto, collideRoundInto, collideRoundInto,
                   collideRoundOnPlaneInto},
    /* Cylinder */ {collideRoundInto, collideRoundInto, collideRoundInto, collideRoundInto, collideRoundInto,
                    collideRoundOnPlaneInto},
    /* HalfSpace */ {mirrored<polytopeOnHalfSpace<order>>, mirrored<polytopeOnHalfSpace<order>>,
                     mirrored<collideRoundOnPlaneInto>, mirrored<collideRoundOnPlaneInto>,
                     mirrored<collideRoundOnPlaneInto>, noCell},
}};

}  // namespace

const PairCells kPairCells[2] = {kCells<ImportanceOrder::Full>, kCells<ImportanceOrder::AmongEqualDepths>};

void throwPoseNotFinite(const char* which) {
    throw InvalidInput(std::string("the pose of ") + which + " is not finite");
}

UnitHalfSpace enterHalfSpace(const Pose& poseA, const HalfSpace& b) {
    if (!poseA.isFinite()) throwPoseNotFinite("A");
    return normaliseHalfSpace(b);
}

}  // namespace gdc::detail
