// The core's manifold written as ODE's dContactGeoms: the last step of every gdc::ode::collide
// call (collide.cpp), apart so that tests/ode/adapter_equality_test.cpp can hold it against ODE's
// convention, written plainly, on every kind of manifold.
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/settings.hpp>

#include "ode_real.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace gdc::ode::detail {

// Where writeContacts stores the fields every contact of a call shares, two at a time (pos and
// normal so only where dReal is double; a single-precision ODE's are converted field by field).
static_assert(offsetof(dContactGeom, g2) == offsetof(dContactGeom, g1) + sizeof(dGeomID),
              "g1 and g2 are written as one pair");

namespace write_contacts_detail {

// A kept point by its depth; the point itself by address (its index cost a multiply per write).
struct Ranked {
    double depth;
    const ContactPoint* point;
};

// Two doubles or two pointer-sized words, for one 16-byte store (GCC's and Clang's vector types).
typedef double DoublePair __attribute__((vector_size(16)));
typedef std::uint64_t WordPair __attribute__((vector_size(16)));
static_assert(sizeof(std::uintptr_t) == sizeof(std::uint64_t) && sizeof(dGeomID) == sizeof(std::uint64_t),
              "g1 and g2 are stored as a pair of 64-bit words");

// Vec3::allFinite without the reduction machinery: x − x is 0 exactly for a finite x, NaN else.
inline bool isFinite(const Vec3& v) { return (v.x() - v.x()) + (v.y() - v.y()) + (v.z() - v.z()) == 0.0; }

// The points of [point, end) at least as deep as `lowest` (and, unless the core checked them,
// with a finite position) inserted by depth after `top`, deepest first, equal depths in the
// core's order; the last one filled returned. Insertion by depth as they are read: at most 16, so
// an insertion sort is the cheapest; the slot before the first holds NaN, which no comparison
// passes, so the inner loop needs no bound check (a kept depth is never NaN). The core's own
// answer needs no finiteness test: a template argument, not a flag tested per point.
template <bool kCheckedFinite>
inline Ranked* rankByDepth(const ContactPoint* point, const ContactPoint* end, double lowest, Ranked* top) {
    for (; point != end; ++point) {
        const double depth = point->depth;
        if (!(depth >= lowest)) continue;
        if (!kCheckedFinite && !isFinite(point->position)) continue;
        Ranked* slot = ++top;  // a pointer walk: indices made g++ unroll into index arithmetic
        if (depth > slot[-1].depth) {
            do {
                *slot = slot[-1];
                --slot;
            } while (depth > slot[-1].depth);
        }
        slot->depth = depth;
        slot->point = point;
    }
    return top;
}

}  // namespace write_contacts_detail

/// ContactOrder::DeepestFirstWhenLoaded's threshold (settings.hpp): `loadedDepthFraction` of the
/// pair's size, the larger of its shapes' diameters, each twice the bounding radius (a plane or a
/// mesh: none, pass 0 for it).
inline double loadedDepthOf(const Settings& settings, double radius1, double radius2) {
    return settings.loadedDepthFraction * 2.0 * std::max(radius1, radius2);
}

