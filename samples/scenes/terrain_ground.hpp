// A static triangle-mesh ground for the scenes (Scene::addTerrain): the ODE trimesh geom, the
// vertex and index arrays ODE reads from (ODE keeps pointers to them, not copies), and the
// geometric penetration measure against the mesh. Private to samples/scenes.
#pragma once

#include <gdcontact/polytope.hpp>
#include <gdcontact/types.hpp>

#include <ode/ode.h>

#include <array>
#include <vector>

namespace gdc::scenes {

class TerrainGround {
public:
    /// Builds the data (dGeomTriMeshDataBuildDouble) and a dCreateTriMesh geom in `space`, at the
    /// identity pose: `vertices` are world coordinates. Each triangle's vertices run
    /// counter-clockwise seen from its front (ODE's winding), the front facing up. The measure
    /// below assumes a height field: over any (x, y) at most one triangle faces up. Throws
    /// std::invalid_argument for an index out of range or a non-finite vertex.
    TerrainGround(dSpaceID space, std::vector<Vec3> vertices, std::vector<std::array<int, 3>> triangles);
    /// Destroys the data; the geom must be gone by then (the scene destroys its space first).
    ~TerrainGround();
    TerrainGround(const TerrainGround&) = delete;
    TerrainGround& operator=(const TerrainGround&) = delete;

    dGeomID geom() const { return geom_; }

    /// How deep the convex `shape` at `pose` lies in the terrain (m; 0 when it does not): the
    /// larger of
    ///  - its deepest vertex below the terrain: for each vertex, its distance below the plane of
    ///    the up-facing triangle under it (along that triangle's normal). Exact where the body
    ///    rests over one plane (the flat part, the slope); across a fold between triangles it is
    ///    the distance to the plane of the triangle under the vertex, which differs from the
    ///    distance to the surface by at most the vertex's depth times the fold's angle;
    ///  - the deepest terrain vertex inside the shape (its distance to the nearest face), which
    ///    catches a bump's top poking into a body's face where no body vertex lies below.
    /// A round part is measured as its tessellation (Part::shape), whose vertices lie on the
    /// surface: up to the tessellation's sagitta.
    double penetration(const Polytope& shape, const Pose& pose) const;

private:
    std::vector<Vec3> vertices_;
    std::vector<std::array<int, 3>> triangles_;
    std::vector<Vec3> normals_;        // unit, per triangle (zero for a degenerate one)
    std::vector<Vec3> lows_, highs_;   // per-triangle bounds
    std::vector<double> odeVertices_;  // what ODE reads: x, y, z per vertex
    std::vector<dTriIndex> odeIndices_;
    dTriMeshDataID data_ = nullptr;
    dGeomID geom_ = nullptr;
};

}  // namespace gdc::scenes
