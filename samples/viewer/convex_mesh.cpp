#include "convex_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace gdc::viewer {

ConvexMesh ConvexMesh::box(const Vec3& h) {
    if (!h.allFinite() || h.minCoeff() <= 0.0) throw InvalidInput("box half extents must be finite and positive");
    std::vector<Vec3> v;
    for (int i = 0; i < 8; ++i)
        v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    // Loops counter-clockwise seen from outside (right-handed about the outward normal).
    return fromFaces(std::move(v), {{0, 4, 6, 2}, {1, 3, 7, 5},  // -x, +x
                                    {0, 1, 5, 4}, {2, 6, 7, 3},  // -y, +y
                                    {0, 2, 3, 1}, {4, 5, 7, 6}});  // -z, +z
}

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Appends a ring of `sides` vertices of radius `rho` at height `z`; returns its first index.
int addRing(std::vector<Vec3>& vertices, double rho, double z, int sides) {
    const int first = int(vertices.size());
    for (int i = 0; i < sides; ++i) {
        const double angle = 2.0 * kPi * i / sides;
        vertices.emplace_back(rho * std::cos(angle), rho * std::sin(angle), z);
    }
    return first;
}

/// The quads joining ring `lower` to ring `upper` above it (both of `sides` vertices, the same
/// azimuths), counter-clockwise seen from outside.
void addBand(std::vector<std::vector<int>>& loops, int lower, int upper, int sides) {
    for (int i = 0; i < sides; ++i) {
        const int next = (i + 1) % sides;
        loops.push_back({lower + i, lower + next, upper + next, upper + i});
    }
}

/// The triangles joining `pole` to `ring`: `upward` when the pole lies above the ring.
void addFan(std::vector<std::vector<int>>& loops, int pole, int ring, int sides, bool upward) {
    for (int i = 0; i < sides; ++i) {
        const int next = (i + 1) % sides;
        if (upward) loops.push_back({ring + i, ring + next, pole});
        else loops.push_back({ring + next, ring + i, pole});
    }
}

}  // namespace

ConvexMesh ConvexMesh::cylinder(double radius, double length, int sides) {
    if (!std::isfinite(radius) || !std::isfinite(length) || !(radius > 0.0) || !(length > 0.0) || sides < 3)
        throw InvalidInput("cylinder radius and length must be finite and positive, with at least 3 sides");
    std::vector<Vec3> vertices;
    const int bottom = addRing(vertices, radius, -0.5 * length, sides);
    const int top = addRing(vertices, radius, 0.5 * length, sides);
    std::vector<std::vector<int>> loops;
    addBand(loops, bottom, top, sides);
    std::vector<int> bottomCap, topCap;
    for (int i = 0; i < sides; ++i) {
        bottomCap.push_back(bottom + sides - 1 - i);  // clockwise from above: counter-clockwise from below
        topCap.push_back(top + i);
    }
    loops.push_back(std::move(bottomCap));
    loops.push_back(std::move(topCap));
    return fromFaces(std::move(vertices), loops);
}

ConvexMesh ConvexMesh::capsule(double radius, double length, int sides) {
    if (!std::isfinite(radius) || !std::isfinite(length) || !(radius > 0.0) || !(length >= 0.0) || sides < 4)
        throw InvalidInput("capsule radius must be finite and positive, its length finite and not negative, "
                           "with at least 4 sides");
    // Rings from the bottom pole's neighbour up to the top pole's, every 90°/rings of latitude on
    // each end ball; a zero length shares the equator ring instead of a zero-height band.
    const int rings = std::max(2, sides / 4);
    std::vector<Vec3> vertices{Vec3(0, 0, -0.5 * length - radius), Vec3(0, 0, 0.5 * length + radius)};
    std::vector<int> ringStarts;
    for (int k = -rings + 1; k <= rings - 1; ++k) {
        const double latitude = 0.5 * kPi * k / rings;
        const double centre = (k < 0 ? -0.5 : 0.5) * length;
        ringStarts.push_back(addRing(vertices, radius * std::cos(latitude), centre + radius * std::sin(latitude), sides));
        if (k == 0 && length > 0.0) ringStarts.insert(ringStarts.end() - 1, addRing(vertices, radius, -0.5 * length, sides));
    }
    std::vector<std::vector<int>> loops;
    addFan(loops, 0, ringStarts.front(), sides, false);
    for (std::size_t r = 0; r + 1 < ringStarts.size(); ++r) addBand(loops, ringStarts[r], ringStarts[r + 1], sides);
    addFan(loops, 1, ringStarts.back(), sides, true);
    return fromFaces(std::move(vertices), loops);
}

