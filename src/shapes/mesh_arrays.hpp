// A triangle mesh's arrays as the mesh query (contact/mesh_pair.cpp) reads them: the accessors of
// gdc::TriangleMesh check every index (they are public), the query's indices come from the mesh
// itself, and a resting body asks for a few hundred of them per call.
#pragma once

#include <gdcontact/triangle_mesh.hpp>

#include <array>

namespace gdc::detail {

/// Views into a TriangleMesh's arrays (valid as long as the mesh), with its accessors' names and
/// meanings (triangle_mesh.hpp), unchecked.
struct MeshArrays {
    const Vec3* vertexData;
    const std::array<int, 3>* triangles;
    const Vec3* normals;
    const unsigned char* activeEdges;
    const std::array<int, 3>* neighbours;

    const Vec3* vertices() const { return vertexData; }
    const std::array<int, 3>& triangle(int t) const { return triangles[t]; }
    const Vec3& triangleNormal(int t) const { return normals[t]; }
    bool edgeActive(int t, int e) const { return (activeEdges[t] >> e) & 1; }
    int neighbour(int t, int e) const { return neighbours[t][e]; }
};

}  // namespace gdc::detail
