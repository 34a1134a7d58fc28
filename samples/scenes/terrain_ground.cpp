#include "terrain_ground.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace gdc::scenes {
namespace {

/// z of the cross product of (b − a) and (p − a): ≥ 0 when p lies left of a→b seen from above.
double leftOf(const Vec3& a, const Vec3& b, const Vec3& p) {
    return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

}  // namespace

TerrainGround::TerrainGround(dSpaceID space, std::vector<Vec3> vertices, std::vector<std::array<int, 3>> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
    for (const Vec3& v : vertices_) {
        if (!v.allFinite()) throw std::invalid_argument("terrain: a vertex is not finite");
        odeVertices_.insert(odeVertices_.end(), {v.x(), v.y(), v.z()});
    }
    for (const auto& triangle : triangles_) {
        for (int index : triangle) {
            if (index < 0 || index >= static_cast<int>(vertices_.size()))
                throw std::invalid_argument("terrain: index " + std::to_string(index) + " out of range");
            odeIndices_.push_back(static_cast<dTriIndex>(index));
        }
        const Vec3 &a = vertices_[triangle[0]], &b = vertices_[triangle[1]], &c = vertices_[triangle[2]];
        const Vec3 normal = (b - a).cross(c - a);
        normals_.push_back(normal.norm() > 0.0 ? Vec3(normal.normalized()) : Vec3::Zero());
        lows_.push_back(a.cwiseMin(b).cwiseMin(c));
        highs_.push_back(a.cwiseMax(b).cwiseMax(c));
    }
    data_ = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildDouble(data_, odeVertices_.data(), 3 * sizeof(double), static_cast<int>(vertices_.size()),
                                odeIndices_.data(), static_cast<int>(odeIndices_.size()), 3 * sizeof(dTriIndex));
    // ODE's own convex–trimesh collider (libccd's) refuses data without its face angles.
    dGeomTriMeshDataPreprocess2(data_, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
    geom_ = dCreateTriMesh(space, data_, nullptr, nullptr, nullptr);
}

TerrainGround::~TerrainGround() { dGeomTriMeshDataDestroy(data_); }

double TerrainGround::penetration(const Polytope& shape, const Pose& pose) const {
    std::vector<Vec3> world;
    world.reserve(shape.vertices().size());
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (const Vec3& v : shape.vertices()) {
        world.push_back(pose.apply(v));
        low = low.cwiseMin(world.back());
        high = high.cwiseMax(world.back());
    }
    double deepest = 0.0;
    // The body's vertices below the up-facing triangle under each (a height field has one).
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
        if (!(normals_[t].z() > 0.0)) continue;
        if (highs_[t].x() < low.x() || lows_[t].x() > high.x() || highs_[t].y() < low.y() || lows_[t].y() > high.y())
            continue;
        const Vec3 &a = vertices_[triangles_[t][0]], &b = vertices_[triangles_[t][1]], &c = vertices_[triangles_[t][2]];
        for (const Vec3& w : world)
            if (leftOf(a, b, w) >= 0.0 && leftOf(b, c, w) >= 0.0 && leftOf(c, a, w) >= 0.0)
                deepest = std::max(deepest, normals_[t].dot(a - w));
    }
    // The terrain's vertices inside the body: the distance to the body's nearest face.
    for (const Vec3& x : vertices_) {
        if ((x.array() < low.array()).any() || (x.array() > high.array()).any()) continue;
        const Vec3 local = pose.applyInverse(x);
        double inside = std::numeric_limits<double>::infinity();
        for (const Polytope::Face& face : shape.faces()) inside = std::min(inside, face.offset - face.normal.dot(local));
        deepest = std::max(deepest, inside);
    }
    return deepest;
}

}  // namespace gdc::scenes
