#include "gauss_map.hpp"

#include <cmath>

namespace gdc::detail {

Feature selectFeature(const Polytope& polytope, const Vec3& direction, const AngularTolerance& tolerance,
                      int bruteForceLimit) {
    // The region containing `direction` belongs to the support vertex, so every candidate face
    // and edge within the tolerance is incident to it (for tolerances below the polytope's
    // smallest dihedral turn, which is what the tolerance is for).
    const int vertex = polytope.supportVertex(direction, bruteForceLimit);
    const int begin = polytope.vertexFaceOffsets()[vertex], end = polytope.vertexFaceOffsets()[vertex + 1];

    Feature best{FeatureType::Vertex, vertex};
    double bestCos = tolerance.cosine;
    for (int i = begin; i < end; ++i) {
        int face = polytope.vertexFaces()[i];
        double c = polytope.faces()[face].normal.dot(direction);
        if (c >= bestCos) bestCos = c, best = {FeatureType::Face, face};
    }
    if (best.type == FeatureType::Face) return best;

    // An edge qualifies when `direction` is within the tolerance of its arc: nearly perpendicular
    // to the edge, and between the two face normals once projected onto the arc's great circle.
    double bestSin = tolerance.sine;
    for (int i = begin; i < end; ++i) {
        int edgeIndex = polytope.vertexEdges()[i];
        const Polytope::Edge& edge = polytope.edges()[edgeIndex];
        Vec3 along = (polytope.vertices()[edge.head] - polytope.vertices()[edge.tail]).normalized();
        double s = std::abs(along.dot(direction));
        if (s > bestSin) continue;
        Vec3 projected = direction - along.dot(direction) * along;
        const Vec3& left = polytope.faces()[edge.leftFace].normal;
        const Vec3& right = polytope.faces()[edge.rightFace].normal;
        Vec3 arcAxis = left.cross(right);
        bool betweenNormals = left.cross(projected).dot(arcAxis) >= 0 && projected.cross(right).dot(arcAxis) >= 0;
        if (betweenNormals) bestSin = s, best = {FeatureType::Edge, edgeIndex};
    }
    return best;
}

int featureVertices(const Polytope& polytope, const Feature& feature, const int** indices, int* storage) {
    switch (feature.type) {
        case FeatureType::Vertex:
            storage[0] = feature.index;
            *indices = storage;
            return 1;
        case FeatureType::Edge:
            storage[0] = polytope.edges()[feature.index].tail;
            storage[1] = polytope.edges()[feature.index].head;
            *indices = storage;
            return 2;
        case FeatureType::Face:
        default: {
            const Polytope::Face& face = polytope.faces()[feature.index];
            *indices = polytope.faceVertices().data() + face.first;
            return face.count;
        }
    }
}

}  // namespace gdc::detail
