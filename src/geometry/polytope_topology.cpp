// The adjacency that makes up a polytope's Gauss map (faces = points, edges = arcs, vertices =
// regions), its volume, centroid and radii, built once from validated faces (polytope.cpp).
#include <gdcontact/polytope.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace gdc {
namespace {

std::string faceName(std::size_t face) { return "face " + std::to_string(face); }

}  // namespace

void Polytope::buildTopology(double size) {
    const int vertexCount = static_cast<int>(vertices_.size());
    // Volume and centroid by a fan of tetrahedra from the vertex mean (an interior point of a
    // convex body), so that the contraction point is the true centroid.
    Vec3 reference = Vec3::Zero();
    for (const Vec3& v : vertices_) reference += v;
    reference /= vertexCount;
    double volume = 0;
    Vec3 moment = Vec3::Zero();
    for (const Face& face : faces_) {
        const Vec3& a = vertices_[faceVertices_[face.first]];
        for (int i = 1; i + 1 < face.count; ++i) {
            const Vec3& b = vertices_[faceVertices_[face.first + i]];
            const Vec3& c = vertices_[faceVertices_[face.first + i + 1]];
            double tetra = (a - reference).dot((b - reference).cross(c - reference)) / 6.0;
            volume += tetra;
            moment += tetra * (reference + a + b + c) / 4.0;
        }
    }
    if (!(volume > 1e-12 * size * size * size))
        throw InvalidInput(volume < 0 ? "faces are wound clockwise seen from outside (expected counter-clockwise)"
                                      : "the polytope has no interior (flat or degenerate)");
    volume_ = volume;
    centroid_ = moment / volume;

    // Planarity and convexity: every vertex must lie inside every face plane, within a tolerance
    // relative to the size so that hulls from noisy points are accepted. The full check is
    // quadratic; above a few million vertex–face pairs (large qhull hulls, convex by construction)
    // each face is checked against the vertices of the faces across its edges (local convexity,
    // which with closedness, outward winding and genus 0 is what a convex surface needs).
    const double tolerance = 1e-7 * size;
    const bool fullConvexityCheck = static_cast<double>(vertexCount) * static_cast<double>(faces_.size()) <= 4e6;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
        const Face& face = faces_[f];
        for (int i = 0; i < face.count; ++i)
            if (face.normal.dot(vertices_[faceVertices_[face.first + i]]) < face.offset - 1e-6 * size)
                throw InvalidInput(faceName(f) + " is not planar");
        if (face.normal.dot(centroid_) >= face.offset)
            throw InvalidInput(faceName(f) + " faces inwards (wrong winding)");
        if (!fullConvexityCheck) continue;
        for (int v = 0; v < vertexCount; ++v)
            if (face.normal.dot(vertices_[v]) > face.offset + tolerance)
                throw InvalidInput("vertex " + std::to_string(v) + " lies outside " + faceName(f) +
                                   ": the polytope is not convex");
    }

    // Edges (each undirected edge once) with the faces on either side: the arcs of the Gauss map.
    std::map<std::pair<int, int>, int> leftFaceOf;
    for (std::size_t f = 0; f < faces_.size(); ++f)
        for (int i = 0; i < faces_[f].count; ++i)
            leftFaceOf[{faceVertices_[faces_[f].first + i],
                        faceVertices_[faces_[f].first + (i + 1) % faces_[f].count]}] = static_cast<int>(f);
    edges_.clear();
    for (const auto& [key, face] : leftFaceOf)
        if (key.first < key.second) {
            auto opposite = leftFaceOf.find({key.second, key.first});
            if (opposite == leftFaceOf.end()) throw InvalidInput("the surface is not closed");
            edges_.push_back({key.first, key.second, face, opposite->second});
        }
    if (!fullConvexityCheck)
        for (const Edge& edge : edges_)
            for (auto [face, other] : {std::pair{edge.leftFace, edge.rightFace}, std::pair{edge.rightFace, edge.leftFace}})
                for (int i = 0; i < faces_[other].count; ++i) {
                    int v = faceVertices_[faces_[other].first + i];
                    if (faces_[face].normal.dot(vertices_[v]) > faces_[face].offset + tolerance)
                        throw InvalidInput("vertex " + std::to_string(v) + " lies outside " + faceName(face) +
                                           ": the polytope is not convex");
                }
    if (vertexCount - static_cast<int>(edges_.size()) + static_cast<int>(faces_.size()) != 2)
        throw InvalidInput("the faces do not form a closed surface of genus 0 (Euler characteristic ≠ 2)");

    // Per-vertex adjacency in compressed rows: neighbours, incident faces, incident edges.
    std::vector<std::vector<int>> neighbours(vertexCount), incidentFaces(vertexCount), incidentEdges(vertexCount);
    for (std::size_t e = 0; e < edges_.size(); ++e) {
        neighbours[edges_[e].tail].push_back(edges_[e].head);
        neighbours[edges_[e].head].push_back(edges_[e].tail);
        incidentEdges[edges_[e].tail].push_back(static_cast<int>(e));
        incidentEdges[edges_[e].head].push_back(static_cast<int>(e));
    }
    for (std::size_t f = 0; f < faces_.size(); ++f)
        for (int i = 0; i < faces_[f].count; ++i)
            incidentFaces[faceVertices_[faces_[f].first + i]].push_back(static_cast<int>(f));
    neighborOffsets_.assign(1, 0);
    vertexFaceOffsets_.assign(1, 0);
    neighbors_.clear(), vertexFaces_.clear(), vertexEdges_.clear();
    for (int v = 0; v < vertexCount; ++v) {
        if (incidentFaces[v].size() != incidentEdges[v].size() || incidentFaces[v].size() < 3)
            throw InvalidInput("vertex " + std::to_string(v) + " is not a proper corner of the surface");
        neighbors_.insert(neighbors_.end(), neighbours[v].begin(), neighbours[v].end());
        vertexFaces_.insert(vertexFaces_.end(), incidentFaces[v].begin(), incidentFaces[v].end());
        vertexEdges_.insert(vertexEdges_.end(), incidentEdges[v].begin(), incidentEdges[v].end());
        neighborOffsets_.push_back(static_cast<int>(neighbors_.size()));
        vertexFaceOffsets_.push_back(static_cast<int>(vertexFaces_.size()));
    }
    // Each face's neighbourhood: the faces sharing a vertex with it, each once, in the order the
    // face's loop and each vertex's face list meet them (the overhang check's candidates).
    faceNeighbourhoodOffsets_.assign(1, 0);
    faceNeighbourhoods_.clear();
    for (const Face& face : faces_) {
        const std::size_t begin = faceNeighbourhoods_.size();
        for (int i = 0; i < face.count; ++i) {
            const int v = faceVertices_[face.first + i];
            for (int k = vertexFaceOffsets_[v]; k < vertexFaceOffsets_[v + 1]; ++k)
                if (std::find(faceNeighbourhoods_.begin() + begin, faceNeighbourhoods_.end(), vertexFaces_[k]) ==
                    faceNeighbourhoods_.end())
                    faceNeighbourhoods_.push_back(vertexFaces_[k]);
        }
        faceNeighbourhoodOffsets_.push_back(static_cast<int>(faceNeighbourhoods_.size()));
    }
    const bool boundsOtherFaces = faces_.size() <= static_cast<std::size_t>(kOtherFaceCosineMaxFaces);
    for (Face& face : faces_) {
        face.largestOtherCosine = boundsOtherFaces ? -1 : 2;
        if (boundsOtherFaces)
            for (const Face& other : faces_)
                if (&other != &face) face.largestOtherCosine = std::max(face.largestOtherCosine, face.normal.dot(other.normal));
    }
    for (Face& face : faces_) {
        face.nearestNeighbourCosine = -1;
        for (int i = 0; i < face.count; ++i) {
            const int v = faceVertices_[face.first + i];
            for (int k = vertexFaceOffsets_[v]; k < vertexFaceOffsets_[v + 1]; ++k) {
                const Face& other = faces_[vertexFaces_[k]];
                if (&other != &face)
                    face.nearestNeighbourCosine = std::max(face.nearestNeighbourCosine, face.normal.dot(other.normal));
            }
        }
    }
    for (Edge& edge : edges_) {
        const Vec3 along = (vertices_[edge.head] - vertices_[edge.tail]).normalized();
        edge.straightestNeighbourCosine = -1;
        // Away from the tail, through the head: an edge continuing it runs head → other end; one
        // continuing it backwards runs other end → tail.
        for (const auto& [end, sign] : {std::pair{edge.head, 1.0}, std::pair{edge.tail, -1.0}})
            for (int k = vertexFaceOffsets_[end]; k < vertexFaceOffsets_[end + 1]; ++k) {
                const Edge& other = edges_[vertexEdges_[k]];
                if (&other == &edge) continue;
                const int far = other.tail == end ? other.head : other.tail;
                const double cosine = sign * (vertices_[far] - vertices_[end]).normalized().dot(along);
                edge.straightestNeighbourCosine = std::max(edge.straightestNeighbourCosine, cosine);
            }
    }
    radius_ = 0;
    for (const Vec3& v : vertices_) radius_ = std::max(radius_, (v - centroid_).norm());
    inradius_ = INFINITY;
    for (const Face& face : faces_)
        for (int i = 0; i < face.count; ++i)
            inradius_ = std::min(inradius_, face.normal.dot(vertices_[faceVertices_[face.first + i]] - centroid_));
    inradius_ = std::max(inradius_, 0.0);

    // Seeds for hill climbing: the brute-force supports of the 26 directions of a cube's faces,
    // edges and corners (duplicates removed).
    supportSeeds_.clear();
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                int seed = supportVertex(Vec3(x, y, z), vertexCount);
                if (std::find(supportSeeds_.begin(), supportSeeds_.end(), seed) == supportSeeds_.end())
                    supportSeeds_.push_back(seed);
            }
    computeFingerprint();
}

// splitmix64's finaliser (Steele, Lea, Flood 2014) over every number a query reads: vertices,
// face planes and loops, and the box flag. Doubles are hashed by their bits, so −0 and 0 differ:
// the fingerprint promises identical answers, not equal shapes.

}  // namespace gdc