/// The core's contacts as ODE's: at most maxContacts, written in place at stride `skip`, in the
/// order that makes dWorldQuickStep meet them as `order` says; the count written. `flip`: the
/// core's A is o2 (its normal then already points from o2 into o1). `sizeOfPair`: the sum of the
/// two polytopes' radii (the touching tolerance's scale). `loadedDepth`: DeepestFirstWhenLoaded's
/// threshold (loadedDepthOf; read for that order only): where the deepest point written is deeper,
/// the pair is written as DeepestFirst, else as DeepestLast.
/// `checkedFinite`: the core's own answer (not one a pair cache carried), whose every position the
/// core has checked finite (every answer it computes is written by emitManifold or the plane
/// contacts, which throw where a contact overflows), so the finiteness test would pass.
inline int writeContacts(const Manifold& manifold, bool flip, double sizeOfPair, int maxContacts, ContactOrder order,
                         double loadedDepth, dGeomID o1, dGeomID o2, dContactGeom* contact, int skip,
                         bool checkedFinite) {
    using write_contacts_detail::Ranked;
    // The core's normal points from A towards B; ODE's from o2 into o1.
    Vec3 normal = flip ? manifold.normal : Vec3(-manifold.normal);
    // norm() is the square root of squaredNorm(): where that is exactly 1 the root is 1 and the
    // division changes no bit, so both are skipped. A normal the core carried through a geom's
    // rotation is off unit by as much as that rotation is off orthonormal: ~1e-16 from a
    // double-precision ODE, up to ~1.2e-6 from a single-precision one (its integrator leaves a
    // body's rotation a few float ulps off; 1e-6 refused such pairs: no contacts), so the limit
    // scales with dReal's precision.
    const double squaredLength = normal.squaredNorm();
    if (squaredLength != 1.0) {
        const double length = std::sqrt(squaredLength);
        if (!std::isfinite(length) || std::abs(length - 1.0) > inputRelativeTolerance(1e-6)) {
            dMessage(d_ERR_UNKNOWN, "gdcontact: the core returned an invalid normal; pair skipped");
            return 0;
        }
        normal /= length;
    }

    // ODE treats every contact as active and clamps a negative depth to zero, so a speculative
    // point (depth < 0, only with Settings::margin > 0) would hold the bodies apart by its gap.
    // Such points are not passed on; a rounding-level negative depth is reported as touching.
    // (Relative to dReal's precision: a single-precision ODE's poses round a resting depth by ~1e-7.)
    const double touchingTolerance = inputRelativeTolerance(1e-9) * sizeOfPair;
    // The core's points come in the order of importance (the deepest first; every prefix the best
    // of its length), already reduced to maxContacts: the set is the best of its size. The ORDER
    // is by depth, for dWorldQuickStep, which solves rows in the order they arrive: ODE's
    // dJointAttach puts each new contact joint at the head of its bodies' joint lists and the
    // island walk follows those lists, so the solver meets a pair's joints in the reverse of the
    // array's order. DeepestLast writes the array deepest first (the solver meets the shallowest
    // first), DeepestFirst the reverse. Ordered by depth, the order follows the tilt of a resting
    // face and corrects it; a fixed order (the importance order) pushed 20-box stacks over in
    // every seed (docs/algorithm.md). Equal depths keep the importance order.
    std::array<Ranked, kMaxManifoldPoints + 1> ranked;  // deepest first from ranked[1]
    ranked[0] = Ranked{NAN, nullptr};
    const ContactPoint* points = manifold.points.data();
    const ContactPoint* pointsEnd = points + manifold.pointCount;
    const Ranked* last =
        checkedFinite
            ? write_contacts_detail::rankByDepth<true>(points, pointsEnd, -touchingTolerance, &ranked[0])
            : write_contacts_detail::rankByDepth<false>(points, pointsEnd, -touchingTolerance, &ranked[0]);
    // Touching points (depth ≤ 0, written as 0) are left out where the pair has overlapping ones,
    // as the body-pair budget does within a cluster (body_pair_reduction.cpp): such a row has a
    // right-hand side of exactly 0 and, between bodies resting together, a relative velocity of
    // exactly 0 — a tie ODE's Dantzig pivoting cannot break ("LCP internal error, s <= 0"; the
    // pyramid under dWorldStep printed it in 2 of 50 seeds). The overlapping points carry the
    // support; the touching one adds no force ODE would not get a step later, when it overlaps.
    // Measured over seeds (docs/algorithm.md, "Sleeping, over seeds"): no change in failures or
    // drift. The ranking is deepest first, so the touching points are its tail.
    if (last != &ranked[0] && ranked[1].depth > 0)
        while (!(last->depth > 0)) --last;
    const int written = std::min(static_cast<int>(last - &ranked[0]), maxContacts);

    // Every contact's fields as they lie in a dContactGeom, those all share made once: pos and
    // normal each as two pairs of doubles (the fourth is ODE's padding, 0), g1 and g2 as one pair,
    // in registers (GCC's and Clang's vector types: an array went through the stack). Stored in
    // pairs, a contact is seven stores instead of fourteen.
    using write_contacts_detail::DoublePair;
    using write_contacts_detail::WordPair;
    const DoublePair normalXY = {normal.x(), normal.y()}, normalZ0 = {normal.z(), 0.0};
    const WordPair geoms = {reinterpret_cast<std::uintptr_t>(o1), reinterpret_cast<std::uintptr_t>(o2)};
    // Walk the ranked entries forwards (DeepestLast) or backwards (DeepestFirst; and
    // DeepestFirstWhenLoaded where the deepest written, ranked[1], is deeper than loadedDepth):
    // one step, no index arithmetic per contact.
    const bool reverse = order == ContactOrder::DeepestFirst ||
                         (order == ContactOrder::DeepestFirstWhenLoaded && written > 0 && ranked[1].depth > loadedDepth);
    const Ranked* entry = reverse ? &ranked[written] : &ranked[1];
    const std::ptrdiff_t step = reverse ? -1 : 1;
    char* outBytes = reinterpret_cast<char*>(contact);
    if constexpr (!kOdeRealIsDouble) {
        // Single precision: each field rounded to dReal (a unit normal stays unit within float's
        // rounding, which ODE's own float colliders have too).
        for (int k = written; k > 0; --k, outBytes += skip, entry += step) {
            const Vec3& position = entry->point->position;
            dContactGeom* out = reinterpret_cast<dContactGeom*>(outBytes);
            for (int axis = 0; axis < 3; ++axis) {
                out->pos[axis] = static_cast<dReal>(position[axis]);
                out->normal[axis] = static_cast<dReal>(normal[axis]);
            }
            out->pos[3] = 0;
            out->normal[3] = 0;
            out->depth = static_cast<dReal>(0.0 > entry->depth ? 0.0 : entry->depth);
            out->g1 = o1;
            out->g2 = o2;
            out->side1 = -1;
            out->side2 = -1;
        }
    } else {
        for (int k = written; k > 0; --k, outBytes += skip, entry += step) {
            const Vec3& position = entry->point->position;
            const DoublePair positionXY = {position.x(), position.y()}, positionZ0 = {position.z(), 0.0};
            std::memcpy(outBytes + offsetof(dContactGeom, pos), &positionXY, sizeof positionXY);
            std::memcpy(outBytes + offsetof(dContactGeom, pos) + sizeof positionXY, &positionZ0, sizeof positionZ0);
            std::memcpy(outBytes + offsetof(dContactGeom, normal), &normalXY, sizeof normalXY);
            std::memcpy(outBytes + offsetof(dContactGeom, normal) + sizeof normalXY, &normalZ0, sizeof normalZ0);
            dContactGeom* out = reinterpret_cast<dContactGeom*>(outBytes);
            // std::max(depth, 0.0) as x86's maxsd computes it (0.0 where 0.0 > depth, else depth: −0.0
            // stays −0.0), one instruction in place of a compare and a branch.
            out->depth = 0.0 > entry->depth ? 0.0 : entry->depth;
            std::memcpy(outBytes + offsetof(dContactGeom, g1), &geoms, sizeof geoms);
            out->side1 = -1;
            out->side2 = -1;
        }
    }
    return written;
}

}  // namespace gdc::ode::detail
