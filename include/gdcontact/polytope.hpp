// A convex polytope in its local frame: vertices, CCW faces with planes, edges and adjacency
// (its Gauss map), and an interior contraction point. Immutable once built; safe to share
// between threads.
#pragma once

#include <gdcontact/settings.hpp>
#include <gdcontact/types.hpp>

#include <cstdint>
#include <vector>

namespace gdc {

class GDCONTACT_API Polytope {
public:
    /// A planar face. Its vertices, counter-clockwise seen from outside, are
    /// faceVertices()[first .. first + count). Points x inside satisfy normal·x ≤ offset.
    struct Face {
        Vec3 normal;
        double offset;
        int first;
        int count;
        /// The largest cosine between this face's normal and that of another face sharing a
        /// vertex with it: how close its nearest neighbour on the Gauss map is (bounds caps).
        double nearestNeighbourCosine = -1;
        /// The largest cosine between this face's normal and that of any other face (every face,
        /// not only its neighbours), for polytopes of at most kOtherFaceCosineMaxFaces faces; 2
        /// (no bound) for larger ones. Stage 2 proves with it that a face is the Gauss-map feature
        /// along a direction near its normal without searching (gauss_map.hpp, faceIsSelected).
        double largestOtherCosine = 2;
    };
    /// Most faces for which Face::largestOtherCosine is computed (it takes F² dot products).
    static constexpr int kOtherFaceCosineMaxFaces = 64;
    /// An edge between vertices `tail` and `head`. On the Gauss map it is the arc between the
    /// normals of its two faces; `leftFace` has the edge tail→head in its CCW order.
    struct Edge {
        int tail;
        int head;
        int leftFace;
        int rightFace;
        /// The largest cosine between this edge's direction and that of an edge continuing it at
        /// either end (the next edge's direction taken away from the shared vertex): how nearly
        /// collinear its straightest neighbour is (bounds edge chains, as the face's bounds caps).
        double straightestNeighbourCosine = -1;
    };

    /// Convex hull of a point cloud (qhull). Throws InvalidInput for fewer than 4 points, NaN/Inf
    /// coordinates, or points that are collinear or coplanar (no interior).
    static Polytope fromPoints(const std::vector<Vec3>& points, const Settings& settings = {});
    /// From explicit faces, each a list of vertex indices, counter-clockwise seen from outside.
    /// Validated: closed, consistently wound, convex, planar, non-degenerate; coplanar
    /// neighbouring faces are merged. Throws InvalidInput naming the offending face otherwise.
    static Polytope fromFaces(const std::vector<Vec3>& vertices,
                              const std::vector<std::vector<int>>& faces,
                              const Settings& settings = {});
    /// An axis-aligned box centred at the origin. Throws InvalidInput unless every half extent is
    /// finite and positive.
    static Polytope box(const Vec3& halfExtents);

    const std::vector<Vec3>& vertices() const { return vertices_; }
    const std::vector<Face>& faces() const { return faces_; }
    const std::vector<int>& faceVertices() const { return faceVertices_; }
    const std::vector<Edge>& edges() const { return edges_; }
    /// Neighbours of vertex v: neighbors()[neighborOffsets()[v] .. neighborOffsets()[v+1]).
    const std::vector<int>& neighborOffsets() const { return neighborOffsets_; }
    const std::vector<int>& neighbors() const { return neighbors_; }
    /// Faces around vertex v: vertexFaces()[vertexFaceOffsets()[v] .. vertexFaceOffsets()[v+1]).
    const std::vector<int>& vertexFaceOffsets() const { return vertexFaceOffsets_; }
    const std::vector<int>& vertexFaces() const { return vertexFaces_; }
    /// Edges around vertex v: vertexEdges()[vertexFaceOffsets()[v] .. vertexFaceOffsets()[v+1])
    /// (a vertex of a closed polytope has as many edges as faces).
    const std::vector<int>& vertexEdges() const { return vertexEdges_; }
    /// Faces sharing a vertex with face f, each once (f among them):
    /// faceNeighbourhoods()[faceNeighbourhoodOffsets()[f] .. faceNeighbourhoodOffsets()[f+1]).
    const std::vector<int>& faceNeighbourhoodOffsets() const { return faceNeighbourhoodOffsets_; }
    const std::vector<int>& faceNeighbourhoods() const { return faceNeighbourhoods_; }

    /// Volume centroid: the contraction point of the growth distance (always interior).
    const Vec3& centroid() const { return centroid_; }
    /// Largest distance from the centroid to a vertex.
    double radius() const { return radius_; }
    /// Radius of a ball about the centroid inside the polytope: the smallest distance from the
    /// centroid to a face's plane, each plane taken through the face's lowest vertex (so that a face
    /// merged within the coplanar tolerance cannot overstate it). Every support value of the
    /// polytope about its centroid is at least this: a lower bound on overlaps that costs nothing.
    double inradius() const { return inradius_; }
    double volume() const { return volume_; }
    /// True for polytopes made by box(): their support mapping and growth distance take exact
    /// closed-form fast paths that give the same answers as the general algorithms.
    bool isBox() const { return isBox_; }
    const Vec3& boxHalfExtents() const { return boxHalfExtents_; }
    /// A 64-bit hash of everything a contact query reads of the polytope (vertices, faces, the box
    /// flag): equal for copies, different — but for a 2⁻⁶⁴ chance — for any other shape. A
    /// PairCache recognises its shapes by it, so a polytope freed and another built at the same
    /// address is never mistaken for the first.
    std::uint64_t fingerprint() const { return fingerprint_; }

    /// Index of a vertex maximising direction·vertex (brute force up to `bruteForceLimit`
    /// vertices, hill climbing over adjacency above it). `start`, when a vertex index, is where the
    /// climb begins — the support of a nearby direction makes it a few steps (warm start);
    /// otherwise it begins at the best of fixed seeds.
    int supportVertex(const Vec3& direction, int bruteForceLimit = 32, int start = -1) const;

private:
    Polytope() = default;
    void buildTopology(double coplanarTolerance);
    void computeFingerprint();

    std::vector<Vec3> vertices_;
    std::vector<Face> faces_;
    std::vector<int> faceVertices_;
    std::vector<Edge> edges_;
    std::vector<int> neighborOffsets_, neighbors_;
    std::vector<int> vertexFaceOffsets_, vertexFaces_, vertexEdges_;
    std::vector<int> faceNeighbourhoodOffsets_, faceNeighbourhoods_;
    std::vector<int> supportSeeds_;  // hill-climbing starts: supports of 26 fixed directions
    Vec3 centroid_ = Vec3::Zero();
    double radius_ = 0.0;
    double inradius_ = 0.0;
    double volume_ = 0.0;
    bool isBox_ = false;
    Vec3 boxHalfExtents_ = Vec3::Zero();
    std::uint64_t fingerprint_ = 0;
};

}  // namespace gdc
