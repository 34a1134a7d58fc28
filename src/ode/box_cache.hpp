// Box polytopes by half extents: one Polytope per size, shared by every box of that size
// (building a Polytope allocates, and box–box must be cheap). A process-wide map under a lock for
// polytopeOf, and in front of it each thread's few last sizes for collide(), which takes no lock
// on a hit.
#pragma once

#include "thread_cache.hpp"

#include <cstring>
#include <memory>

namespace gdc::ode::detail {

/// A box polytope of the given half extents (bounded cache).
std::shared_ptr<const Polytope> boxPolytope(double halfX, double halfY, double halfZ);

/// As boxPolytope, for collide(): borrowed from the thread's cache. The reference stays valid
/// until this thread has looked up kBorrowedBoxSizes − 1 other sizes, which covers both boxes
/// of one pair — or, while ThreadCache::pinnedBoxes is set, until that vector is cleared.
/// `lengths`: the box's as dGeomBoxGetLengths gives them; the half extents are half of each. The
/// last slot is compared by the bytes of the lengths it was found for (integer compares); the
/// search of the others by the half extents' values, as before: a box whose lengths equal the
/// last's by value but not by bytes finds the slot it found before.
const Polytope& borrowedBoxPolytopeSlow(ThreadCache& cache, const double* lengths);
inline const Polytope& borrowedBoxPolytope(ThreadCache& cache, const double* lengths) {
    ThreadCache::BoxSlot& last = cache.boxes[cache.lastBox];
    if (std::memcmp(last.lengths, lengths, sizeof last.lengths) == 0) {
        last.lastUse = ++cache.boxClock;
        return *last.polytope;
    }
    return borrowedBoxPolytopeSlow(cache, lengths);
}
/// The same for a single-precision ODE's lengths (dReal is float): converted to double first.
inline const Polytope& borrowedBoxPolytope(ThreadCache& cache, const float* lengths) {
    const double asDouble[3] = {lengths[0], lengths[1], lengths[2]};
    return borrowedBoxPolytope(cache, asDouble);
}

}  // namespace gdc::ode::detail
