// What a shape kind hands the paper's stages 2 and 3: its Gauss-map feature for a direction, as a
// value in the common (A's) frame — the points of a vertex, an edge or a face loop, a face's plane,
// and the pieces of a face's cap or an edge's chain — and the angular tolerance that widens faces
// and edges on the Gauss map. The contact stages (src/contact) read features only through these
// types; each shape kind (src/shapes, and the polytope's Gauss-map search in contact/gauss_map)
// makes them.
#pragma once

#include "geometry/small_vector.hpp"

#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>

#include <cmath>
#include <vector>

namespace gdc::detail {

/// The Gauss-map angular tolerance as its cosine and sine (computed once per query). Tolerances
/// are small angles, where the Taylor series to x¹⁶ is exact in double precision (the first
/// omitted term is below 1e-17 for x ≤ 0.8) at a fraction of the cost of the library call, which
/// showed in the profile of the cheapest queries (a hull on a plane); larger angles use it.
struct AngularTolerance {
    double cosine;
    double sine;
    explicit AngularTolerance(double radians) {
        if (!(std::abs(radians) <= 0.8)) {
            cosine = std::cos(radians), sine = std::sin(radians);
            return;
        }
        const double x2 = radians * radians;
        // Horner form of Σ (−x²)^k / (2k)! and x·Σ (−x²)^k / (2k+1)!, k = 0…8.
        double c = 1.0 / 20922789888000.0, s = 1.0 / 355687428096000.0;
        constexpr double kCosine[] = {-1.0 / 87178291200.0, 1.0 / 479001600.0, -1.0 / 3628800.0, 1.0 / 40320.0,
                                      -1.0 / 720.0,          1.0 / 24.0,        -1.0 / 2.0,        1.0};
        constexpr double kSine[] = {-1.0 / 1307674368000.0, 1.0 / 6227020800.0, -1.0 / 39916800.0, 1.0 / 362880.0,
                                    -1.0 / 5040.0,           1.0 / 120.0,        -1.0 / 6.0,        1.0};
        for (int k = 0; k < 8; ++k) c = c * x2 + kCosine[k], s = s * x2 + kSine[k];
        cosine = c, sine = s * radians;
    }
};

/// A feature in the common (A's) frame: its vertices and, for a face, its plane.
struct FeatureGeometry {
    FeatureType type = FeatureType::Vertex;
    SmallVector<Vec3, 16> points;  // 1 for a vertex, 2 for an edge, the loop of a face
    Vec3 planeNormal = Vec3::Zero();  // faces only
    double planeOffset = 0;
    // A face may come with its cap: the near-coplanar neighbours within the angular tolerance
    // (gauss_map.hpp). Then `capFaces` holds every face of the cap as a face feature of its own
    // (the selected one first); the intersection is the union of the pairwise intersections of
    // the two features' faces, each point lifted onto its own two faces, so every contact lies on
    // both surfaces exactly however the cap bends.
    std::vector<FeatureGeometry> capFaces;
};

/// A feature as stage 3 and the normal's refinement read it, whoever stores it: its points (1 for a
/// vertex, 2 for an edge, a face's loop) and, for a face, its plane, with the pieces of a face's cap
/// or an edge's chain where it has them. A box's feature lives in fixed arrays (box_shape.hpp,
/// BoxFeature: no pieces), a hull's in a FeatureGeometry; the view owns nothing, so the stages are
/// written once for both and a box pays for no container.
struct FeatureView {
    FeatureType type = FeatureType::Vertex;
    const Vec3* points = nullptr;
    int count = 0;
    Vec3 planeNormal = Vec3::Zero();  // faces only
    double planeOffset = 0;
    const FeatureGeometry* pieces = nullptr;  // FeatureGeometry::capFaces; nullptr and 0 for none
    int pieceCount = 0;
};

inline FeatureView view(const FeatureGeometry& feature) {
    return {feature.type,        feature.points.data(), static_cast<int>(feature.points.size()),
            feature.planeNormal, feature.planeOffset,   feature.capFaces.data(),
            static_cast<int>(feature.capFaces.size())};
}

/// The feature's vertices in order (1 for a vertex, 2 for an edge, the CCW loop of a face).
/// Inline: a few loads, which out of line would cost every query a call.
inline int featureVertices(const Polytope& polytope, const Feature& feature, const int** indices, int* storage) {
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
