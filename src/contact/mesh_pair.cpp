// A convex polytope on a triangle mesh (triangle_mesh.hpp): the mid phase picks the triangles the
// polytope's bounds reach; each is a shape of the pair table (TriangleMesh::trianglePrism: its face
// extruded behind it, so that every stage applies as to any hull), and the mesh adds what a triangle knows
// beyond that: which side is its front, and which of its edges are inactive. The triangles'
// contacts become one manifold by the per-body-pair rule.
#include <gdcontact/triangle_mesh.hpp>

#include "contact/feature_geometry.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/gauss_map.hpp"
#include "contact/pair_table.hpp"

#include <algorithm>
#include <cmath>

namespace gdc {
namespace {

using namespace detail;  // the stages' internals this file composes

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

// A's side of the contacts along one face normal: its Gauss-map feature there, in its own frame.
// Every triangle of a flat region has the same normal, so the feature is found once for all of
// them (`normal` remembers which it is for).
struct FeatureAlong {
    Vec3 normal = Vec3::Zero();  // A's frame, from A towards the mesh; zero: none yet
    FeatureGeometry geometry;
    SmallVector<int, 8> pieces;
    void place(const Polytope& a, const Vec3& towardsMesh, const AngularTolerance& tolerance) {
        if (towardsMesh == normal) return;
        normal = towardsMesh;
        const Feature feature = selectFeature(a, towardsMesh, a.supportVertex(towardsMesh), tolerance);
        featurePieces(a, feature, towardsMesh, tolerance, pieces);
        geometry = featureGeometry(a, feature, pieces, Pose{}, a.vertices().data());
    }
};

// Whether x and y coincide seen along `up` (unit), to `tolerance`.
bool sameAlong(const Vec3& x, const Vec3& y, const Vec3& up, double tolerance) {
    const Vec3 apart = x - y;
    return (apart - apart.dot(up) * up).squaredNorm() <= tolerance * tolerance;
}

// Drops from points[first, end) those that lie on a seam of triangle t — an edge whose neighbour
// has the same normal to 1e-12, so that the two triangles' points join one cluster — unless they
// are a vertex of A's feature. Such a point lies inside the region A's feature has on the flat
// surface, or on its boundary between two of its vertices; the depth along a plane is affine, so
// it is never the deepest or an extreme of the region: the body-pair reduction would only spend
// its time on it (a resting box on half-metre cells brings some forty of them).
void dropSeamPoints(const TriangleMesh& mesh, int t, const FeatureGeometry& face, const FeatureGeometry& feature,
                    const Vec3& up, double tolerance, LiftedPoints& points, std::size_t first) {
    bool seam[3];
    bool anySeam = false;
    for (int e = 0; e < 3; ++e) {
        const int u = mesh.neighbour(t, e);
        seam[e] = u >= 0 && !mesh.edgeActive(t, e) && mesh.triangleNormal(t).dot(mesh.triangleNormal(u)) >= 1 - 1e-12;
        anySeam = anySeam || seam[e];
    }
    if (!anySeam) return;
    auto onSeam = [&](const Vec3& x) {
        for (int e = 0; e < 3; ++e) {
            if (!seam[e]) continue;
            const Vec3& p = face.points[e];
            const Vec3 edge = face.points[(e + 1) % 3] - p;
            if (std::abs((x - p).cross(edge).dot(up)) <= tolerance * edge.norm()) return true;
        }
        return false;
    };
    auto featureVertex = [&](const Vec3& x) {
        for (const Vec3& vertex : feature.points)
            if (sameAlong(x, vertex, up, tolerance)) return true;
        for (const FeatureGeometry& piece : feature.capFaces)
            for (const Vec3& vertex : piece.points)
                if (sameAlong(x, vertex, up, tolerance)) return true;
        return false;
    };
    std::size_t kept = first;
    for (std::size_t i = first; i < points.size(); ++i)
        if (!onSeam(points[i].position) || featureVertex(points[i].position)) points[kept++] = points[i];
    points.setSize(kept);
}

// Triangle t's contacts along its face normal, appended: A's feature along it intersected with the
// face in the contact plane (stage 3), each point with its own depth — what the plane of the face
// gives, clipped to the triangle. No depth confirmation: A's deepest point may lie beyond this
// triangle, over the neighbour that reports it.
void appendAlongFace(const Polytope& a, const TriangleMesh& mesh, const Pose& meshInA, int t,
                     const AngularTolerance& angularTolerance, const Settings& settings, FeatureAlong& along,
                     LiftedPoints& points) {
    const Vec3 up = meshInA.rotation * mesh.triangleNormal(t);  // A's frame, from the face towards A
    along.place(a, -up, angularTolerance);
    FeatureGeometry face;
    face.type = FeatureType::Face;
    double size = a.radius();
    for (int corner : mesh.triangle(t)) {
        face.points.push_back(meshInA.apply(mesh.vertices()[corner]));
        size = std::max(size, (face.points.back() - face.points[0]).norm());
    }
    face.planeNormal = up;
    face.planeOffset = up.dot(face.points[0]);
    const double tolerance = 1e-9 * size;
    const std::size_t first = points.size();
    intersectFeatures(view(along.geometry), view(face), -up, tolerance, -settings.margin, settings.spanContactRegion,
                      points);
    dropSeamPoints(mesh, t, face, along.geometry, up, tolerance, points, first);
}

}  // namespace

void collide(const Polytope& a, const Pose& poseA, const TriangleMesh& mesh, const Pose& poseMesh,
             const Settings& settings, std::vector<MeshContact>& out) {
    out.clear();
    if (!poseA.isFinite()) throwPoseNotFinite("A");
    if (!poseMesh.isFinite()) throwPoseNotFinite("B (the mesh)");
    // A's bounds in the mesh's frame, exact: its supports along the mesh's axes (a resting box's
    // are its footprint, where the ball about its centroid would reach twice as many triangles),
    // grown by the margin.
    const Vec3 centreWorld = poseA.apply(a.centroid());
    const Vec3 centre = poseMesh.applyInverse(centreWorld);
    const Pose meshInA = poseA.relative(poseMesh);
    const Pose aInMesh = poseMesh.relative(poseA);
    const double grown = std::max(settings.margin, 0.0);
    Aabb bounds;
    for (int axis = 0; axis < 3; ++axis) {
        const Vec3 along = meshInA.rotation.col(axis);  // the mesh's axis in A's frame
        bounds.upper[axis] = aInMesh.apply(a.vertices()[a.supportVertex(along)])[axis] + grown;
        bounds.lower[axis] = aInMesh.apply(a.vertices()[a.supportVertex(-along)])[axis] - grown;
    }
    const double reach = a.radius() + grown;
    std::vector<int> triangles;
    mesh.overlapping(bounds, triangles);
    if (triangles.empty()) return;

    const double cosine = std::cos(settings.angularTolerance), sine = std::sin(settings.angularTolerance);
    std::vector<BodyPairContact> contacts;
    std::vector<int> from;  // each contact's triangle
    Manifold manifold;
    const AngularTolerance angularTolerance(settings.angularTolerance);
    FeatureAlong along;
    LiftedPoints lifted;
    for (int t : triangles) {
        const Vec3& n = mesh.triangleNormal(t);
        const std::array<int, 3>& corners = mesh.triangle(t);
        const double aboveFace = n.dot(centre - mesh.vertices()[corners[0]]);
        if (aboveFace > reach || aboveFace < -a.radius()) continue;  // wholly in front (beyond the margin) or behind
        // The face's normal wherever the triangle's feature is its face or an inactive edge or vertex:
        // then the mesh answers as the plane of its face would, clipped to the triangle. A triangle
        // none of whose edges is active (inside a flat region) has no other feature: the growth
        // distance is not asked.
        const bool anyActiveEdge = mesh.edgeActive(t, 0) || mesh.edgeActive(t, 1) || mesh.edgeActive(t, 2);
        bool alongFace = !anyActiveEdge;
        if (anyActiveEdge) {
            collidePair(Shape::of(a), poseA, Shape::of(mesh.trianglePrism(t)), poseMesh, PairQuery{settings}, manifold);
            if (manifold.empty()) continue;
            const Vec3 outward = -(poseMesh.rotation.transpose() * manifold.normal);  // triangle → A
            const double cosineToFace = outward.dot(n);
            alongFace = cosineToFace >= cosine || !featureIsActive(mesh, t, outward, sine);
            // An active edge's or vertex's normal out of the triangle's back or sides: the shape is
            // behind the surface there (or beside its boundary), where a one-sided mesh has nothing.
            if (!alongFace && !(cosineToFace > 1e-9)) continue;
        }
        if (alongFace) {  // the face's normal (see featureIsActive)
            lifted.clear();
            appendAlongFace(a, mesh, meshInA, t, angularTolerance, settings, along, lifted);
            const Vec3 normal = -(poseMesh.rotation * n);  // from A towards the mesh
            for (const LiftedPoint& point : lifted) {
                contacts.push_back({poseA.apply(point.position), -normal, point.depth});
                from.push_back(t);
            }
            continue;
        }
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
