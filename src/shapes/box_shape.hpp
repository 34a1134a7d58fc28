// The box's shape hooks: what a box made by Polytope::box supplies to the pipeline in closed form
// where a hull searches its tables — the support vertex, the Gauss-map feature of a direction, and
// that feature's geometry. Used by the box–box path (box_box.cpp) and the box–half-space path
// (half_space.cpp); tests/box_box_test.cpp and tests/half_space_test.cpp check each against the
// hull's general answer (Polytope::supportVertex, selectFeature, featureVertices).
#pragma once

#include "shapes/feature.hpp"

#include <gdcontact/polytope.hpp>

#include <optional>

namespace gdc::detail {

/// Polytope::box numbers vertex v with the signs of its bits (x: 1, y: 2, z: 4), the faces
/// −x, +x, −y, +y, −z, +z, and Polytope::buildTopology the edges in the order of their (tail, head)
/// vertex pairs, tail < head: (0,1) (0,2) (0,4) (1,3) (1,5) (2,3) (2,6) (3,7) (4,5) (4,6) (5,7) (6,7).
/// kBoxEdge[v][axis] is the edge from v along `axis` (box_box_test checks both against Polytope::box).
constexpr int kBoxEdge[8][3] = {{0, 1, 2}, {0, 3, 4}, {5, 1, 6}, {5, 3, 7},
                                {8, 9, 2}, {8, 10, 4}, {11, 9, 6}, {11, 10, 7}};

/// The face of a box whose outward normal is +e_axis (`positive`) or −e_axis.
constexpr int boxFace(int axis, bool positive) { return 2 * axis + (positive ? 1 : 0); }

/// Polytope::supportVertex for a box: the vertex with the signs of `direction` (the lowest index of
/// equals where a component is 0, as the search finds it).
inline int boxSupport(const Vec3& direction) {
    return (direction.x() > 0 ? 1 : 0) | (direction.y() > 0 ? 2 : 0) | (direction.z() > 0 ? 4 : 0);
}

/// The comparisons of selectFeature with the Gauss-map tolerance's cosine and sine, exactly as
/// AngularTolerance(radians) decides them, settled by Taylor bounds (cos θ ∈ [1 − θ²/2, 1 − θ²/2 +
/// θ⁴/24], sin θ ∈ [θ − θ³/6, θ] for 0 ≤ θ ≤ 1) wherever the value is clear of them by far more
/// than rounding; only a value within that slack of the tolerance pays for AngularTolerance's
/// series, whose numbers then decide.
class LazyAngularTolerance {
public:
    explicit LazyAngularTolerance(double radians) : radians_(radians), square_(radians * radians) {}

    /// c ≥ AngularTolerance(radians).cosine: a face within the tolerance.
    bool withinCosine(double c) {
        const double lower = 1 - 0.5 * square_;
        if (c >= lower + square_ * square_ / 24 + kSlack) return true;
        if (c < lower - kSlack) return false;
        return c >= exact().cosine;
    }
    /// s ≤ AngularTolerance(radians).sine: an edge within the tolerance.
    bool withinSine(double s) {
        if (s <= radians_ - radians_ * square_ / 6 - kSlack) return true;
        if (s > radians_ + kSlack) return false;
        return s <= exact().sine;
    }

private:
    // Far above the rounding of the bounds and of AngularTolerance's series (a few 1e-16).
    static constexpr double kSlack = 1e-14;
    const AngularTolerance& exact() {
        if (!exact_) exact_.emplace(radians_);
        return *exact_;
    }
    double radians_, square_;
    std::optional<AngularTolerance> exact_;
};

/// selectFeature(box, direction, support, tolerance) in closed form, for a tolerance below π/4
/// (`tolerance` answers withinCosine and withinSine: LazyAngularTolerance, or an AngularTolerance's
/// numbers). A box's face normals are exactly ±e_k and its edge directions exactly ±e_k
/// (box_box_test checks it), so every number selectFeature compares is a component of `direction`
/// up to sign, exactly:
/// - faces: the face of the support vertex along axis k has cosine |d_k|; the other candidates
///   (faces of neighbouring vertices) are the same faces or opposite ones at −|d_k|, which never
///   win. So the face is the axis of largest |d_k| (ties: the lowest axis, the lowest face index),
///   when |d_k| ≥ cos θ.
/// - edges: the edge along axis k has sine |d_k|, and every edge of the support vertex passes the
///   between-the-normals test (its faces' normals point along the signs of d). An edge of a
///   neighbour passes it only where a component of d is exactly 0, and then ties with the support
///   vertex's parallel edge, whose index is lower. So the edge is the smallest |d_k| (ties: the
///   lowest edge index), when |d_k| ≤ sin θ.
/// `support` is boxSupport(direction). Always inlined: a call of its own cost box–plane 2 %.
template <class Tolerance>
[[gnu::always_inline]] inline Feature selectBoxFeature(const Vec3& direction, int support, Tolerance& tolerance) {
    const Vec3 c = direction.cwiseAbs();
    int axis = c.y() > c.x() ? 1 : 0;
    if (c.z() > c[axis]) axis = 2;
    if (tolerance.withinCosine(c[axis])) return {FeatureType::Face, 2 * axis + ((support >> axis) & 1)};
    const int* edges = kBoxEdge[support];
    int edge = edges[0];
    double sine = c.x();
    for (int k = 1; k < 3; ++k)
        if (c[k] < sine || (c[k] == sine && edges[k] < edge)) sine = c[k], edge = edges[k];
    if (tolerance.withinSine(sine)) return {FeatureType::Edge, edge};
    return {FeatureType::Vertex, support};
}

/// selectBoxFeature with an AngularTolerance's own numbers (for a caller that has them).
Feature selectBoxFeature(const Vec3& direction, const AngularTolerance& tolerance);

/// A box feature in the common frame without heap storage: its vertices (1, 2 or the face's 4, in
/// the polytope's order) and, for a face, its plane. A box face has no cap below π/4.
struct BoxFeature {
    FeatureType type = FeatureType::Vertex;
    int count = 0;
    Vec3 points[4];
    Vec3 planeNormal = Vec3::Zero();  // faces only
    double planeOffset = 0;
};

inline FeatureView view(const BoxFeature& feature) {
    return {feature.type, feature.points, feature.count, feature.planeNormal, feature.planeOffset, nullptr, 0};
}

/// The geometry of `feature` of `box` mapped by `toCommon` (nullptr: the box's own frame) with the
/// general pipeline's arithmetic (collide.cpp, featureGeometry: the same Pose::apply of the same
/// vertices, the same plane), so to the bit: A's own vertices as they are (the identity pose
/// changes no bit). Inline: the box–box path calls it twice, with and without `toCommon`.
inline BoxFeature boxFeature(const Polytope& box, const Feature& feature, const Pose* toCommon) {
    BoxFeature geometry;
    geometry.type = feature.type;
    int storage[2];
    const int* indices = nullptr;
    geometry.count = featureVertices(box, feature, &indices, storage);
    for (int i = 0; i < geometry.count; ++i)
        geometry.points[i] = toCommon ? toCommon->apply(box.vertices()[indices[i]]) : box.vertices()[indices[i]];
    if (feature.type == FeatureType::Face) {
        const Polytope::Face& face = box.faces()[feature.index];
        if (toCommon) {
            geometry.planeNormal = toCommon->rotation * face.normal;
            geometry.planeOffset = face.offset + geometry.planeNormal.dot(toCommon->position);
        } else {
            geometry.planeNormal = face.normal;
            geometry.planeOffset = face.offset;
        }
    }
    return geometry;
}


}  // namespace gdc::detail
