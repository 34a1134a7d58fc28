// A triangle mesh built once: each triangle's normal, its neighbours across each edge and which
// edges are active (docs/meshes.md), and a bounding-volume tree over the
// triangles' bounds for the mid phase.
#include <gdcontact/triangle_mesh.hpp>

#include "shapes/mesh_arrays.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <string>
#include <unordered_map>

namespace gdc {

namespace {

// A node of the mid phase's tree: a leaf holds order[first, first + count); an inner node (count
// ≤ 0) has its children at nodes[first] and nodes[−count].
struct MeshNode {
    Aabb box;
    int first = 0;
    int count = 0;
};

// The thinnest triangle kept: its height over its longest edge. A thinner sliver covers no surface
// that matters beside its neighbours (10 µm across a metre), and its prism's two long sides would be
// one face to the polytope's coplanar tolerance (no interior): it is skipped as zero area is.
constexpr double kThinnest = 1e-5;

// The unit normal of (a, b, c) by the right hand; zero for a triangle thinner than kThinnest.
Vec3 frontNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 cross = (b - a).cross(c - a);
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double length = cross.norm();
    if (!(length > kThinnest * longest)) return Vec3::Zero();
    return cross / length;
}

Aabb boundsOf(const Vec3& a, const Vec3& b, const Vec3& c) {
    return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

// Vertices at exactly the same position are one vertex for the neighbours: meshes often repeat a
// vertex per face (for its own normal or texture coordinate), and a seam between two triangles
// that share only positions is still a seam.
std::vector<int> weldedIndices(const std::vector<Vec3>& vertices) {
    std::map<std::array<double, 3>, int> first;
    std::vector<int> canonical(vertices.size());
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        const std::array<double, 3> key{vertices[v].x() + 0.0, vertices[v].y() + 0.0, vertices[v].z() + 0.0};
        canonical[v] = first.emplace(key, static_cast<int>(v)).first->second;
    }
    return canonical;
}

// The mid phase's tree, built top-down: each node splits its triangles at the median of their
// centres along the longest axis of the centres' bounds, down to leaves of kLeafSize.
class TreeBuilder {
public:
    TreeBuilder(const std::vector<Aabb>& bounds, std::vector<MeshNode>& nodes, std::vector<int>& order)
        : bounds_(bounds), nodes_(nodes), order_(order) {}
    int build(int first, int count) {
        const int index = static_cast<int>(nodes_.size());
        nodes_.push_back({});
        Aabb box = bounds_[order_[first]];
        Vec3 lowCentre = centre(order_[first]), highCentre = lowCentre;
        for (int i = first; i < first + count; ++i) {
            const Aabb& b = bounds_[order_[i]];
            box.lower = box.lower.cwiseMin(b.lower), box.upper = box.upper.cwiseMax(b.upper);
            lowCentre = lowCentre.cwiseMin(centre(order_[i])), highCentre = highCentre.cwiseMax(centre(order_[i]));
        }
        nodes_[index].box = box;
        if (count <= kLeafSize) {
            nodes_[index].first = first, nodes_[index].count = count;
            return index;
        }
        int axis = 0;
        (highCentre - lowCentre).maxCoeff(&axis);
        const int half = count / 2;
        // Ties broken by index: the tree, and so the order triangles are visited in, is the same
        // on every machine.
        std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                         [&](int p, int q) {
                             const double cp = centre(p)[axis], cq = centre(q)[axis];
                             return cp < cq || (cp == cq && p < q);
                         });
        const int left = build(first, half);
        const int right = build(first + half, count - half);
        nodes_[index].first = left, nodes_[index].count = -right;  // an inner node: both children
        return index;
    }

private:
    static constexpr int kLeafSize = 4;
    Vec3 centre(int t) const { return 0.5 * (bounds_[t].lower + bounds_[t].upper); }
    const std::vector<Aabb>& bounds_;
    std::vector<MeshNode>& nodes_;
    std::vector<int>& order_;
};

}  // namespace

