#include "scene_shapes.hpp"

#include <cmath>
#include <limits>

namespace gdc::viewer {

Pose poseFromOde(const dReal* position, const dReal* rotation) {
    Pose pose;
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) pose.rotation(row, column) = rotation[4 * row + column];
        pose.position[row] = position[row];
    }
    return pose;
}

namespace {

/// The drawn tessellation of a dCylinder or dCapsule; null for a size it cannot draw (a zero
/// radius, a zero-length cylinder), which is then skipped like a class the viewer does not draw.
std::shared_ptr<const ConvexMesh> roundMesh(int geomClass, double radius, double length) {
    const bool drawable = radius > 0.0 && std::isfinite(radius) && std::isfinite(length) &&
                          (geomClass == dCapsuleClass ? length >= 0.0 : length > 0.0);
    if (!drawable) return nullptr;
    return std::make_shared<const ConvexMesh>(geomClass == dCylinderClass ? ConvexMesh::cylinder(radius, length)
                                                                         : ConvexMesh::capsule(radius, length));
}

/// A trimesh's triangles in its own frame, each a face. ODE 0.16 gives them only in world
/// coordinates (dGeomTriMeshGetTriangle), so they are mapped back with the geom's pose; vertices
/// are not shared between faces (every triangle's edges are outlined). Null when it has none.
std::shared_ptr<const ConvexMesh> triangleSurface(dGeomID geom, int count) {
    if (count <= 0) return nullptr;
    const Pose pose = poseFromOde(dGeomGetPosition(geom), dGeomGetRotation(geom));
    std::vector<Vec3> vertices;
    std::vector<std::vector<int>> loops;
    for (int t = 0; t < count; ++t) {
        dVector3 corner[3];
        dGeomTriMeshGetTriangle(geom, t, &corner[0], &corner[1], &corner[2]);
        const int first = int(vertices.size());
        for (const dVector3& c : corner) vertices.push_back(pose.applyInverse(Vec3(c[0], c[1], c[2])));
        if (!((vertices[first + 1] - vertices[first]).cross(vertices[first + 2] - vertices[first]).norm() > 0.0)) {
            vertices.resize(first);  // a degenerate triangle: nothing to draw
            continue;
        }
        loops.push_back({first, first + 1, first + 2});
    }
    if (loops.empty()) return nullptr;
    return std::make_shared<const ConvexMesh>(ConvexMesh::fromFaces(std::move(vertices), loops));
}

/// Where a world ray first meets the front of one of a surface's triangles (Möller–Trumbore).
std::optional<double> intersectSurface(const Ray& worldRay, const ConvexMesh& mesh, const Pose& pose) {
    const Vec3 origin = pose.applyInverse(worldRay.origin);
    const Vec3 direction = pose.rotation.transpose() * worldRay.direction;
    std::optional<double> best;
    for (const auto& face : mesh.faces) {
        if (face.normal.dot(direction) >= 0.0) continue;  // from behind or edge-on
        const Vec3 &a = mesh.vertices[face.loop[0]], &b = mesh.vertices[face.loop[1]], &c = mesh.vertices[face.loop[2]];
        const Vec3 ab = b - a, ac = c - a, p = direction.cross(ac);
        const double determinant = ab.dot(p);
        if (determinant == 0.0) continue;
        const Vec3 s = origin - a;
        const double u = s.dot(p) / determinant;
        const Vec3 q = s.cross(ab);
        const double v = direction.dot(q) / determinant;
        const double t = ac.dot(q) / determinant;
        if (u < 0.0 || v < 0.0 || u + v > 1.0 || t < 0.0) continue;
        if (!best || t < *best) best = t;
    }
    return best;
}

}  // namespace

void SceneShapes::clear() {
    cache_.clear();
    shapes_.clear();
}

void SceneShapes::update(dSpaceID space) {
    shapes_.clear();
    skipped_ = 0;
    collect(space);
}

void SceneShapes::collect(dSpaceID space) {
    const int count = dSpaceGetNumGeoms(space);
    for (int i = 0; i < count; ++i) {
        dGeomID geom = dSpaceGetGeom(space, i);
        if (dGeomIsSpace(geom)) collect(reinterpret_cast<dSpaceID>(geom));
        else add(geom, geom, Pose{}, false);
    }
}

