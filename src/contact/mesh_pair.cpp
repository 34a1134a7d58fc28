// A convex polytope on a triangle mesh (triangle_mesh.hpp): the mid phase picks the triangles the
// polytope's bounds reach; each is a shape of the pair table (TriangleMesh::trianglePrism: its face
// extruded behind it, so that every stage applies as to any hull), and the mesh adds what a triangle knows
// beyond that: which side is its front, and which of its edges are inactive. The triangles'
// contacts become one manifold by the per-body-pair rule.
#include <gdcontact/triangle_mesh.hpp>

#include "contact/collide_general.hpp"
#include "contact/pair_table.hpp"

#include <algorithm>
#include <cmath>

namespace gdc {
namespace {

// Whether the triangle's Gauss-map feature along `outward` (the mesh's frame, from the triangle
// towards the shape, not within the tolerance of the face normal) is an active edge, or a vertex
// with an active edge: an inactive one — between coplanar or concave triangles — is no feature of
// the surface, only of how it was cut into triangles.
bool featureIsActive(const TriangleMesh& mesh, int t, const Vec3& outward, double sine) {
    const std::array<int, 3>& corners = mesh.triangle(t);
    const std::vector<Vec3>& v = mesh.vertices();
    int top = 0;
    for (int i = 1; i < 3; ++i)
        if (outward.dot(v[corners[i]]) > outward.dot(v[corners[top]])) top = i;
    // The edges at the top vertex: e from corner e to corner e + 1, so `top` and the one before it.
    int edge = -1;
    double straightest = sine;
    for (int e : {top, (top + 2) % 3}) {
        const Vec3 along = (v[corners[(e + 1) % 3]] - v[corners[e]]).normalized();
        const double off = std::abs(outward.dot(along));
        if (off <= straightest) straightest = off, edge = e;
    }
    if (edge >= 0) return mesh.edgeActive(t, edge);
    return mesh.edgeActive(t, top) || mesh.edgeActive(t, (top + 2) % 3);
}

}  // namespace

void collide(const Polytope& a, const Pose& poseA, const TriangleMesh& mesh, const Pose& poseMesh,
             const Settings& settings, std::vector<MeshContact>& out) {
    out.clear();
    if (!poseA.isFinite()) detail::throwPoseNotFinite("A");
    if (!poseMesh.isFinite()) detail::throwPoseNotFinite("B (the mesh)");
    // A's bounds in the mesh's frame: the ball about its centroid through its farthest vertex.
    const Vec3 centreWorld = poseA.apply(a.centroid());
    const Vec3 centre = poseMesh.applyInverse(centreWorld);
    const double reach = a.radius() + std::max(settings.margin, 0.0);
    std::vector<int> triangles;
    mesh.overlapping({centre.array() - reach, centre.array() + reach}, triangles);
    if (triangles.empty()) return;

    const double cosine = std::cos(settings.angularTolerance), sine = std::sin(settings.angularTolerance);
    std::vector<BodyPairContact> contacts;
    std::vector<int> from;  // each contact's triangle
    Manifold manifold;
    for (int t : triangles) {
        const Vec3& n = mesh.triangleNormal(t);
        const std::array<int, 3>& corners = mesh.triangle(t);
        const double aboveFace = n.dot(centre - mesh.vertices()[corners[0]]);
        if (aboveFace > reach || aboveFace < -a.radius()) continue;  // wholly in front (beyond the margin) or behind
        const Polytope& prism = mesh.trianglePrism(t);
        const Vec3 faceNormal = -(poseMesh.rotation * n);  // from A towards the triangle, as a manifold's
        // The face's normal wherever the triangle's feature is its face or an inactive edge or vertex:
        // then the mesh answers as the plane of its face would, clipped to the triangle. A triangle
        // none of whose edges is active (inside a flat region) has no other feature: the growth
        // distance is not asked.
        const bool anyActiveEdge = mesh.edgeActive(t, 0) || mesh.edgeActive(t, 1) || mesh.edgeActive(t, 2);
        bool alongFace = !anyActiveEdge;
        if (anyActiveEdge) {
            detail::collidePair(detail::Shape::of(a), poseA, detail::Shape::of(prism), poseMesh,
                                detail::PairQuery{settings}, manifold);
            if (manifold.empty()) continue;
            const Vec3 outward = -(poseMesh.rotation.transpose() * manifold.normal);  // triangle → A
            const double cosineToFace = outward.dot(n);
            alongFace = cosineToFace >= cosine || !featureIsActive(mesh, t, outward, sine);
            // An active edge's or vertex's normal out of the triangle's back or sides: the shape is
            // behind the surface there (or beside its boundary), where a one-sided mesh has nothing.
            if (!alongFace && !(cosineToFace > 1e-9)) continue;
        }
        if (alongFace) detail::collideAlongInto(a, poseA, prism, poseMesh, faceNormal, settings, manifold);
        for (int i = 0; i < manifold.pointCount; ++i) {
            contacts.push_back({manifold.points[i].position, -manifold.normal, manifold.points[i].depth});
            from.push_back(t);
        }
    }
    if (contacts.empty()) return;
    BodyPairFrame frame;
    frame.centreA = centreWorld;
    frame.hasCentreA = true;
    std::vector<int> kept;
    const int count = reduceBodyPairContacts(contacts.data(), static_cast<int>(contacts.size()), frame, settings, kept);
    out.reserve(count);
    for (int k = 0; k < count; ++k) {
        const BodyPairContact& contact = contacts[kept[k]];
        out.push_back({contact.position, -contact.normal, contact.depth, from[kept[k]]});
    }
}

}  // namespace gdc