struct TriangleMesh::Data {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;
    std::vector<Vec3> normals;               // unit; zero for a skipped triangle
    std::vector<unsigned char> activeEdges;  // bit e: edge e is active
    std::vector<std::array<int, 3>> neighbours;  // across each edge; −1: none
    int skipped = 0;
    std::vector<MeshNode> nodes;  // nodes[0] the root
    std::vector<int> order;       // the kept triangles, as the leaves hold them
    Settings settings;            // what the prisms are built with
    mutable std::mutex prismsLock;
    mutable std::unordered_map<int, std::unique_ptr<const Polytope>> prisms;  // built on first use
};

TriangleMesh::TriangleMesh(std::vector<Vec3> vertices, const std::vector<std::array<int, 3>>& triangles,
                           const Settings& settings)
    : data_(std::make_unique<Data>()) {
    validate(settings);
    Data& d = *data_;
    for (std::size_t v = 0; v < vertices.size(); ++v)
        if (!vertices[v].allFinite())
            throw InvalidInput("triangle mesh: vertex " + std::to_string(v) + " is not finite");
    const int vertexCount = static_cast<int>(vertices.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int corner : triangles[t])
            if (corner < 0 || corner >= vertexCount)
                throw InvalidInput("triangle mesh: triangle " + std::to_string(t) + " has vertex index " +
                                   std::to_string(corner) + ", outside [0, " + std::to_string(vertexCount) + ")");
    d.settings = settings;
    d.vertices = std::move(vertices);
    d.triangles = triangles;
    const std::vector<int> canonical = weldedIndices(d.vertices);
    const int count = static_cast<int>(triangles.size());
    d.normals.assign(count, Vec3::Zero());
    d.activeEdges.assign(count, 0);
    d.neighbours.assign(count, {-1, -1, -1});
    std::vector<Aabb> bounds(count);
    std::vector<int> kept;
    for (int t = 0; t < count; ++t) {
        const std::array<int, 3>& tri = triangles[t];
        const int a = canonical[tri[0]], b = canonical[tri[1]], c = canonical[tri[2]];
        if (a == b || b == c || c == a) continue;  // a repeated vertex: no area
        d.normals[t] = frontNormal(d.vertices[tri[0]], d.vertices[tri[1]], d.vertices[tri[2]]);
        if (d.normals[t].isZero()) continue;
        bounds[t] = boundsOf(d.vertices[tri[0]], d.vertices[tri[1]], d.vertices[tri[2]]);
        kept.push_back(t);
    }
    d.skipped = count - static_cast<int>(kept.size());

    // Neighbours: the kept triangles around each edge, by its welded end points.
    std::unordered_map<std::uint64_t, std::vector<std::pair<int, int>>> aroundEdge;  // (triangle, edge)
    auto edgeKey = [&](int t, int e) {
        const std::uint64_t p = static_cast<std::uint32_t>(canonical[triangles[t][e]]);
        const std::uint64_t q = static_cast<std::uint32_t>(canonical[triangles[t][(e + 1) % 3]]);
        return std::min(p, q) << 32 | std::max(p, q);
    };
    for (int t : kept)
        for (int e = 0; e < 3; ++e) aroundEdge[edgeKey(t, e)].emplace_back(t, e);
    const double cosine = std::cos(settings.angularTolerance);
    for (int t : kept) {
        for (int e = 0; e < 3; ++e) {
            const std::vector<std::pair<int, int>>& around = aroundEdge[edgeKey(t, e)];
            // Active: the boundary, more than two triangles at the edge, or a neighbour wound the
            // other way (its edge runs the same way as this one's: which side is front is unknown).
            bool active = true;
            const std::pair<int, int>& first = around[0];
            const bool consistent = around.size() == 2 && canonical[triangles[first.first][first.second]] !=
                                                              canonical[triangles[around[1].first][around[1].second]];
            if (consistent) {
                const std::pair<int, int>& other = around[0].first == t ? around[1] : around[0];
                const int u = other.first;
                d.neighbours[t][e] = u;
                const int opposite = triangles[u][(other.second + 2) % 3];
                const Vec3& n = d.normals[t];
                const bool coplanar = n.dot(d.normals[u]) >= cosine;
                // Convex where the neighbour's far vertex lies behind this triangle's plane.
                const bool convex = n.dot(d.vertices[opposite] - d.vertices[triangles[t][e]]) < 0;
                active = !coplanar && convex;
            }
            if (active) d.activeEdges[t] |= static_cast<unsigned char>(1u << e);
        }
    }

    // The tree over the kept triangles.
    d.order = kept;
    if (!kept.empty()) TreeBuilder(bounds, d.nodes, d.order).build(0, static_cast<int>(kept.size()));
}

