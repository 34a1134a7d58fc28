// Tests' tolerances for values that pass through ODE's dReal: a single-precision ODE (dReal is
// float) rounds every pose it hands over and every contact field it takes back to float, so a
// comparison that holds to `forDouble` with a double-precision ODE holds to float's rounding
// there. The same rule as the adapter's own (src/ode/ode_real.hpp): 64 float ulps, 7.6e-6 relative.
#pragma once

#include <ode/ode.h>

#include <algorithm>
#include <limits>

namespace gdc::ode::test {

inline constexpr bool kOdeIsDouble = sizeof(dReal) == sizeof(double);

/// `forDouble`, or what float's rounding allows where dReal is float.
inline constexpr double realTolerance(double forDouble) {
    return std::max(forDouble, 64.0 * static_cast<double>(std::numeric_limits<dReal>::epsilon()));
}

}  // namespace gdc::ode::test
