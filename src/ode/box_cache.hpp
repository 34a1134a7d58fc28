// Box polytopes by half extents: one Polytope per size, shared by every box of that size
// (building a Polytope allocates, and box–box must be cheap). A process-wide map under a lock for
// polytopeOf, and in front of it each thread's few last sizes for collide(), which takes no lock
// on a hit.
#pragma once

#include "thread_cache.hpp"

#include <memory>

namespace gdc::ode::detail {

/// A box polytope of the given half extents (bounded cache).
std::shared_ptr<const Polytope> boxPolytope(double halfX, double halfY, double halfZ);

/// As boxPolytope, for collide(): borrowed from the thread's cache. The reference stays valid
/// until this thread has looked up kBorrowedBoxSizes − 1 other sizes, which covers both boxes
/// of one pair — or, while ThreadCache::pinnedBoxes is set, until that vector is cleared.
const Polytope& borrowedBoxPolytopeSlow(ThreadCache& cache, double halfX, double halfY, double halfZ);
inline const Polytope& borrowedBoxPolytope(ThreadCache& cache, double halfX, double halfY, double halfZ) {
    ThreadCache::BoxSlot& last = cache.boxes[cache.lastBox];
    if (last.halfExtents[0] == halfX && last.halfExtents[1] == halfY && last.halfExtents[2] == halfZ) {
        last.lastUse = ++cache.boxClock;
        return *last.polytope;
    }
    return borrowedBoxPolytopeSlow(cache, halfX, halfY, halfZ);
}

}  // namespace gdc::ode::detail