ConvexMesh ConvexMesh::fromPolytope(const Polytope& polytope) {
    ConvexMesh mesh;
    mesh.vertices = polytope.vertices();
    const auto& indices = polytope.faceVertices();
    for (const auto& face : polytope.faces()) {
        Face f{face.normal, face.offset, {}};
        f.loop.assign(indices.begin() + face.first, indices.begin() + face.first + face.count);
        mesh.faces.push_back(std::move(f));
    }
    for (const auto& edge : polytope.edges()) mesh.edges.emplace_back(edge.tail, edge.head);
    return mesh;
}

ConvexMesh ConvexMesh::fromFaces(std::vector<Vec3> vertices, const std::vector<std::vector<int>>& loops) {
    ConvexMesh mesh;
    mesh.vertices = std::move(vertices);
    const int count = int(mesh.vertices.size());
    std::set<std::pair<int, int>> edges;
    for (std::size_t f = 0; f < loops.size(); ++f) {
        const auto& loop = loops[f];
        if (loop.size() < 3) throw InvalidInput("face " + std::to_string(f) + " has fewer than 3 vertices");
        for (int i : loop)
            if (i < 0 || i >= count) throw InvalidInput("face " + std::to_string(f) + " names a vertex out of range");
        // Newell's method: robust normal of a planar polygon of any size.
        Vec3 normal = Vec3::Zero();
        for (std::size_t i = 0; i < loop.size(); ++i)
            normal += mesh.vertices[loop[i]].cross(mesh.vertices[loop[(i + 1) % loop.size()]]);
        if (!(normal.norm() > 0.0)) throw InvalidInput("face " + std::to_string(f) + " has no area");
        normal.normalize();
        mesh.faces.push_back({normal, normal.dot(mesh.vertices[loop[0]]), loop});
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const int a = loop[i], b = loop[(i + 1) % loop.size()];
            edges.emplace(std::min(a, b), std::max(a, b));
        }
    }
    mesh.edges.assign(edges.begin(), edges.end());
    return mesh;
}

std::optional<double> intersect(const Ray& ray, const ConvexMesh& mesh) {
    // Clip the half-line against each face's half-space: where the ray crosses a plane going
    // inwards it may enter, going outwards it may leave. It hits iff the last entry precedes the
    // first exit.
    double enter = 0.0, leave = std::numeric_limits<double>::infinity();
    for (const auto& face : mesh.faces) {
        const double approach = face.normal.dot(ray.direction);
        const double clearance = face.offset - face.normal.dot(ray.origin);  // ≥ 0: origin inside
        if (approach == 0.0) {
            if (clearance < 0.0) return std::nullopt;  // parallel and outside this face
            continue;
        }
        const double t = clearance / approach;
        if (approach < 0.0) enter = std::max(enter, t);
        else leave = std::min(leave, t);
        if (enter > leave) return std::nullopt;
    }
    return enter;
}

std::optional<double> intersect(const Ray& worldRay, const ConvexMesh& mesh, const Pose& pose) {
    const Ray local{pose.applyInverse(worldRay.origin), pose.rotation.transpose() * worldRay.direction};
    return intersect(local, mesh);
}

std::optional<double> intersectHalfSpace(const Ray& ray, const Vec3& normal, double offset) {
    const double approach = normal.dot(ray.direction);
    const double clearance = normal.dot(ray.origin) - offset;  // > 0: origin outside the solid
    if (clearance <= 0.0 || approach >= 0.0) return std::nullopt;
    return clearance / -approach;
}

}  // namespace gdc::viewer
