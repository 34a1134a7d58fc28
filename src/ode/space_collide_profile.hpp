// Where gdc::ode::spaceCollide spends a call's time, for the big-world benchmark
// (bench/big_world.cpp) and for anyone profiling a scene. Compiled in only with the build option
// GDCONTACT_PHASE_PROFILING (scripts/bench turns it on); then off until asked, at the cost of one
// relaxed atomic load per call. Not part of the public API (include/gdcontact/ode.hpp): the
// phases are the implementation's, and may change with it.
#pragma once

#include <gdcontact/export.hpp>

#include <cstddef>

namespace gdc::ode::detail {

/// One spaceCollide call, wall-clock seconds on the calling thread unless said otherwise.
struct SpaceCollideProfile {
    int threads = 0;                  ///< threads that could work on gdcontact's pairs (1: serial)
    std::size_t gdcontactPairs = 0;   ///< candidate pairs gdcontact collided
    std::size_t otherPairs = 0;       ///< candidate pairs dCollide collided on the calling thread
    double totalSeconds = 0;          ///< the whole call
    double broadPhaseSeconds = 0;     ///< dSpaceCollide: ODE's broad phase, listing the pairs, dCollide's
                                      ///< pairs (and, serial, gdcontact's: see narrowSeconds)
    double drainSeconds = 0;          ///< after the broad phase: the calling thread's share of the narrow
                                      ///< phase and its waits for the pool (0 when serial)
    double handlerSeconds = 0;        ///< the rest of the call after the broad phase: the handler loop
    double narrowSeconds = 0;         ///< inside gdcontact's collide for its pairs, summed over threads
    double narrowOnCallerSeconds = 0; ///< the part of narrowSeconds on the calling thread
    double poolStartSeconds = -1;     ///< from the call's start to the first chunk a pool thread took
                                      ///< (its wake-up latency); −1 when no pool thread took one
};

/// Whether this build records phases (GDCONTACT_PHASE_PROFILING).
bool spaceCollideProfilingBuilt();
/// Turns the recording on or off for every later spaceCollide call (any thread). Throws
/// InvalidInput when asked to turn it on in a build without it.
void setSpaceCollideProfiling(bool enabled);
/// The calling thread's last spaceCollide call while recording was on.
SpaceCollideProfile lastSpaceCollideProfile();

}  // namespace gdc::ode::detail
