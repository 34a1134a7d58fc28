// Box–, convex–, capsule– and cylinder–trimesh pairs: resolved as collide.cpp resolves its pairs, collided by the
// core's mesh query (gdc::collide with a TriangleMesh), written as ODE's contacts
// (trimesh_geoms.hpp).
#include "trimesh_geoms.hpp"

#include "box_cache.hpp"
#include "convex_geoms.hpp"
#include "geom_reading.hpp"
#include "ode_real.hpp"
#include "round_geoms.hpp"
#include "write_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gdc::ode::detail {
namespace {

// The vectors of one call, reused by the thread's calls. A dTriCallback may call dCollide on the
// same thread: the inner call then finds them in use and takes vectors of its own.
struct MeshScratch {
    std::vector<MeshContact> contacts;
    std::vector<int> triangles;                // the array callback's candidates
    std::vector<std::pair<double, int>> kept;  // (depth, contact index)
    bool busy = false;
};

class ScratchLease {
public:
    ScratchLease() {
        thread_local MeshScratch shared;
        if (!shared.busy) {
            scratch_ = &shared;
            shared.busy = true;
        } else {
            own_ = std::make_unique<MeshScratch>();
            scratch_ = own_.get();
        }
    }
    ~ScratchLease() {
        if (!own_) scratch_->busy = false;
    }
    ScratchLease(const ScratchLease&) = delete;
    ScratchLease& operator=(const ScratchLease&) = delete;
    MeshScratch& operator*() const { return *scratch_; }

private:
    MeshScratch* scratch_ = nullptr;
    std::unique_ptr<MeshScratch> own_;
};

// The triangles whose bounds meet the shape's axis-aligned bounds in the mesh's frame (a polytope's
// vertices; a curved shape's ball about its centre): what the geom's dTriArrayCallback gets, as
// ODE's colliders give it the triangles their bounding-volume query found.
void candidateTriangles(const ResolvedPair& pair, const TriangleMesh& mesh, std::vector<int>& out) {
    const Pose relative = pair.pose2().relative(pair.pose1());
    Aabb box;
    if (pair.polytope1) {
        box.lower = Vec3::Constant(INFINITY);
        box.upper = -box.lower;
        for (const Vec3& vertex : pair.polytope1->vertices()) {
            const Vec3 p = relative.apply(vertex);
            box.lower = box.lower.cwiseMin(p);
            box.upper = box.upper.cwiseMax(p);
        }
    } else {
        const double reach = roundRadius(pair.kind1, pair.round1);
        box.lower = relative.position.array() - reach;
        box.upper = relative.position.array() + reach;
    }
    out.clear();
    mesh.overlapping(box, out);
}

// The geom's dTriCallback as the core's triangle filter.
struct CallbackFilter {
    dTriCallback* callback;
    dGeomID meshGeom, other;
    static bool accepts(void* context, int t) {
        const CallbackFilter& filter = *static_cast<const CallbackFilter*>(context);
        return filter.callback(filter.meshGeom, filter.other, t) != 0;
    }
};

// The other geom of a Mesh pair as the core's query takes it.
ShapeRef shapeOf(const ResolvedPair& pair) {
    if (pair.polytope1) return *pair.polytope1;
    const gdc::detail::RoundShape& round = pair.round1;
    switch (pair.kind1) {
        case gdc::detail::ShapeKind::Capsule: return Capsule{round.radius, 2 * round.halfLength};
        case gdc::detail::ShapeKind::Cylinder: return Cylinder{round.radius, 2 * round.halfLength};
        default: return Sphere{round.radius};
    }
}

bool isValid(const MeshContact& c) {
    return c.position.allFinite() && std::isfinite(c.depth) &&
           std::abs(c.normal.norm() - 1.0) <= inputRelativeTolerance(1e-6);
}

}  // namespace

bool resolveMeshPair(const Settings& settings, ThreadCache& cache, ResolvedPair& out) {
    using Kind = ResolvedPair::Kind;
    if (!isGdcontactPair(out.class1, out.class2))
        dError(d_ERR_UASSERT, "%s",
               (std::string("gdcontact: gdc::ode::collide takes a trimesh with a box, a convex, a capsule or a "
                            "cylinder only; it got ") +
                className(out.class1) + " and " + className(out.class2) +
                " (leave that pair to ODE: install() overrides only the supported pairs)")
                   .c_str());
    const bool meshFirst = out.class1 == dTriMeshClass;
    const dGeomID other = meshFirst ? out.o2 : out.o1;
    const int otherClass = meshFirst ? out.class2 : out.class1;
    readPoseInto(other, out.pose1());
    readPoseInto(meshFirst ? out.o1 : out.o2, out.pose2());
    out.flip = meshFirst;
    out.plane = nullptr;
    out.polytope1 = nullptr;  // a reused pair (spaceCollide's slots) may hold an earlier pair's
    if (isRoundClass(otherClass)) {
        readRound(other, otherClass, out.kind1, out.round1);
    } else if (otherClass == dBoxClass) {
        dVector3 lengths;
        dGeomBoxGetLengths(other, lengths);
        out.polytope1 = &borrowedBoxPolytope(cache, lengths);
    } else {
        bool unregistered = false;
        out.polytope1 = knownHull(other, out.pose1(), settings, cache, unregistered);
        if (!out.polytope1) {
            out.kind = Kind::Ode;
            return !unregistered;
        }
    }
    out.kind = Kind::Mesh;
    return true;
}

