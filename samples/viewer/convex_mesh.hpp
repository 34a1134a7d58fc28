// The viewer's own copy of a convex shape in its local frame: what it needs to draw (face loops,
// edges) and to pick (face planes). Built once per geom, then only its pose changes.
#pragma once

#include "camera.hpp"

#include <gdcontact/polytope.hpp>
#include <gdcontact/types.hpp>

#include <optional>
#include <utility>
#include <vector>

namespace gdc::viewer {

struct ConvexMesh {
    struct Face {
        Vec3 normal;  // outward unit normal
        double offset;  // points x inside satisfy normal·x ≤ offset
        std::vector<int> loop;  // vertex indices, counter-clockwise seen from outside
    };
    std::vector<Vec3> vertices;
    std::vector<Face> faces;
    std::vector<std::pair<int, int>> edges;  // each undirected edge once, for outlines

    /// A box centred at the origin. Throws InvalidInput unless every half extent is finite and > 0.
    static ConvexMesh box(const Vec3& halfExtents);
    static ConvexMesh fromPolytope(const Polytope& polytope);
    /// A cylinder along z, centred, `length` tall: two `sides`-gon caps (vertices on the circle)
    /// and a band of quads. For drawing and picking only; the physics uses the exact geom. Throws
    /// InvalidInput unless radius and length are finite and > 0 and sides ≥ 3.
    static ConvexMesh cylinder(double radius, double length, int sides = 32);
    /// A capsule along z, centred: `length` between its end balls' centres (may be 0: a ball),
    /// hemispheres of `sides`-point rings with vertices on the surface, joined by a band of
    /// quads. For drawing and picking only. Throws InvalidInput unless radius > 0, length ≥ 0
    /// (both finite) and sides ≥ 4.
    static ConvexMesh capsule(double radius, double length, int sides = 24);
    /// From vertices and CCW face loops; planes and edges are derived. Throws InvalidInput for a
    /// face with fewer than three vertices or an index out of range.
    static ConvexMesh fromFaces(std::vector<Vec3> vertices, const std::vector<std::vector<int>>& loops);
};

/// Distance t ≥ 0 along `ray` (in the mesh's local frame) where it enters the solid, 0 when its
/// origin is inside, nothing when it misses. Exact: the ray is clipped against every face plane.
std::optional<double> intersect(const Ray& localRay, const ConvexMesh& mesh);
/// The same for a mesh placed at `pose` and a world-frame ray.
std::optional<double> intersect(const Ray& worldRay, const ConvexMesh& mesh, const Pose& pose);
/// Where a ray enters the solid half-space {x : normal·x ≤ offset} from outside; nothing when it
/// starts inside or runs parallel or away.
std::optional<double> intersectHalfSpace(const Ray& ray, const Vec3& normal, double offset);

}  // namespace gdc::viewer
