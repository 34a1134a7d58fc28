// ODE's dReal — double or float, as the ODE gdcontact is built against was built — at the
// adapter's boundary. The core computes in double whatever dReal is: the adapter converts what it
// reads from ODE (poses, box lengths, plane parameters, AABBs) to double and what it writes
// (contacts) back to dReal. Tolerances that compare a value ODE computed in dReal with gdcontact's
// own double value (a geom's AABB, a depth that rounds below zero) scale with dReal's precision.
// (The caches keyed by box lengths and plane parameters take float arrays too: box_cache.hpp,
// thread_cache.hpp, which include no ODE header.)
#pragma once

#include <ode/ode.h>

#include <algorithm>
#include <limits>

namespace gdc::ode::detail {

/// Whether dReal is double (ODE's dDOUBLE build); the adapter's fast paths store doubles as they are.
inline constexpr bool kOdeRealIsDouble = sizeof(dReal) == sizeof(double);
static_assert(kOdeRealIsDouble || sizeof(dReal) == sizeof(float), "dReal is float or double");

/// A relative tolerance `forDouble` (what a double-precision ODE's values need) widened for a
/// single-precision ODE to 64 units in the last place of a float (7.6e-6): the most a value ODE
/// computes in float from a few products and sums (an AABB from a rotation, a position and the
/// hull's extent; a depth from float poses) can differ from the same value computed in double.
inline constexpr double inputRelativeTolerance(double forDouble) {
    return std::max(forDouble, 64.0 * static_cast<double>(std::numeric_limits<dReal>::epsilon()));
}

}  // namespace gdc::ode::detail
