#include "thread_cache.hpp"

#include "contact/half_space.hpp"

namespace gdc::ode::detail {

const ThreadCache::PlaneSlot& planeSlotSlow(ThreadCache& cache, double a, double b, double c, double d) {
    for (int i = 0; i < ThreadCache::kPlaneSlots; ++i) {
        const ThreadCache::PlaneSlot& slot = cache.planes[i];
        if (slot.raw[0] == a && slot.raw[1] == b && slot.raw[2] == c && slot.raw[3] == d) {
            cache.lastPlane = i;
            return slot;
        }
    }
    cache.lastPlane = (cache.lastPlane + 1) % ThreadCache::kPlaneSlots;
    ThreadCache::PlaneSlot& slot = cache.planes[cache.lastPlane];
    slot.raw[0] = a;
    slot.raw[1] = b;
    slot.raw[2] = c;
    slot.raw[3] = d;
    slot.halfSpace = HalfSpace{Vec3(a, b, c).normalized(), d};
    slot.normalised = false;
    try {
        slot.normalisedHalfSpace = gdc::detail::normaliseHalfSpace(slot.halfSpace);
        slot.normalised = true;
    } catch (const InvalidInput&) {  // a bad plane: each call's core query reports it
    }
    return slot;
}

}  // namespace gdc::ode::detail
