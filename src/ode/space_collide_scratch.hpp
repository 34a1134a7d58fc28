// One spaceCollide call's buffers (space_collide.cpp): the candidate pairs in the broad phase's
// order, the slots the pool writes each gdcontact pair's contacts into, and the per-thread scratch
// that holds them between calls, so that a step allocates nothing once the buffers have grown.
#pragma once

#include "body_pair.hpp"
#include "pair_cache_table.hpp"
#include "resolved_pair.hpp"
#include "thread_cache.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gdc::ode::detail {

// A candidate pair in the broad phase's order: a gdcontact pair collided on the pool by its index in
// the slot store; a pair collided at once on the calling thread by its contacts' offset in the
// packed buffer (`count` contacts).
struct Pair {
    dGeomID o1;
    dGeomID o2;
    std::size_t index;
    int count;
    bool gdcontact;
};

// gdcontact's pairs and their output slots, written by the broad phase while the pool reads the
// ones published: blocks that never move, block k holding kFirstBlock << k pairs.
constexpr std::size_t kFirstBlock = 1024;
constexpr int kBlocks = 40;  // kFirstBlock · (2^40 − 1) pairs: more than memory holds

struct Slot {
    // Resolved once, by the broad phase's thread (addPair); read by the thread colliding the pair.
    detail::ResolvedPair pair;
    detail::ThreadCache::PlaneSlot plane;  // the pair's plane, copied from the resolving thread's cache
    // Contacts found, stored (release) by the thread that collided the pair; −1 until then. The
    // handler loop reads it (acquire) to know the pair's contacts are there.
    std::atomic<int> count;
    PairCache* cache;  // the pair's entry in the adapter's pair cache; nullptr: none
};

struct SlotBlock {
    std::unique_ptr<Slot[]> slots;
    std::unique_ptr<dContactGeom[]> contacts;  // slotSize per pair
    int slotSize = 0;
};

inline int blockOf(std::size_t index, std::size_t& offset) {
    const std::size_t scaled = index / kFirstBlock + 1;  // block k holds scaled in [2^k, 2^(k+1))
    const int block = 63 - __builtin_clzll(static_cast<unsigned long long>(scaled));
    offset = index - kFirstBlock * ((std::size_t{1} << block) - 1);
    return block;
}

// One spaceCollide call's buffers, kept per calling thread so that a step allocates nothing once
// the scene's size has been seen (a handler calling spaceCollide again gets fresh ones).
struct Scratch {
    std::vector<Pair> pairs;
    SlotBlock blocks[kBlocks];
    // The contacts of the pairs collided on the calling thread (ODE's; gdcontact's when serial),
    // one pair after the other. Not a std::vector: room for a pair is made without filling it.
    struct Packed {
        std::unique_ptr<dContactGeom[]> data;
        std::size_t size = 0, capacity = 0;
        dContactGeom* reserve(std::size_t room) {  // room for `room` more; their address
            if (size + room > capacity) {
                const std::size_t grown = std::max(2 * capacity, size + room + 1024);
                std::unique_ptr<dContactGeom[]> bigger(new dContactGeom[grown]);
                std::copy(data.get(), data.get() + size, bigger.get());
                data = std::move(bigger);
                capacity = grown;
            }
            return data.get() + size;
        }
    } packed;
    std::size_t gdcontactPairs = 0;
    bool inUse = false;
    // Box polytopes the calling thread's cache evicted during this call (ThreadCache::pinnedBoxes):
    // resolved pairs may still point at them until the pool has collided them.
    std::vector<std::shared_ptr<const Polytope>> pinnedBoxes;

    // The per-body-pair budget (Settings::maxBodyPairContacts): pairs between the same two bodies,
    // linked in the broad phase's order. For pair i: the first pair of its body pair when that body
    // pair has several geom pairs (else −1), the next pair of the same body pair (−1: the last),
    // and its contacts' count after the reduction (−1: not reduced yet).
    struct BodyPairLinks {
        int first, last, size;
    };
    struct BodyPairHash {
        std::size_t operator()(const std::pair<dBodyID, dBodyID>& key) const noexcept {
            const auto a = reinterpret_cast<std::uintptr_t>(key.first), b = reinterpret_cast<std::uintptr_t>(key.second);
            return std::hash<std::uintptr_t>()(a * 0x9E3779B97F4A7C15ull ^ b);
        }
    };
    std::unordered_map<std::pair<dBodyID, dBodyID>, BodyPairLinks, BodyPairHash> bodyPairs;
    std::vector<int> bodyPairHead, bodyPairNext, reducedCount;
    std::vector<dContactGeom> bodyPairContacts;  // one body pair's contacts, gathered
    std::vector<int> bodyPairOwner;               // which pair each gathered contact came from
    std::vector<BodyPairContact> bodyPairPoints;
    std::vector<int> bodyPairKept;

    // Links the pairs of each body pair; false when no body pair has several geom pairs.
    bool linkBodyPairs() {
        const std::size_t n = pairs.size();
        bodyPairs.clear();
        bodyPairHead.assign(n, -1);
        bodyPairNext.assign(n, -1);
        reducedCount.assign(n, -1);
        bool any = false;
        // Two bodies of one geom each touch through one pair at most: most pairs of a pile skip
        // the table (a body against the static world may touch several static geoms).
        for (std::size_t i = 0; i < n; ++i) {
            dBodyID b1 = dGeomGetBody(pairs[i].o1), b2 = dGeomGetBody(pairs[i].o2);
            if (b1 == b2) continue;  // static geoms (ODE lists no two geoms of one body)
            if (detail::bothHaveOneGeom(b1, b2)) continue;
            if (std::less<dBodyID>()(b2, b1)) std::swap(b1, b2);
            const int index = static_cast<int>(i);
            auto [entry, created] = bodyPairs.try_emplace({b1, b2}, BodyPairLinks{index, index, 1});
            if (created) continue;
            bodyPairNext[static_cast<std::size_t>(entry->second.last)] = index;
            entry->second.last = index;
            ++entry->second.size;
            any = true;
        }
        if (!any) return false;
        for (const auto& entry : bodyPairs)
            if (entry.second.size > 1)
                for (int i = entry.second.first; i >= 0; i = bodyPairNext[static_cast<std::size_t>(i)])
                    bodyPairHead[static_cast<std::size_t>(i)] = entry.second.first;
        return true;
    }

    // The slot of gdcontact pair `index`, its block made ready for `slotSize` contacts a pair.
    Slot& slotFor(std::size_t index, int slotSize, dContactGeom*& contacts) {
        std::size_t offset;
        SlotBlock& block = blocks[blockOf(index, offset)];
        const std::size_t size = kFirstBlock << (&block - blocks);
        if (!block.slots) block.slots.reset(new Slot[size]);
        if (block.slotSize != slotSize) {
            block.contacts.reset(new dContactGeom[size * static_cast<std::size_t>(slotSize)]);
            block.slotSize = slotSize;
        }
        contacts = block.contacts.get() + offset * static_cast<std::size_t>(slotSize);
        return block.slots[offset];
    }
};

}  // namespace gdc::ode::detail
