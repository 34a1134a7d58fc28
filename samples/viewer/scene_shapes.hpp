// Everything drawable and pickable in an ODE space: boxes, convex hulls (through the gdcontact
// adapter), cylinders and capsules (drawn and picked as fine tessellations), triangle meshes
// (terrain), planes, geoms inside a dGeomTransform and geoms with a body offset, in nested spaces.
#pragma once

#include "convex_mesh.hpp"

#include <ode/ode.h>

#include <functional>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

namespace gdc::viewer {

struct DrawShape {
    dGeomID geom = nullptr;   // the geom whose shape this is (inside a transform: the wrapped geom)
    dGeomID placed = nullptr; // the geom that sits in the space (the transform, or `geom` itself)
    dBodyID body = nullptr;   // null for static geometry
    std::shared_ptr<const ConvexMesh> mesh;  // null for a plane
    /// A trimesh (dCreateTriMesh): `mesh` holds its triangles as faces, an open surface rather than
    /// a convex solid, so it is picked triangle by triangle (front faces only).
    bool surface = false;
    Pose pose;                // world pose of the mesh
    Vec3 planeNormal = Vec3::UnitZ();  // plane only: the solid is {x : normal·x ≤ offset}
    double planeOffset = 0.0;
    bool isPlane() const { return mesh == nullptr; }
};

struct PickHit {
    int shape = -1;     // index into SceneShapes::shapes()
    double distance = 0.0;  // along the ray
    Vec3 point = Vec3::Zero();
};

class SceneShapes {
public:
    /// Where the polytope of a dConvex geom comes from (ODE itself offers no way to read it back).
    /// Returns null for a geom it does not know; such geoms are skipped.
    using PolytopeLookup = std::function<std::shared_ptr<const Polytope>(dGeomID)>;
    void setPolytopeLookup(PolytopeLookup lookup) { lookup_ = std::move(lookup); }

    /// Re-read every geom of `space` (recursively): poses always, meshes only for geoms not seen
    /// before or whose dimensions changed (a trimesh: whose triangle count changed). Geoms of
    /// classes the viewer cannot draw (spheres, heightfields...) are counted in skipped().
    void update(dSpaceID space);
    /// Forget all cached meshes (after the scene was rebuilt: ODE may reuse geom addresses).
    void clear();

    const std::vector<DrawShape>& shapes() const { return shapes_; }
    int skipped() const { return skipped_; }

    /// The nearest shape the ray enters, static or not.
    std::optional<PickHit> pick(const Ray& ray) const;

    /// Axis-aligned bounds of every finite shape (planes excluded); false when there is none.
    bool bounds(Vec3& low, Vec3& high) const;

private:
    struct Cached {
        Vec3 size = Vec3::Zero();  // boxes: the lengths; cylinders, capsules: radius, length, 0; trimeshes: triangle count, 0, 0
        int geomClass = -1;        // rebuild when the class or the size changes (ODE reuses addresses)
        std::shared_ptr<const Polytope> source;  // for convex geoms: the polytope it was built from
        std::shared_ptr<const ConvexMesh> mesh;
    };
    void collect(dSpaceID space);
    void add(dGeomID placed, dGeomID geom, const Pose& parent, bool nested);
    std::shared_ptr<const ConvexMesh> meshOf(dGeomID geom);

    PolytopeLookup lookup_;
    std::unordered_map<dGeomID, Cached> cache_;
    std::vector<DrawShape> shapes_;
    int skipped_ = 0;
};

/// A geom's pose from ODE (its dReal[12] row-major 3×4 rotation and position).
Pose poseFromOde(const dReal* position, const dReal* rotation);

}  // namespace gdc::viewer
