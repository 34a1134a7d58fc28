// The general pipeline's cells (collide_general.hpp) by value, for tests that run it where the pair
// table would send the pair to a kind's closed forms (boxes), to check the general hooks themselves.
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/collide_general.hpp"
#include "contact/pair_table.hpp"

namespace gdc::testing {

inline Manifold generalManifold(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                                const Settings& settings = {}) {
    if (!poseA.isFinite() || !poseB.isFinite()) return collide(a, poseA, b, poseB, settings);  // throws why
    Manifold manifold;
    detail::collideGeneralInto<detail::ImportanceOrder::Full>(a, poseA, b, poseB, settings, manifold);
    return manifold;
}

inline Manifold generalManifold(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings = {}) {
    const detail::UnitHalfSpace plane = detail::enterHalfSpace(poseA, b);
    Manifold manifold;
    detail::collideGeneralInto(a, poseA, plane, settings, manifold);
    return manifold;
}

}  // namespace gdc::testing
