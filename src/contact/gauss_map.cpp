#include "contact/gauss_map.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {

Feature selectFeature(const Polytope& polytope, const Vec3& direction, int support, const AngularTolerance& tolerance) {
    // The region containing `direction` belongs to the support vertex, so the candidate faces and
    // edges are those around it (for tolerances below the polytope's smallest dihedral turn, which
    // is what the tolerance is for). When `direction` lies on (or within the tolerance of) an
    // arc — an edge nearly perpendicular to it, as every edge–edge normal is — the edge's other
    // end supports as well and rounding decides which one supportVertex() returns; its faces and
    // edges are candidates too, so that the choice does not depend on that rounding (it made
    // collide(A, B) and collide(B, A) pick a face in one and an edge in the other).
    // The adjacency read through plain pointers (so their bounds are not reloaded after every
    // push_back) and the face test as scalar code, the same operations in the same order as
    // Eigen's dot ((n₀d₀ + n₁d₁) + n₂d₂), so the same bits: the face test is most of a hull's
    // feature selection, and Eigen spends packet shuffles on 3-vectors.
    const int vertex = support;
    const Vec3* vertices = polytope.vertices().data();
    const int* neighborOffsets = polytope.neighborOffsets().data();
    const int* neighbors = polytope.neighbors().data();
    const int* faceOffsets = polytope.vertexFaceOffsets().data();
    const int* vertexFaces = polytope.vertexFaces().data();
    const Polytope::Face* faces = polytope.faces().data();
    const double sineSquared = tolerance.sine * tolerance.sine;
    SmallVector<int, 8> around;
    around.push_back(vertex);
    const Vec3& apex = vertices[vertex];
    for (int k = neighborOffsets[vertex], end = neighborOffsets[vertex + 1]; k < end; ++k) {
        const int neighbour = neighbors[k];
        // direction·edge ≤ sin(tolerance)·|edge|, squared to spare the root (the left side is
        // never negative: the apex supports).
        const Vec3 edge = apex - vertices[neighbour];
        const double along = direction.dot(edge);
        if (along <= 0 || along * along <= sineSquared * edge.squaredNorm()) around.push_back(neighbour);
    }

    const double dx = direction.x(), dy = direction.y(), dz = direction.z();
    Feature best{FeatureType::Vertex, vertex};
    double bestCos = tolerance.cosine;
    for (int v : around)
        for (int i = faceOffsets[v], end = faceOffsets[v + 1]; i < end; ++i) {
            const int face = vertexFaces[i];
            const Vec3& n = faces[face].normal;
            const double c = n.x() * dx + n.y() * dy + n.z() * dz;
            if (c > bestCos || (c == bestCos && (best.type != FeatureType::Face || face < best.index)))
                bestCos = c, best = {FeatureType::Face, face};  // ties: the lowest index, in any visiting order
        }
    if (best.type == FeatureType::Face) return best;

    // An edge qualifies when `direction` is within the tolerance of its arc: nearly perpendicular
    // to the edge, and between the two face normals once projected onto the arc's great circle.
    double bestSin = tolerance.sine;
    for (int v : around)
        for (int i = polytope.vertexFaceOffsets()[v]; i < polytope.vertexFaceOffsets()[v + 1]; ++i) {
            int edgeIndex = polytope.vertexEdges()[i];
            const Polytope::Edge& edge = polytope.edges()[edgeIndex];
            Vec3 along = (polytope.vertices()[edge.head] - polytope.vertices()[edge.tail]).normalized();
            double s = std::abs(along.dot(direction));
            if (s > bestSin || (s == bestSin && best.type == FeatureType::Edge && edgeIndex > best.index)) continue;
            Vec3 projected = direction - along.dot(direction) * along;
            const Vec3& left = polytope.faces()[edge.leftFace].normal;
            const Vec3& right = polytope.faces()[edge.rightFace].normal;
            Vec3 arcAxis = left.cross(right);
            bool betweenNormals = left.cross(projected).dot(arcAxis) >= 0 && projected.cross(right).dot(arcAxis) >= 0;
            if (betweenNormals) bestSin = s, best = {FeatureType::Edge, edgeIndex};
        }
    return best;
}

