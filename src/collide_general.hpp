// The general pipeline of the paper, without the specialised paths (box–box, polytope–half-space
// vertex loops): the reference every specialised path is tested equal to. collide() dispatches.
#pragma once

#include <gdcontact/collide.hpp>

namespace gdc::detail {

/// The paper's three stages for any two polytopes (collide.cpp).
Manifold collideGeneral(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings);
/// Gauss-map feature of A lifted onto the half-space, for any polytope (collide.cpp).
Manifold collideGeneral(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings);

}  // namespace gdc::detail
