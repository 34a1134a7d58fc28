// Polytope construction from explicit faces: validation, coplanar-face merging, and the
// adjacency that makes up the Gauss map (faces = points, edges = arcs, vertices = regions).
#include <gdcontact/polytope.hpp>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <utility>

namespace gdc {
namespace {

std::string faceName(std::size_t face) { return "face " + std::to_string(face); }

// Newell's method: robust area-weighted normal of a (possibly slightly non-planar) polygon. Taken
// about the loop's first vertex, so its rounding is relative to the face's own extent rather than
// to its distance from the origin: a face 1e-7 of the hull's size wide keeps a normal good to
// rounding (issue 21).
Vec3 newellNormal(const std::vector<Vec3>& vertices, const std::vector<int>& loop) {
    Vec3 normal = Vec3::Zero();
    const Vec3& origin = vertices[loop[0]];
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const Vec3 p = vertices[loop[i]] - origin;
        const Vec3 q = vertices[loop[(i + 1) % loop.size()]] - origin;
        normal += Vec3((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
                       (p.x() - q.x()) * (p.y() + q.y()));
    }
    return normal;  // length = 2 · area
}

// The squared extent of a face (its bounding box's diagonal): the scale its area is judged by.
double squaredExtent(const std::vector<Vec3>& vertices, const std::vector<int>& loop) {
    Vec3 lo = vertices[loop[0]], hi = lo;
    for (int v : loop) lo = lo.cwiseMin(vertices[v]), hi = hi.cwiseMax(vertices[v]);
    return (hi - lo).squaredNorm();
}

// A face has zero area when its area is below rounding of its own extent: 1e-12 of its extent
// squared (a width below 1e-12 of its length), whatever the hull's size — a cut corner 1e-7 of
// the hull's size is a real face with a well-defined normal, a sliver of rounding is not.
constexpr double kZeroAreaRatio = 1e-12;
bool hasZeroArea(const Vec3& newell, double extentSquared) { return !(newell.norm() > kZeroAreaRatio * extentSquared); }

// A face loop must turn one way only (no reflex corner) and exactly once around (a bow tie
// turns both ways, a pentagram twice): the turning angles must sum to 2π.
bool isConvexLoop(const std::vector<Vec3>& vertices, const std::vector<int>& loop, const Vec3& normal) {
    double turning = 0;
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
        Vec3 in = vertices[loop[i]] - vertices[loop[(i + n - 1) % n]];
        Vec3 out = vertices[loop[(i + 1) % n]] - vertices[loop[i]];
        double sine = normal.dot(in.cross(out)), cosine = in.dot(out);
        if (sine < -1e-9 * in.norm() * out.norm()) return false;
        turning += std::atan2(sine, cosine);
    }
    return std::abs(turning - 2 * M_PI) < 1e-6;
}

struct UnionFind {
    std::vector<int> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
    void unite(int i, int j) { parent[find(i)] = find(j); }
};

using DirectedEdges = std::map<std::pair<int, int>, int>;  // (tail, head) → face

DirectedEdges directedEdges(const std::vector<std::vector<int>>& faces) {
    DirectedEdges edges;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& loop = faces[f];
        for (std::size_t i = 0; i < loop.size(); ++i) {
            auto key = std::make_pair(loop[i], loop[(i + 1) % loop.size()]);
            if (!edges.emplace(key, static_cast<int>(f)).second)
                throw InvalidInput("edge " + std::to_string(key.first) + "→" + std::to_string(key.second) +
                                   " is used twice in the same direction (" + faceName(f) +
                                   "): faces are not consistently wound or the surface is not manifold");
        }
    }
    for (const auto& [key, face] : edges)
        if (!edges.count({key.second, key.first}))
            throw InvalidInput("edge " + std::to_string(key.first) + "→" + std::to_string(key.second) + " of " +
                               faceName(face) + " has no opposite edge: the surface is not closed");
    return edges;
}

