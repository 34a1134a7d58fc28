// The general pipeline of the paper, without the specialised paths (box–box, polytope–half-space
// vertex loops): the reference every specialised path is tested equal to. collide() dispatches.
#pragma once

#include <gdcontact/collide.hpp>

namespace gdc::detail {

/// The paper's three stages for any two polytopes (collide.cpp). `alwaysConfirmDepth` runs the
/// depth confirmation's ray cast wherever the lifted points fall short of the supports' overlap,
/// even where a certificate shows it cannot add a point: the path the certificate replaced, kept
/// so that a test can prove the two equal.
Manifold collideGeneral(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings, bool alwaysConfirmDepth = false);
/// Gauss-map feature of A lifted onto the half-space, for any polytope (collide.cpp).
Manifold collideGeneral(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings);

}  // namespace gdc::detail
