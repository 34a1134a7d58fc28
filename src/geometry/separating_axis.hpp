// An alternative stage 1: the contact normal by the separating-axis test, for measuring the
// speed/accuracy trade against the paper's growth distance (Settings::normalMethod).
//
// For two convex polytopes the minimum-translation direction is the normal of a face of A − B:
// a face normal of A, of B, or the cross product of an edge of A and an edge of B whose arcs cross
// on the Gauss map (the other edge pairs span no face of A − B). Testing exactly those gives the
// exact minimum normal at a cost of (edges of A) × (edges of B) arc tests (Gregorius, "The
// Separating Axis Test between Convex Polyhedra", GDC 2013).
#pragma once

#include "geometry/minkowski.hpp"

namespace gdc::detail {

struct SeparatingAxis {
    Vec3 normal = Vec3::UnitZ();  // unit, A's frame, from A towards B
    double overlap = 0;           // the pair's overlap along it (< 0: separated by that much)
};

/// The axis along which A and B (B in A's frame) overlap least.
SeparatingAxis minimumOverlapAxis(const MinkowskiDifference& pair);

}  // namespace gdc::detail