// Merges neighbouring faces whose normals differ by less than the tolerance, so that a face
// of the Gauss map is a single point (the paper's Fig. 3) rather than a cluster of triangles.
std::vector<std::vector<int>> mergeCoplanarFaces(const std::vector<Vec3>& vertices,
                                                 const std::vector<std::vector<int>>& faces,
                                                 double coplanarTolerance) {
    std::vector<Vec3> normals;
    for (const auto& loop : faces) normals.push_back(newellNormal(vertices, loop).normalized());
    const DirectedEdges edges = directedEdges(faces);
    UnionFind groups(faces.size());
    // The angle by its sine (the cross product), which resolves angles down to rounding, where a
    // cosine is 1.0 for every angle below 1.5e-8 rad; a tolerance of 0 merges nothing.
    const double sinTolerance = std::sin(coplanarTolerance);
    for (const auto& [key, face] : edges) {
        int other = edges.at({key.second, key.first});
        if (normals[face].dot(normals[other]) > 0 && normals[face].cross(normals[other]).norm() < sinTolerance)
            groups.unite(face, other);
    }
    // Boundary of each group: directed edges whose opposite edge belongs to another group.
    std::map<int, std::map<int, int>> nextInGroup;  // group → (tail → head)
    for (const auto& [key, face] : edges) {
        int other = edges.at({key.second, key.first});
        if (groups.find(face) != groups.find(other)) nextInGroup[groups.find(face)][key.first] = key.second;
    }
    std::vector<std::vector<int>> merged;
    for (auto& [group, next] : nextInGroup) {
        std::vector<int> loop;
        int start = next.begin()->first, current = start;
        do {
            loop.push_back(current);
            auto it = next.find(current);
            if (it == next.end() || loop.size() > next.size())
                throw InvalidInput("merged coplanar faces around " + faceName(group) + " do not form one polygon");
            current = it->second;
        } while (current != start);
        if (loop.size() != next.size())
            throw InvalidInput("merged coplanar faces around " + faceName(group) + " have a hole");
        merged.push_back(std::move(loop));
    }
    return merged;
}

// Drops vertices that lie on a straight run of a face boundary (only two faces meet there):
// they carry no region of the Gauss map and would create zero-length arcs.
void removeFlatVertices(std::vector<std::vector<int>>& faces, std::size_t vertexCount) {
    for (bool changed = true; changed;) {
        changed = false;
        std::vector<int> faceCount(vertexCount, 0);
        for (const auto& loop : faces)
            for (int v : loop) ++faceCount[v];
        for (auto& loop : faces) {
            auto end = std::remove_if(loop.begin(), loop.end(), [&](int v) { return faceCount[v] == 2; });
            if (end != loop.end()) {
                loop.erase(end, loop.end());
                changed = true;
            }
        }
    }
}

}  // namespace

Polytope Polytope::fromFaces(const std::vector<Vec3>& vertices, const std::vector<std::vector<int>>& faces,
                             const Settings& settings) {
    if (vertices.size() < 4) throw InvalidInput("a polytope needs at least 4 vertices");
    if (faces.size() < 4) throw InvalidInput("a closed polytope needs at least 4 faces");
    for (std::size_t i = 0; i < vertices.size(); ++i)
        if (!vertices[i].allFinite()) throw InvalidInput("vertex " + std::to_string(i) + " is not finite");
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& loop = faces[f];
        if (loop.size() < 3) throw InvalidInput(faceName(f) + " has fewer than 3 vertices");
        for (int v : loop)
            if (v < 0 || static_cast<std::size_t>(v) >= vertices.size())
                throw InvalidInput(faceName(f) + " names vertex " + std::to_string(v) + ", which does not exist");
        std::vector<int> sorted = loop;
        std::sort(sorted.begin(), sorted.end());
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
            throw InvalidInput(faceName(f) + " repeats a vertex");
    }
    Vec3 lo = vertices[0], hi = vertices[0];
    for (const Vec3& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double size = (hi - lo).norm();
    if (!(size > 0)) throw InvalidInput("all vertices coincide");
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Vec3 normal = newellNormal(vertices, faces[f]);
        if (hasZeroArea(normal, squaredExtent(vertices, faces[f])))
            throw InvalidInput(faceName(f) + " has zero area (collinear vertices, or a self-intersecting loop)");
        if (!isConvexLoop(vertices, faces[f], normal.normalized()))
            throw InvalidInput(faceName(f) + " is not a convex polygon (self-intersecting or reflex)");
    }

    Polytope p;
    std::vector<std::vector<int>> loops = mergeCoplanarFaces(vertices, faces, settings.coplanarTolerance);
    removeFlatVertices(loops, vertices.size());

    // Keep only referenced vertices, renumbered in their original order.
    std::vector<int> renumber(vertices.size(), -1);
    for (const auto& loop : loops)
        for (int v : loop) renumber[v] = 0;
    for (std::size_t v = 0; v < vertices.size(); ++v)
        if (renumber[v] == 0) {
            renumber[v] = static_cast<int>(p.vertices_.size());
            p.vertices_.push_back(vertices[v]);
        }
    for (auto& loop : loops) {
        Polytope::Face face{};
        face.first = static_cast<int>(p.faceVertices_.size());
        face.count = static_cast<int>(loop.size());
        for (int& v : loop) v = renumber[v], p.faceVertices_.push_back(v);
        Vec3 normal = loop.size() < 3 ? Vec3::Zero() : newellNormal(p.vertices_, loop);
        if (loop.size() < 3 || hasZeroArea(normal, squaredExtent(p.vertices_, loop)))
            throw InvalidInput("a merged face has zero area: the polytope is flat (no interior)");
        face.normal = normal.normalized();
        face.offset = -1e300;
        for (int v : loop) face.offset = std::max(face.offset, face.normal.dot(p.vertices_[v]));
        p.faces_.push_back(face);
    }
    p.buildTopology(size);
    return p;
}

