// The adapter's writeContacts as it was at ac53fc8 (src/ode/collide.cpp), kept verbatim but for
// its namespace and `inline`: tests/ode/adapter_equality_test.cpp holds the current one
// (src/ode/write_contacts.hpp) against it, byte for byte.
#pragma once

#include <gdcontact/manifold.hpp>
#include <gdcontact/settings.hpp>

#include <ode/ode.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace gdc::ode::reference {

// Vec3::allFinite without the reduction machinery: x − x is 0 exactly for a finite x, NaN else.
inline bool isFinite(const Vec3& v) { return (v.x() - v.x()) + (v.y() - v.y()) + (v.z() - v.z()) == 0.0; }

// The core's contacts as ODE's: at most maxContacts, written in place at stride `skip`, in the
// order that makes dWorldQuickStep meet them as `order` says. `flip`: the core's A is o2 (its
// normal then already points from o2 into o1).
// `checkedFinite`: the core's own answer (not one a pair cache carried), whose every position the
// core has checked finite (every answer it computes is written by emitManifold or the plane
// contacts, which throw where a contact overflows), so the test below would pass.
inline int writeContacts(const Manifold& manifold, bool flip, double sizeOfPair, int maxContacts, ContactOrder order,
                         dGeomID o1, dGeomID o2, dContactGeom* contact, int skip, bool checkedFinite) {
    // The core's normal points from A towards B; ODE's from o2 into o1.
    Vec3 normal = flip ? manifold.normal : Vec3(-manifold.normal);
    // norm() is the square root of squaredNorm(): where that is exactly 1 (the common case) the
    // root is 1 and the division changes no bit, so both are skipped.
    const double squaredLength = normal.squaredNorm();
    if (squaredLength != 1.0) {
        const double length = std::sqrt(squaredLength);
        if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-6) {
            dMessage(d_ERR_UNKNOWN, "gdcontact: the core returned an invalid normal; pair skipped");
            return 0;
        }
        normal /= length;
    }

    // ODE treats every contact as active and clamps a negative depth to zero, so a speculative
    // point (depth < 0, only with Settings::margin > 0) would hold the bodies apart by its gap.
    // Such points are not passed on; a rounding-level negative depth is reported as touching.
    const double touchingTolerance = 1e-9 * sizeOfPair;
    // The core's points come in the order of importance (the deepest first; every prefix the best
    // of its length), already reduced to maxContacts: the set is the best of its size. The ORDER
    // is by depth, for dWorldQuickStep, which solves rows in the order they arrive: ODE's
    // dJointAttach puts each new contact joint at the head of its bodies' joint lists and the
    // island walk follows those lists, so the solver meets a pair's joints in the reverse of the
    // array's order. DeepestLast writes the array deepest first (the solver meets the shallowest
    // first), DeepestFirst the reverse. Ordered by depth, the order follows the tilt of a resting
    // face and corrects it; a fixed order (the importance order) pushed 20-box stacks over in
    // every seed (docs/algorithm.md). Equal depths keep the importance order. Kept points are
    // inserted by depth as they are read; at most 16, so an insertion sort of (depth, index)
    // pairs is the cheapest. Slot 0 holds NaN, which no comparison passes, so the inner loop needs
    // no bound check (a kept depth is never NaN).
    struct Ranked {
        double depth;
        int index;
    };
    std::array<Ranked, kMaxManifoldPoints + 1> ranked;  // deepest first from ranked[1]
    ranked[0] = Ranked{NAN, -1};
    int kept = 0;
    for (int i = 0; i < manifold.pointCount; ++i) {
        const ContactPoint& point = manifold.points[i];
        const double depth = point.depth;
        if (!(depth >= -touchingTolerance && (checkedFinite || isFinite(point.position)))) continue;
        Ranked* slot = &ranked[++kept];  // a pointer walk: indices made g++ unroll into index arithmetic
        for (; depth > slot[-1].depth; --slot) *slot = slot[-1];
        *slot = Ranked{depth, i};
    }
    // Touching points (depth ≤ 0, written as 0) are left out where the pair has overlapping ones,
    // as the body-pair budget does within a cluster (body_pair_reduction.cpp): such a row has a
    // right-hand side of exactly 0 and, between bodies resting together, a relative velocity of
    // exactly 0 — a tie ODE's Dantzig pivoting cannot break ("LCP internal error, s <= 0"; the
    // pyramid under dWorldStep printed it in 2 of 50 seeds). The overlapping points carry the
    // support; the touching one adds no force ODE would not get a step later, when it overlaps.
    // Measured over seeds (docs/algorithm.md, "Sleeping, over seeds"): no change in failures or
    // drift. The ranking is deepest first, so the touching points are its tail.
    if (kept > 0 && ranked[1].depth > 0)
        while (!(ranked[kept].depth > 0)) --kept;
    const int written = std::min(kept, maxContacts);
    // Walk the ranked entries forwards (DeepestLast) or backwards (DeepestFirst): one step, no
    // index arithmetic per contact.
    const bool reverse = order == ContactOrder::DeepestFirst;
    const Ranked* entry = reverse ? &ranked[written] : &ranked[1];
    const std::ptrdiff_t step = reverse ? -1 : 1;
    const double nx = normal.x(), ny = normal.y(), nz = normal.z();
    const ContactPoint* points = manifold.points.data();
    char* outBytes = reinterpret_cast<char*>(contact);
    for (int k = 0; k < written; ++k, outBytes += skip, entry += step) {
        const Vec3& position = points[entry->index].position;
        dContactGeom* out = reinterpret_cast<dContactGeom*>(outBytes);
        out->pos[0] = position.x();
        out->pos[1] = position.y();
        out->pos[2] = position.z();
        out->pos[3] = 0;
        out->normal[0] = nx;
        out->normal[1] = ny;
        out->normal[2] = nz;
        out->normal[3] = 0;
        out->depth = std::max(entry->depth, 0.0);
        out->g1 = o1;
        out->g2 = o2;
        out->side1 = -1;
        out->side2 = -1;
    }
    return written;
}

}  // namespace gdc::ode::reference