int collideMeshPair(const ResolvedPair& pair, int maxContacts, dContactGeom* contact, int skip,
                    const Settings& settings) {
    const bool meshFirst = pair.flip;
    const dGeomID meshGeom = meshFirst ? pair.o1 : pair.o2;
    const dGeomID other = meshFirst ? pair.o2 : pair.o1;
    // The other geom's bounding radius (the touching tolerance, the loaded depth).
    const double radius = pair.polytope1 ? pair.polytope1->radius() : roundRadius(pair.kind1, pair.round1);
    const Pose& pose = pair.pose1();
    const Pose& meshPose = pair.pose2();
    // Held for the call: a rebuild by another thread cannot take it away meanwhile.
    const std::shared_ptr<const TriangleMesh> mesh = trimeshOf(meshGeom, meshPose, settings);
    if (!mesh) return 0;

    const ScratchLease lease;
    MeshScratch& scratch = *lease;
    if (dTriArrayCallback* arrayCallback = dGeomTriMeshGetArrayCallback(meshGeom)) {
        candidateTriangles(pair, *mesh, scratch.triangles);
        if (!scratch.triangles.empty())
            arrayCallback(meshGeom, other, scratch.triangles.data(), static_cast<int>(scratch.triangles.size()));
    }
    // The core's call is the same for either order of o1 and o2 (the shape A, the mesh B): the
    // answers of collide(a,b) and collide(b,a) are exact mirrors. The geom's dTriCallback, if any,
    // is the core's triangle filter: a triangle it rejects takes no place in the reduction.
    std::vector<MeshContact>& contacts = scratch.contacts;
    CallbackFilter callback{dGeomTriMeshGetCallback(meshGeom), meshGeom, other};
    TriangleFilter filter;
    if (callback.callback) filter = {&CallbackFilter::accepts, &callback};
    gdc::collide(shapeOf(pair), pose, *mesh, meshPose, settings, contacts, filter);
    if (contacts.empty()) return 0;

    // Kept: valid, not speculative (ODE would hold the bodies apart by the gap; a rounding-level
    // negative depth is touching, written as 0).
    scratch.kept.clear();
    const double touching = inputRelativeTolerance(1e-9) * 2.0 * radius;
    bool overlapping = false;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        const MeshContact& c = contacts[i];
        if (!(c.depth >= -touching) || !isValid(c)) continue;
        scratch.kept.emplace_back(c.depth, static_cast<int>(i));
        overlapping = overlapping || c.depth > 0;
    }
    // Touching points are left out where the pair has overlapping ones (as writeContacts does: a
    // row of exactly zero residual stalls ODE's Dantzig solver).
    std::vector<std::pair<double, int>>& kept = scratch.kept;
    if (overlapping)
        kept.erase(std::remove_if(kept.begin(), kept.end(), [](const auto& k) { return !(k.first > 0); }), kept.end());
    // The deepest, deepest first; equal depths in the core's order (by triangle).
    std::stable_sort(kept.begin(), kept.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const int written = std::min(static_cast<int>(kept.size()), maxContacts);
    if (written <= 0) return 0;
    const ContactOrder order = settings.contactOrder;
    const bool reverse =
        order == ContactOrder::DeepestFirst ||
        (order == ContactOrder::DeepestFirstWhenLoaded && kept[0].first > loadedDepthOf(settings, radius, 0.0));

    char* bytes = reinterpret_cast<char*>(contact);
    for (int k = 0; k < written; ++k) {
        const MeshContact& c = contacts[static_cast<std::size_t>(kept[static_cast<std::size_t>(reverse ? written - 1 - k : k)].second)];
        // The core's normal points from the shape towards the mesh; ODE's from o2 into o1.
        const Vec3 normal = (meshFirst ? c.normal : Vec3(-c.normal)).normalized();
        dContactGeom& out = *reinterpret_cast<dContactGeom*>(bytes + static_cast<std::ptrdiff_t>(k) * skip);
        for (int axis = 0; axis < 3; ++axis) {
            out.pos[axis] = static_cast<dReal>(c.position[axis]);
            out.normal[axis] = static_cast<dReal>(normal[axis]);
        }
        out.pos[3] = 0;
        out.normal[3] = 0;
        out.depth = static_cast<dReal>(std::max(c.depth, 0.0));
        out.g1 = pair.o1;
        out.g2 = pair.o2;
        out.side1 = meshFirst ? c.triangle : -1;
        out.side2 = meshFirst ? -1 : c.triangle;
    }
    return written;
}

}  // namespace gdc::ode::detail