void Polytope::computeFingerprint() {
    std::uint64_t hash = 0x9E3779B97F4A7C15ull;
    auto mix = [&hash](std::uint64_t value) {
        std::uint64_t z = hash + value + 0x9E3779B97F4A7C15ull;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        hash = z ^ (z >> 31);
    };
    auto mixDouble = [&mix](double value) {
        std::uint64_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        mix(bits);
    };
    mix(vertices_.size());
    for (const Vec3& v : vertices_) mixDouble(v.x()), mixDouble(v.y()), mixDouble(v.z());
    mix(faces_.size());
    for (const Face& face : faces_) {
        mixDouble(face.normal.x()), mixDouble(face.normal.y()), mixDouble(face.normal.z()), mixDouble(face.offset);
        mix(static_cast<std::uint64_t>(face.count));
    }
    for (int v : faceVertices_) mix(static_cast<std::uint64_t>(v));
    mix(isBox_ ? 1 : 0);
    fingerprint_ = hash;
}

Polytope Polytope::box(const Vec3& halfExtents) {
    if (!halfExtents.allFinite() || !(halfExtents.minCoeff() > 0))
        throw InvalidInput("box half extents must be finite and positive");
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back((i & 1 ? 1 : -1) * halfExtents.x(), (i & 2 ? 1 : -1) * halfExtents.y(),
                             (i & 4 ? 1 : -1) * halfExtents.z());
    // Counter-clockwise seen from outside: −x, +x, −y, +y, −z, +z.
    const std::vector<std::vector<int>> faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                 {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    Polytope box = fromFaces(corners, faces);
    box.isBox_ = true;  // vertex i has the signs of bits (x: 1, y: 2, z: 4), as built above
    box.boxHalfExtents_ = halfExtents;
    box.computeFingerprint();
    return box;
}

int Polytope::supportVertex(const Vec3& direction, int bruteForceLimit, int start) const {
    if (isBox_) return (direction.x() > 0 ? 1 : 0) | (direction.y() > 0 ? 2 : 0) | (direction.z() > 0 ? 4 : 0);
    const int count = static_cast<int>(vertices_.size());
    int best = 0;
    double bestValue = vertices_[0].dot(direction);
    if (count <= bruteForceLimit) {
        for (int v = 1; v < count; ++v) {
            double value = vertices_[v].dot(direction);
            if (value > bestValue) bestValue = value, best = v;
        }
        return best;
    }
    // Hill climbing: on a convex polytope a vertex with no strictly better neighbour is a global
    // maximum (the maximisers form a face, and any other vertex has an ascending edge). It starts
    // from the best of a few precomputed seeds (the supports of 26 directions), so a climb
    // crosses at most a small cap of the hull instead of half of it — unless the caller knows a
    // better start (the support of the previous, nearby direction of an iteration).
    if (start >= 0 && start < count) {
        best = start;
        bestValue = vertices_[start].dot(direction);
    } else {
        for (int seed : supportSeeds_) {
            double value = vertices_[seed].dot(direction);
            if (value > bestValue) bestValue = value, best = seed;
        }
    }
    for (bool improved = true; improved;) {
        improved = false;
        const int begin = neighborOffsets_[best], end = neighborOffsets_[best + 1];  // of this vertex
        int next = best;
        for (int i = begin; i < end; ++i) {
            int candidate = neighbors_[i];
            double value = vertices_[candidate].dot(direction);
            if (value > bestValue) bestValue = value, next = candidate, improved = true;
        }
        best = next;
    }
    return best;
}

}  // namespace gdc