void faceCap(const Polytope& polytope, int face, const Vec3& direction, const AngularTolerance& tolerance,
             SmallVector<int, 8>& faces) {
    faces.clear();
    faces.push_back(face);
    // A face within the tolerance of `direction` whose nearest neighbour on the Gauss map is more
    // than twice the tolerance away has no neighbour within it (angle(neighbour, direction) ≥
    // angle(neighbour, face) − angle(face, direction) > 2·tolerance − tolerance): the cap is the
    // face alone, found without the search (every face of a box, most faces of a coarse hull).
    // cos(2θ) = 2·cos²θ − 1; the small slack keeps rounding on the side of searching.
    constexpr double kCosineSlack = 1e-9;
    const Polytope::Face& selected = polytope.faces()[face];
    const double twiceToleranceCosine = 2 * tolerance.cosine * tolerance.cosine - 1;
    if (tolerance.cosine >= 0 && selected.normal.dot(direction) >= tolerance.cosine &&
        selected.nearestNeighbourCosine < twiceToleranceCosine - kCosineSlack)
        return;
    auto contains = [&](int f) {
        for (int g : faces)
            if (g == f) return true;
        return false;
    };
    // Breadth first over faces sharing a vertex; a box's neighbours fail the test at once. The
    // adjacency arrays are read through plain pointers so their bounds are not reloaded after
    // every push_back.
    const int* faceVertices = polytope.faceVertices().data();
    const int* offsets = polytope.vertexFaceOffsets().data();
    const int* vertexFaces = polytope.vertexFaces().data();
    for (std::size_t next = 0; next < faces.size(); ++next) {
        const Polytope::Face& current = polytope.faces()[faces[next]];
        for (int i = 0; i < current.count; ++i) {
            const int vertex = faceVertices[current.first + i];
            for (int k = offsets[vertex], end = offsets[vertex + 1]; k < end; ++k) {
                const int candidate = vertexFaces[k];
                if (polytope.faces()[candidate].normal.dot(direction) < tolerance.cosine || contains(candidate)) continue;
                if (static_cast<int>(faces.size()) >= kMaxCapFaces) return;
                faces.push_back(candidate);
            }
        }
    }
}

namespace {

// Whether `direction` is within the tolerance of the edge's arc: nearly perpendicular to the edge
// and, projected onto the arc's great circle, between its two face normals (selectFeature's test).
bool withinArc(const Polytope& polytope, const Polytope::Edge& edge, const Vec3& direction,
               const AngularTolerance& tolerance) {
    const Vec3 along = (polytope.vertices()[edge.head] - polytope.vertices()[edge.tail]).normalized();
    if (std::abs(along.dot(direction)) > tolerance.sine) return false;
    const Vec3 projected = direction - along.dot(direction) * along;
    const Vec3& left = polytope.faces()[edge.leftFace].normal;
    const Vec3& right = polytope.faces()[edge.rightFace].normal;
    const Vec3 arcAxis = left.cross(right);
    return left.cross(projected).dot(arcAxis) >= 0 && projected.cross(right).dot(arcAxis) >= 0;
}

}  // namespace

void edgeChain(const Polytope& polytope, int edge, const Vec3& direction, const AngularTolerance& tolerance,
               SmallVector<int, 8>& edges) {
    edges.clear();
    edges.push_back(edge);
    // No neighbour continues the edge within the tolerance: the chain is the edge alone, found
    // without the walk (every edge of a box, most edges of a coarse hull).
    const Polytope::Edge& selected = polytope.edges()[edge];
    if (!(selected.straightestNeighbourCosine >= tolerance.cosine)) return;
    const std::vector<Vec3>& vertices = polytope.vertices();
    const Vec3 along = (vertices[selected.head] - vertices[selected.tail]).normalized();
    const int* offsets = polytope.vertexFaceOffsets().data();
    const int* vertexEdges = polytope.vertexEdges().data();
    // Walk from each end outwards, each step to the straightest continuation that qualifies (ties:
    // the lowest index), so the chain is the same whichever of its edges was selected.
    for (const auto& [start, sign] : {std::pair{selected.head, 1.0}, std::pair{selected.tail, -1.0}}) {
        int vertex = start;
        while (static_cast<int>(edges.size()) < kMaxChainEdges) {
            int next = -1, far = -1;
            double bestCosine = tolerance.cosine;
            for (int k = offsets[vertex], end = offsets[vertex + 1]; k < end; ++k) {
                const int candidate = vertexEdges[k];
                bool known = false;
                for (int e : edges) known |= e == candidate;
                if (known) continue;
                const Polytope::Edge& other = polytope.edges()[candidate];
                const int otherEnd = other.tail == vertex ? other.head : other.tail;
                const double cosine = sign * (vertices[otherEnd] - vertices[vertex]).normalized().dot(along);
                if (cosine < bestCosine || (cosine == bestCosine && next >= 0 && candidate > next)) continue;
                if (!withinArc(polytope, other, direction, tolerance)) continue;
                bestCosine = cosine, next = candidate, far = otherEnd;
            }
            if (next < 0) break;
            edges.push_back(next);
            vertex = far;
        }
    }
    std::sort(edges.data(), edges.data() + edges.size());
}

void capVertices(const Polytope& polytope, const SmallVector<int, 8>& cap, SmallVector<int, 32>& vertices) {
    for (int f : cap) {
        const Polytope::Face& face = polytope.faces()[f];
        for (int i = 0; i < face.count; ++i) {
            const int vertex = polytope.faceVertices()[face.first + i];
            bool seen = false;
            for (int v : vertices) seen |= v == vertex;
            if (!seen) vertices.push_back(vertex);
        }
    }
}

}  // namespace gdc::detail
