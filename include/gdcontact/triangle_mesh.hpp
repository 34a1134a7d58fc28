// A triangle mesh (terrain, a static level, a concave body's surface) and the contacts of a convex
// shape with it: each triangle the shape's bounds reach is a shape of its own for the paper's three
// stages, the mesh adds what a triangle knows beyond that — its neighbours — so that a contact
// whose normal comes from an edge between two coplanar (or concave) triangles takes the face's
// normal instead (no bump at a seam), and the triangles' contacts become one manifold by the
// per-body-pair rule (body_pair.hpp). docs/meshes.md.
#pragma once

#include <gdcontact/body_pair.hpp>
#include <gdcontact/export.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>
#include <gdcontact/shapes.hpp>
#include <gdcontact/types.hpp>

#include <array>
#include <memory>
#include <vector>

namespace gdc {

/// An axis-aligned box: the points x with lower ≤ x ≤ upper, component by component.
struct Aabb {
    Vec3 lower = Vec3::Zero();
    Vec3 upper = Vec3::Zero();
    bool overlaps(const Aabb& other) const {
        return (lower.array() <= other.upper.array()).all() && (other.lower.array() <= upper.array()).all();
    }
};

class TriangleMesh;
namespace detail {
struct MeshArrays;
/// The mesh's arrays as gdcontact's own query reads them, unchecked (src/shapes/mesh_arrays.hpp).
MeshArrays meshArrays(const TriangleMesh& mesh);
}  // namespace detail

/// A triangle mesh in its own frame, one-sided: a triangle's front is where its vertices run
/// counter-clockwise (ODE's winding: the normal is (v1 − v0) × (v2 − v0)), and only a shape in front
/// of a triangle touches it. Built once (neighbours across each edge, which edges are active, a
/// bounding-volume tree); immutable and safe to share between threads afterwards.
class GDCONTACT_API TriangleMesh {
public:
    /// Triangles as vertex index triples. Throws InvalidInput for a non-finite vertex or an index
    /// out of range. Degenerate triangles (a repeated vertex, or thinner than 1e-5 of their longest
    /// edge: no area to rounding) are skipped: they stay numbered, never touch anything, and
    /// skippedTriangleCount() says how many.
    TriangleMesh(std::vector<Vec3> vertices, const std::vector<std::array<int, 3>>& triangles,
                 const Settings& settings = {});
    ~TriangleMesh();
    TriangleMesh(const TriangleMesh&) = delete;
    TriangleMesh& operator=(const TriangleMesh&) = delete;
    TriangleMesh(TriangleMesh&&) noexcept;
    TriangleMesh& operator=(TriangleMesh&&) noexcept;

    int triangleCount() const;
    int skippedTriangleCount() const;
    const std::vector<Vec3>& vertices() const;
    const std::array<int, 3>& triangle(int t) const;
    /// The unit front normal of triangle t (zero for a skipped one).
    const Vec3& triangleNormal(int t) const;
    /// Whether edge e of triangle t (from vertex e to vertex (e + 1) % 3) is active: on the
    /// boundary (no neighbour), shared by more than two triangles, or convex with a neighbour whose
    /// normal differs by more than Settings::angularTolerance. An inactive edge (coplanar within it,
    /// or concave) never gives a contact its normal.
    bool edgeActive(int t, int e) const;
    /// The triangle across edge e of triangle t: −1 on the boundary, where more than two triangles
    /// share the edge, or where the neighbour is wound the other way (each an active edge).
    int neighbour(int t, int e) const;
    /// Appends to `out` the triangles (ascending, skipped ones never) whose bounds overlap `box`
    /// (the mesh's frame), from the bounding-volume tree: the cost grows with the answer and the
    /// tree's depth, not with the mesh's size.
    void overlapping(const Aabb& box, std::vector<int>& out) const;
    /// Triangle t (not a skipped one) as a solid for the pair table: its face extruded behind it by
    /// its longest edge into a prism, so that every stage applies to it as to any hull. Built on
    /// first use and kept (under a lock: safe from several threads); valid as long as the mesh.
    const Polytope& trianglePrism(int t) const;

private:
    struct Data;
    std::unique_ptr<Data> data_;
    friend detail::MeshArrays detail::meshArrays(const TriangleMesh& mesh);
};

/// One contact of a shape with a mesh.
struct MeshContact {
    Vec3 position = Vec3::Zero();  ///< world, midway between the surfaces (as ContactPoint)
    Vec3 normal = Vec3::UnitZ();   ///< world unit normal from the shape towards the mesh (as Manifold)
    double depth = 0.0;            ///< overlap along the normal
    int triangle = -1;             ///< the triangle it came from
};

/// Which triangles a mesh query may use (ODE's dTriCallback, say): `accepts(context, t)` is asked
/// once for each triangle the mid phase finds, before it is collided; a triangle it refuses gives
/// no contact and takes no place in the reduction. Without `accepts`, every triangle.
struct TriangleFilter {
    bool (*accepts)(void* context, int triangle) = nullptr;
    void* context = nullptr;
};

/// Contacts of a convex shape A (a polytope, a sphere, a capsule or a cylinder; not a half-space)
/// with a mesh, written into `out` (cleared first): each triangle
/// whose bounds meet A's is collided with A by the paper's three stages. Where the triangle's
/// Gauss-map feature along the growth-distance normal is its face, or an inactive edge or vertex,
/// the contacts are the features' intersection along the face's own normal — what the plane of the
/// face gives, clipped to the triangle; a triangle with no active edge is never asked for another
/// normal. An active edge's or vertex's normal stands, unless it points out of the triangle's back
/// or sides (no contact: the shape is behind a one-sided surface there). Then the contacts of every
/// triangle are merged and reduced as a body pair's (reduceBodyPairContacts,
/// Settings::maxBodyPairContacts per normal cluster; 0 keeps all), in triangle order. Throws
/// InvalidInput for a non-finite pose, a half-space or a curved size shapes.hpp refuses.
GDCONTACT_API void collide(const ShapeRef& a, const Pose& poseA, const TriangleMesh& mesh, const Pose& poseMesh,
                           const Settings& settings, std::vector<MeshContact>& out, const TriangleFilter& filter = {});

}  // namespace gdc
