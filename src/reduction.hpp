// Reduction of a contact polygon to the caller's maximum count without losing its support:
// keep the deepest point (it carries the penetration), then greedily the points that span the
// largest area (they carry the torque that keeps a resting body flat). Deterministic: ties go to
// the lowest index.
#pragma once

#include "feature_intersection.hpp"

namespace gdc::detail {

/// Chooses at most `maxCount` of `points` (by index into `points`, written to `chosen`).
/// Returns how many were chosen.
int reduceContacts(const LiftedPoints& points, int maxCount, int* chosen);

}  // namespace gdc::detail