TriangleMesh::~TriangleMesh() = default;
TriangleMesh::TriangleMesh(TriangleMesh&&) noexcept = default;
TriangleMesh& TriangleMesh::operator=(TriangleMesh&&) noexcept = default;

int TriangleMesh::triangleCount() const { return static_cast<int>(data_->triangles.size()); }
int TriangleMesh::skippedTriangleCount() const { return data_->skipped; }
const std::vector<Vec3>& TriangleMesh::vertices() const { return data_->vertices; }
namespace detail {
MeshArrays meshArrays(const TriangleMesh& mesh) {
    const TriangleMesh::Data& d = *mesh.data_;
    return {d.vertices.data(), d.triangles.data(), d.normals.data(), d.activeEdges.data(), d.neighbours.data()};
}
}  // namespace detail

const std::array<int, 3>& TriangleMesh::triangle(int t) const { return data_->triangles.at(t); }
const Vec3& TriangleMesh::triangleNormal(int t) const { return data_->normals.at(t); }
bool TriangleMesh::edgeActive(int t, int e) const { return (data_->activeEdges.at(t) >> e) & 1; }
int TriangleMesh::neighbour(int t, int e) const { return data_->neighbours.at(t).at(e); }

const Polytope& TriangleMesh::trianglePrism(int t) const {
    const Data& d = *data_;
    if (d.normals.at(t).isZero()) throw InvalidInput("triangle mesh: triangle " + std::to_string(t) + " is skipped");
    const std::lock_guard<std::mutex> lock(d.prismsLock);
    std::unique_ptr<const Polytope>& prism = d.prisms[t];
    if (!prism) {
        // The side faces, each counter-clockwise seen from outside, of the triangle's vertices (0,
        // 1, 2, counter-clockwise seen from its front) and those moved behind it (3, 4, 5). The
        // depth behind only gives the growth distance a solid to grow: a shape sunk into the face
        // by less than it leaves by the front.
        static const std::vector<std::vector<int>> kFaces = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
        const std::array<int, 3>& corners = d.triangles[t];
        double longest = 0;
        for (int i = 0; i < 3; ++i)
            longest = std::max(longest, (d.vertices[corners[(i + 1) % 3]] - d.vertices[corners[i]]).norm());
        std::vector<Vec3> points(6);
        for (int i = 0; i < 3; ++i) {
            points[i] = d.vertices[corners[i]];
            points[i + 3] = points[i] - longest * d.normals[t];
        }
        prism = std::make_unique<const Polytope>(Polytope::fromFaces(points, kFaces, d.settings));
    }
    return *prism;
}

void TriangleMesh::overlapping(const Aabb& box, std::vector<int>& out) const {
    const Data& d = *data_;
    if (d.nodes.empty()) return;
    const std::size_t begin = out.size();
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const MeshNode& node = d.nodes[stack[--top]];
        if (!node.box.overlaps(box)) continue;
        if (node.count > 0) {
            for (int i = node.first; i < node.first + node.count; ++i) {
                const std::array<int, 3>& tri = d.triangles[d.order[i]];
                if (boundsOf(d.vertices[tri[0]], d.vertices[tri[1]], d.vertices[tri[2]]).overlaps(box))
                    out.push_back(d.order[i]);
            }
        } else {
            stack[top++] = node.first;
            stack[top++] = -node.count;
        }
    }
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end());
}

}  // namespace gdc