void SceneShapes::add(dGeomID placed, dGeomID geom, const Pose& parent, bool nested) {
    const int type = dGeomGetClass(geom);
    if (type == dPlaneClass) {
        dVector4 p;
        dGeomPlaneGetParams(geom, p);
        DrawShape shape;
        shape.geom = geom;
        shape.placed = placed;
        const Vec3 n(p[0], p[1], p[2]);
        const double length = n.norm();
        if (!(length > 0.0)) return;
        shape.planeNormal = n / length;
        shape.planeOffset = p[3] / length;
        shapes_.push_back(shape);
        return;
    }
    if (type == dGeomTransformClass) {
        // Deprecated in ODE 0.16 in favour of body offsets, but still in use by older programs.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
        dGeomID inner = dGeomTransformGetGeom(geom);
#pragma GCC diagnostic pop
        if (inner == nullptr) return;
        const Pose outer = poseFromOde(dGeomGetPosition(geom), dGeomGetRotation(geom));
        add(placed, inner, outer, true);
        return;
    }
    auto mesh = meshOf(geom);
    if (!mesh) {
        ++skipped_;
        return;
    }
    DrawShape shape;
    shape.geom = geom;
    shape.placed = placed;
    shape.body = dGeomGetBody(placed);
    shape.mesh = std::move(mesh);
    shape.surface = dGeomGetClass(geom) == dTriMeshClass;
    // A geom inside a transform stores its pose relative to the transform; any other placeable
    // geom reports its world pose, body offset included.
    const Pose own = poseFromOde(dGeomGetPosition(geom), dGeomGetRotation(geom));
    shape.pose = nested ? Pose{parent.rotation * own.rotation, parent.apply(own.position)} : own;
    shapes_.push_back(shape);
}

std::shared_ptr<const ConvexMesh> SceneShapes::meshOf(dGeomID geom) {
    const int type = dGeomGetClass(geom);
    Cached& cached = cache_[geom];
    if (type == dBoxClass) {
        dVector3 lengths;
        dGeomBoxGetLengths(geom, lengths);
        const Vec3 size(lengths[0], lengths[1], lengths[2]);
        if (!cached.mesh || cached.geomClass != type || cached.size != size) {
            cached = Cached{size, type, nullptr, std::make_shared<const ConvexMesh>(ConvexMesh::box(0.5 * size))};
        }
        return cached.mesh;
    }
    if (type == dCylinderClass || type == dCapsuleClass) {
        dReal radius, length;
        if (type == dCylinderClass) dGeomCylinderGetParams(geom, &radius, &length);
        else dGeomCapsuleGetParams(geom, &radius, &length);
        const Vec3 size(radius, length, 0.0);
        if (!cached.mesh || cached.geomClass != type || cached.size != size) {
            auto mesh = roundMesh(type, radius, length);
            if (!mesh) {
                cache_.erase(geom);
                return nullptr;
            }
            cached = Cached{size, type, nullptr, std::move(mesh)};
        }
        return cached.mesh;
    }
    if (type == dConvexClass) {
        std::shared_ptr<const Polytope> polytope = lookup_ ? lookup_(geom) : nullptr;
        if (polytope == nullptr) return nullptr;  // a dConvex nobody told us the shape of
        if (!cached.mesh || cached.source != polytope) {
            auto mesh = std::make_shared<const ConvexMesh>(ConvexMesh::fromPolytope(*polytope));
            cached = Cached{Vec3::Zero(), type, std::move(polytope), std::move(mesh)};
        }
        return cached.mesh;
    }
    if (type == dTriMeshClass) {
        const int count = dGeomTriMeshGetTriangleCount(geom);
        const Vec3 size(count, 0.0, 0.0);
        if (!cached.mesh || cached.geomClass != type || cached.size != size) {
            auto mesh = triangleSurface(geom, count);
            if (!mesh) {
                cache_.erase(geom);
                return nullptr;
            }
            cached = Cached{size, type, nullptr, std::move(mesh)};
        }
        return cached.mesh;
    }
    cache_.erase(geom);
    return nullptr;
}

std::optional<PickHit> SceneShapes::pick(const Ray& ray) const {
    std::optional<PickHit> best;
    for (std::size_t i = 0; i < shapes_.size(); ++i) {
        const DrawShape& shape = shapes_[i];
        const auto t = shape.isPlane()   ? intersectHalfSpace(ray, shape.planeNormal, shape.planeOffset)
                       : shape.surface ? intersectSurface(ray, *shape.mesh, shape.pose)
                                       : intersect(ray, *shape.mesh, shape.pose);
        if (t && (!best || *t < best->distance)) best = PickHit{int(i), *t, ray.at(*t)};
    }
    return best;
}

bool SceneShapes::bounds(Vec3& low, Vec3& high) const {
    low = Vec3::Constant(std::numeric_limits<double>::infinity());
    high = -low;
    bool any = false;
    for (const auto& shape : shapes_) {
        if (shape.isPlane()) continue;
        for (const auto& v : shape.mesh->vertices) {
            const Vec3 w = shape.pose.apply(v);
            low = low.cwiseMin(w);
            high = high.cwiseMax(w);
            any = true;
        }
    }
    return any;
}

}  // namespace gdc::viewer
