// A convex shape on a triangle mesh (triangle_mesh.hpp): the mid phase picks the triangles the
// shape's bounds reach; each is a shape of the pair table (TriangleMesh::trianglePrism: its face
// extruded behind it, so that every stage applies as to any hull), and the mesh adds what a
// triangle knows beyond that: which side is its front, which of its edges are inactive, and which
// are seams inside a flat region. The triangles' contacts become one manifold by the per-body-pair
// rule.
#include <gdcontact/triangle_mesh.hpp>

#include "contact/disc_intersection.hpp"
#include "contact/pair_table.hpp"
#include "contact/shape_body.hpp"
#include "shapes/mesh_arrays.hpp"

#include <algorithm>
#include <cmath>

namespace gdc {
namespace {

using namespace detail;  // the stages' internals this file composes

// Whether the growth distance's normal `outward` (the mesh's frame, from triangle t towards the
// shape, not within the tolerance of the face normal) is a normal the surface has there: the
// triangle's Gauss-map feature along it is an active edge and the normal lies on the edge's arc of
// the surface's normals (between the two faces' normals; any that leans out over a boundary edge),
// or a vertex both of whose edges in the triangle are active (a corner of the rim, a peak). Not
// otherwise: an inactive edge, between coplanar or concave triangles, is no feature of the surface,
// only of how it was cut into triangles; a vertex with an inactive edge lies on a straight ridge
// or a flat region's rim, where the surface's normals are an edge's or the face's; and a normal
// beyond a ridge's arc (a prism's side) leans over a face the surface does not have. The triangle
// then answers with its face's normal (Jolt's rule for inactive edges, with the arc).
bool keepsGrowthNormal(const MeshArrays& mesh, int t, const Vec3& outward, double sine) {
    const std::array<int, 3>& corners = mesh.triangle(t);
    const Vec3* v = mesh.vertices();
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
    if (edge < 0) return mesh.edgeActive(t, top) && mesh.edgeActive(t, (top + 2) % 3);
    if (!mesh.edgeActive(t, edge)) return false;
    const int u = mesh.neighbour(t, edge);
    if (u < 0) return true;
    // On the arc from n_t to n_u (both unit, the normal all but perpendicular to the edge): no
    // farther from either than they are from each other, to rounding. A normal beyond n_u is within
    // the tolerance of u's face or past it: that face, not this edge, is the surface's feature.
    const Vec3 &nt = mesh.triangleNormal(t), &nu = mesh.triangleNormal(u);
    const double between = nt.dot(nu);
    return outward.dot(nt) >= between - 1e-9 && outward.dot(nu) >= between - 1e-9;
}

// Which edges of triangle t are seams: inactive, and the neighbour's normal the same to 1e-12, so
// that the two triangles' points join one cluster of the body-pair reduction.
std::array<bool, 3> seamsOf(const MeshArrays& mesh, int t) {
    std::array<bool, 3> seam{};
    for (int e = 0; e < 3; ++e) {
        const int u = mesh.neighbour(t, e);
        seam[e] = u >= 0 && !mesh.edgeActive(t, e) && mesh.triangleNormal(t).dot(mesh.triangleNormal(u)) >= 1 - 1e-12;
    }
    return seam;
}

// Whether x and y coincide seen along `up` (unit), to `tolerance`.
bool sameAlong(const Vec3& x, const Vec3& y, const Vec3& up, double tolerance) {
    const Vec3 apart = x - y;
    return (apart - apart.dot(up) * up).squaredNorm() <= tolerance * tolerance;
}

// Whether the edge e of triangle t into its neighbour u folds up: u's far corner lies in front of
// t's plane. An inactive edge is concave or within the angular tolerance of flat either way; only a
// concave one has the solid below it as the union of the two sides.
bool concave(const MeshArrays& mesh, int t, int e, int u) {
    const Vec3* v = mesh.vertices();
    const Vec3& a = v[mesh.triangle(t)[e]];
    const Vec3& b = v[mesh.triangle(t)[(e + 1) % 3]];
    double farthest = 0;
    for (int corner : mesh.triangle(u)) {
        const Vec3& w = v[corner];
        if (w != a && w != b) farthest = mesh.triangleNormal(t).dot(w - a);
    }
    return farthest > 0;
}

// The triangle's face (corners in A's frame, counter-clockwise seen along `up`) with each edge into a
// valley — inactive, not a seam: the neighbour rises beyond it — moved out in the face's plane by
// as much as a shape `depth` below the plane can need. Below a valley the solid is the union of
// what lies below each side's plane, so a point below this face's plane just beyond such an edge is
// inside it; clipped at the edge, a shape sunk into the valley has points below both sides that
// project onto neither (each side's normal leans away from the other), and no contact. A point
// `depth` below the edge projects along this face's normal at most depth·tan(fold) beyond it (fold:
// the angle between the two normals), so the edge moves out by that (a fold over 80° by 80°'s): a
// strip that stays below the neighbour, never a reach over terrain beyond it. No triangle with a
// corner under 2° is widened: its moved edges would meet far off.
AnyFeature reachingOverValleys(const AnyFeature& face, const MeshArrays& mesh, int t, const std::array<bool, 3>& seam,
                               const Vec3& up, double depth, double tolerance) {
    if (!(depth > 0)) return face;
    double push[3];
    bool any = false;
    for (int e = 0; e < 3; ++e) {
        push[e] = 0;
        const int u = mesh.neighbour(t, e);
        if (seam[e] || mesh.edgeActive(t, e) || u < 0 || !concave(mesh, t, e, u)) continue;
        const double fold = std::acos(std::clamp(mesh.triangleNormal(t).dot(mesh.triangleNormal(u)), -1.0, 1.0));
        push[e] = depth * std::tan(std::min(fold, 1.4)) + tolerance;
        any = true;
    }
    if (!any) return face;
    const SmallVector<Vec3, 16>& corners = face.geometry.points;
    Vec3 outward[3];  // each edge's outward normal in the face's plane
    for (int e = 0; e < 3; ++e) outward[e] = (corners[(e + 1) % 3] - corners[e]).cross(up).normalized();
    AnyFeature widened = face;
    for (int k = 0; k < 3; ++k) {
        // Corner k where edge k − 1 and edge k meet, each line moved out by its push: x in the plane
        // with x·m₁ = d₁, x·m₂ = d₂.
        const int before = (k + 2) % 3;
        const double g = outward[before].dot(outward[k]), determinant = 1 - g * g;
        if (determinant < 1e-3) return face;
        const double a = (push[before] - g * push[k]) / determinant, b = (push[k] - g * push[before]) / determinant;
        widened.geometry.points[k] = corners[k] + a * outward[before] + b * outward[k];
    }
    return widened;
}

// The plane's points (A's feature lifted onto a plane) for the last plane asked: the triangles of
// a flat region share it, up to rounding in their normals and offsets.
struct PlanePoints {
    Vec3 normal = Vec3::Zero();  // zero: none yet
    double offset = 0;
    LiftedPoints points;
    bool holds(const Vec3& up, double upOffset, double tolerance) const {
        return std::abs(upOffset - offset) <= tolerance && (up - normal).squaredNorm() <= 1e-24;
    }
};

// Triangle t's contacts along its face normal, appended to `points` (A's frame): what the plane of
// the face gives — A's feature along the normal lifted onto it (`plane`: for a polytope its
// feature's vertices, for a cylinder's cap the regular polygon of the budget from its deepest rim
// point) — within the region the flat surface around the triangle covers. A triangle whose three
// edges are seams takes the plane's points over it. Any other triangle intersects A's feature with
// itself (stage 3), then drops the points on its seams that are not the plane's: such a point lies
// inside the flat region's contact area, or on its boundary between two of the plane's points, and
// the depth along a plane is affine, so it is never the deepest or an extreme of the area (and on
// a cap a crossing would move the points as the seams pass under it, where the plane's stay put).
// No depth confirmation: A's deepest point may lie over another triangle, which reports it.
void appendAlongFace(const AnyFeature& feature, const ShapeBody& body, const MeshArrays& mesh, const Pose& meshInA,
                     int t, const Settings& settings, PlanePoints& plane, LiftedPoints& points) {
    const Vec3 up = meshInA.rotation * mesh.triangleNormal(t);  // A's frame, from the face towards A
    Vec3 corners[3];
    double longest = 0;  // squared, from corner 0
    for (int i = 0; i < 3; ++i) {
        corners[i] = meshInA.apply(mesh.vertices()[mesh.triangle(t)[i]]);
        longest = std::max(longest, (corners[i] - corners[0]).squaredNorm());
    }
    const double planeOffset = up.dot(corners[0]);
    const double tolerance = 1e-9 * std::max(body.radius, std::sqrt(longest));
    auto intersect = [&](const AnyFeature& with, LiftedPoints& out) {
        intersectAnyFeatures(feature, with, -up, tolerance, -settings.margin, settings.spanContactRegion,
                             settings.rimPointsPerTurn, wholeRimPoints(settings), out);
    };
    if (!plane.holds(up, planeOffset, tolerance)) {
        plane.normal = up, plane.offset = planeOffset;
        plane.points.clear();
        intersect(planeFeature(PlaneInA{up, plane.offset}, body), plane.points);
    }
    const LiftedPoints& scratch = plane.points;
    const std::array<bool, 3> seam = seamsOf(mesh, t);
    // How far x lies inside edge e of the triangle seen along up (< 0: beyond it): along the edge's
    // unit inward normal in the face's plane, up × edge / |edge|.
    Vec3 inward[3];
    for (int e = 0; e < 3; ++e) inward[e] = up.cross(corners[(e + 1) % 3] - corners[e]).normalized();
    auto beyondEdge = [&](const Vec3& x, int e) { return inward[e].dot(x - corners[e]); };
    if (seam[0] && seam[1] && seam[2]) {
        for (const LiftedPoint& point : scratch)
            if (beyondEdge(point.position, 0) >= -tolerance && beyondEdge(point.position, 1) >= -tolerance &&
                beyondEdge(point.position, 2) >= -tolerance)
                points.push_back(point);
        return;
    }
    // Not inside a flat region: the triangle's own face, intersected with A's feature.
    AnyFeature face;
    face.geometry.type = FeatureType::Face;
    for (const Vec3& corner : corners) face.geometry.points.push_back(corner);
    face.geometry.planeNormal = up;
    face.geometry.planeOffset = planeOffset;
    const std::size_t first = points.size();
    double deepest = -INFINITY;  // how far A reaches below the face's plane: its plane points' depth
    for (const LiftedPoint& point : scratch) deepest = std::max(deepest, point.depth);
    intersect(reachingOverValleys(face, mesh, t, seam, up, deepest, tolerance), points);
    auto onSeam = [&](const Vec3& x) {
        for (int e = 0; e < 3; ++e)
            if (seam[e] && std::abs(beyondEdge(x, e)) <= tolerance) return true;
        return false;
    };
    auto planePoint = [&](const Vec3& x) {
        for (const LiftedPoint& point : scratch)
            if (sameAlong(x, point.position, up, tolerance)) return true;
        return false;
    };
    // Beyond two edges is beyond a corner: over triangles that meet this one at a vertex only, where
    // nothing says the surface is above this face's plane (the widened corners of two valley edges).
    auto beyondCorner = [&](const Vec3& x) {
        int beyond = 0;
        for (int e = 0; e < 3; ++e) beyond += beyondEdge(x, e) < -tolerance;
        return beyond > 1;
    };
    std::size_t kept = first;
    for (std::size_t i = first; i < points.size(); ++i)
        if ((!onSeam(points[i].position) || planePoint(points[i].position)) && !beyondCorner(points[i].position))
            points[kept++] = points[i];
    points.setSize(kept);
}

// A's feature along one normal (A's frame, towards the mesh). Every triangle of a flat region has
// the same normal, so it is found once for all of them.
struct FeatureAlong {
    Vec3 normal = Vec3::Zero();  // zero: none yet
    AnyFeature feature;
    const AnyFeature& at(const ShapeBody& body, const Vec3& towardsMesh, const AngularTolerance& tolerance) {
        if (towardsMesh != normal) normal = towardsMesh, feature = body.feature(towardsMesh, tolerance);
        return feature;
    }
};

// A polytope's vertices below triangle t's plane within its shadow (the mesh's frame, `aInMesh`
// placing A there), each a contact at its own depth along the triangle's normal, midway between
// the vertex and the plane: what the plane of that triangle says of them. The fallback of a query
// whose triangles found nothing although the shape is sunk into the mesh: deep in a surface that
// curves within the angular tolerance, A's feature along each triangle's normal can lie over
// another triangle, and that triangle's along its own normal elsewhere again.
void appendSunkVertices(const Polytope& polytope, const Pose& aInMesh, const MeshArrays& mesh, const Pose& poseMesh,
                        int t, std::vector<BodyPairContact>& contacts, std::vector<int>& from) {
    const Vec3& n = mesh.triangleNormal(t);
    const Vec3* v = mesh.vertices();
    const std::array<int, 3>& corners = mesh.triangle(t);
    for (const Vec3& vertex : polytope.vertices()) {
        const Vec3 p = aInMesh.apply(vertex);
        const double depth = n.dot(v[corners[0]] - p);
        if (!(depth > 0)) continue;
        bool inside = true;
        for (int e = 0; e < 3 && inside; ++e)
            inside = n.dot((v[corners[(e + 1) % 3]] - v[corners[e]]).cross(p - v[corners[e]])) >= 0;
        if (!inside) continue;
        contacts.push_back({poseMesh.apply(Vec3(p + 0.5 * depth * n)), poseMesh.rotation * n, depth});
        from.push_back(t);
    }
}

// The shape as the pair table takes it, its size checked where it enters.
Shape enterShape(const ShapeRef& a) {
    switch (a.kind()) {
        case ShapeRef::Kind::Polytope: return Shape::of(*a.polytope());
        case ShapeRef::Kind::HalfSpace: throw InvalidInput("a half-space is no shape to collide with a triangle mesh");
        default: return enterRound(a.kind(), a.radius(), a.length(), "A");
    }
}

}  // namespace

void collide(const ShapeRef& shapeA, const Pose& poseA, const TriangleMesh& mesh, const Pose& poseMesh,
             const Settings& settings, std::vector<MeshContact>& out, const TriangleFilter& filter) {
    out.clear();
    if (shapeA.kind() != ShapeRef::Kind::HalfSpace && !poseA.isFinite()) throwPoseNotFinite("A");
    if (!poseMesh.isFinite()) throwPoseNotFinite("B (the mesh)");
    const Shape shape = enterShape(shapeA);
    const ShapeBody body(shape, Pose{}, settings.bruteForceSupportLimit);  // in A's own frame
    // A's bounds in the mesh's frame, exact: its supports along the mesh's axes (a resting box's
    // are its footprint, where the ball about its centroid would reach twice as many triangles),
    // grown by the margin.
    const Pose meshInA = poseA.relative(poseMesh);
    const Pose aInMesh = poseMesh.relative(poseA);
    const double grown = std::max(settings.margin, 0.0);
    Aabb bounds;
    for (int axis = 0; axis < 3; ++axis) {
        const Vec3 along = meshInA.rotation.col(axis);  // the mesh's axis in A's frame
        bounds.upper[axis] = aInMesh.apply(body.support(along))[axis] + grown;
        bounds.lower[axis] = aInMesh.apply(body.support(-along))[axis] - grown;
    }
    std::vector<int> triangles;
    triangles.reserve(64);  // a resting body's few dozen: one allocation, not a growth per doubling
    mesh.overlapping(bounds, triangles);
    if (filter.accepts)
        triangles.erase(std::remove_if(triangles.begin(), triangles.end(),
                                       [&](int t) { return !filter.accepts(filter.context, t); }),
                        triangles.end());
    if (triangles.empty()) return;

    const Vec3 centreWorld = poseA.apply(body.centre);
    const Vec3 centre = aInMesh.apply(body.centre);
    const double reach = body.radius + grown;
    const double cosine = std::cos(settings.angularTolerance), sine = std::sin(settings.angularTolerance);
    const AngularTolerance angularTolerance(settings.angularTolerance);
    std::vector<BodyPairContact> contacts;
    std::vector<int> from;  // each contact's triangle
    contacts.reserve(32), from.reserve(32);
    Manifold manifold;
    FeatureAlong along;
    LiftedPoints lifted;
    PlanePoints plane;
    const MeshArrays arrays = meshArrays(mesh);
    // Whether A faces triangle t: not wholly in front beyond the margin, nor wholly behind. A shape
    // sunk through the face from the front but not through it — its centre behind, part of it
    // still in front — is pushed back out to the front: that is a body that went halfway through a
    // terrain in one step (a rock falling at 9 m/s moves 9 cm a step), and letting it go would drop
    // it out of the world (docs/meshes.md measures it). A shape that approaches the face from
    // behind is pushed through it alike: a one-sided mesh cannot tell the two apart.
    auto facing = [&](int t) {
        const double aboveFace = arrays.triangleNormal(t).dot(centre - arrays.vertices()[arrays.triangle(t)[0]]);
        return aboveFace <= reach && aboveFace >= -body.radius;
    };
    for (int t : triangles) {
        const Vec3& n = arrays.triangleNormal(t);
        if (!facing(t)) continue;
        // The face's normal wherever the triangle's feature is its face or an inactive edge or vertex:
        // then the mesh answers as the plane of its face would, clipped to the triangle. A triangle
        // none of whose edges is active (inside a flat region) has no other feature: the growth
        // distance is not asked.
        const bool anyActiveEdge = arrays.edgeActive(t, 0) || arrays.edgeActive(t, 1) || arrays.edgeActive(t, 2);
        bool alongFace = !anyActiveEdge;
        if (anyActiveEdge) {
            collidePair(shape, poseA, Shape::of(mesh.trianglePrism(t)), poseMesh, PairQuery{settings}, manifold);
            if (manifold.empty()) continue;
            const Vec3 outward = -(poseMesh.rotation.transpose() * manifold.normal);  // triangle → A
            const double cosineToFace = outward.dot(n);
            // A normal out of the triangle's back or sides is no normal of a one-sided surface
            // either: the shape is sunk deep at a ridge (the prism's growth leaves by its back) or
            // lies beside the rim, and the face's normal answers (nothing where the shape is not
            // over the face).
            alongFace =
                cosineToFace >= cosine || !(cosineToFace > 1e-9) || !keepsGrowthNormal(arrays, t, outward, sine);
        }
        if (alongFace) {
            const Vec3 down = -(meshInA.rotation * n);  // A's frame, from A towards the face
            lifted.clear();
            appendAlongFace(along.at(body, down, angularTolerance), body, arrays, meshInA, t, settings, plane, lifted);
            const Vec3 normal = -(poseMesh.rotation * n);  // world, from A towards the mesh
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
    if (contacts.empty() && shape.polytope)
        for (int t : triangles)
            if (facing(t)) appendSunkVertices(*shape.polytope, aInMesh, arrays, poseMesh, t, contacts, from);
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
