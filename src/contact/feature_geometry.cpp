// The general pipeline's features in A's frame and the depth certificate (feature_geometry.hpp).
#include "contact/feature_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {

// The feature geometries below place the polytope's vertices in the common frame by `toCommon`,
// unless `common` has them there already (bit for bit: A's own where toCommon is the identity, and
// then its planes too; B's as the hull enumeration placed them, hull_gauge.hpp).
FeatureGeometry faceGeometry(const Polytope& polytope, int index, const Pose& toCommon, const Vec3* common) {
    FeatureGeometry geometry;
    geometry.type = FeatureType::Face;
    const Polytope::Face& face = polytope.faces()[index];
    for (int i = 0; i < face.count; ++i) {
        const int vertex = polytope.faceVertices()[face.first + i];
        geometry.points.push_back(common ? common[vertex] : toCommon.apply(polytope.vertices()[vertex]));
    }
    if (common == polytope.vertices().data()) {  // the identity: what the product would give
        geometry.planeNormal = face.normal;
        geometry.planeOffset = face.offset;
    } else {
        geometry.planeNormal = toCommon.rotation * face.normal;
        geometry.planeOffset = face.offset + geometry.planeNormal.dot(toCommon.position);
    }
    return geometry;
}

FeatureGeometry edgeGeometry(const Polytope& polytope, int index, const Pose& toCommon, const Vec3* common) {
    FeatureGeometry geometry;
    geometry.type = FeatureType::Edge;
    const Polytope::Edge& edge = polytope.edges()[index];
    geometry.points.push_back(common ? common[edge.tail] : toCommon.apply(polytope.vertices()[edge.tail]));
    geometry.points.push_back(common ? common[edge.head] : toCommon.apply(polytope.vertices()[edge.head]));
    return geometry;
}

// The pieces of a selected feature: the faces of a face's cap or the edges of an edge's chain
// (gauss_map.hpp), the selected one among them; nothing for a vertex. `direction` is the contact
// normal in the polytope's own frame, pointing away from the body (n for A, −n for B).
void featurePieces(const Polytope& polytope, const Feature& feature, const Vec3& direction,
                   const AngularTolerance& angularTolerance, SmallVector<int, 8>& pieces) {
    pieces.clear();
    if (feature.type == FeatureType::Face) faceCap(polytope, feature.index, direction, angularTolerance, pieces);
    else if (feature.type == FeatureType::Edge) edgeChain(polytope, feature.index, direction, angularTolerance, pieces);
}

// The feature in the common frame; with more than one piece (featurePieces) each is a feature of
// its own in `capFaces`, intersected one by one.
FeatureGeometry featureGeometry(const Polytope& polytope, const Feature& feature, const SmallVector<int, 8>& pieces,
                                const Pose& toCommon, const Vec3* common) {
    if (feature.type == FeatureType::Face || feature.type == FeatureType::Edge) {
        // A face's cap or an edge's chain: the same pieces of the one kind.
        auto pieceGeometry = feature.type == FeatureType::Face ? faceGeometry : edgeGeometry;
        FeatureGeometry geometry = pieceGeometry(polytope, feature.index, toCommon, common);
        if (pieces.size() > 1) {
            geometry.capFaces.reserve(pieces.size());
            for (int piece : pieces) geometry.capFaces.push_back(pieceGeometry(polytope, piece, toCommon, common));
        }
        return geometry;
    }
    FeatureGeometry geometry;
    geometry.type = feature.type;
    geometry.points.push_back(common ? common[feature.index] : toCommon.apply(polytope.vertices()[feature.index]));
    return geometry;
}

// Whether the deepest lifted point provably carries the whole penetration along n, so the ray cast
// of the depth confirmation (separationAlong) could not add a point. The penetration along n is
// t* = max{t : t·n ∈ A − B}, and every direction m with m·n > 0 bounds it from above by the support
// plane of A − B along m: t* ≤ overlap(m)/(m·n). The lifted point q is a lower bound, so a direction
// whose bound is within `slack` of q's depth settles it. The direction that makes the bound tight is
// the normal of the facet of A − B the ray leaves through, and q's provenance names it (van den
// Bergen 2004, §4.3.4: the facets of A − B are face ⊕ vertex and edge ⊕ edge): A's vertex inside B's
// face — B's face normal; B's vertex inside A's face — A's face normal; a crossing of an edge of
// each — their cross product. At most three candidates, two support searches each, where the ray
// cast takes dozens on the thin facets that a slightly tilted resting face makes of A − B.
// A feature with a cap (several faces) is represented by the face of it the point was lifted onto.
// Every direction gives a valid bound, so a wrong guess only costs the ray cast.
bool penetrationCertified(const LiftedPoint& deepest, const FeatureGeometry& featureA, const FeatureGeometry& featureB,
                          const Vec3& normal, const MinkowskiDifference& pair, double slack, double tolerance) {
    auto pieceOf = [](const FeatureGeometry& feature, int piece) -> const FeatureGeometry* {
        if (feature.capFaces.empty()) return &feature;
        return piece >= 0 && piece < static_cast<int>(feature.capFaces.size()) ? &feature.capFaces[piece] : nullptr;
    };
    const FeatureGeometry* pieceA = pieceOf(featureA, deepest.pieceA);
    const FeatureGeometry* pieceB = pieceOf(featureB, deepest.pieceB);
    if (!pieceA || !pieceB) return false;
    const FeatureGeometry& a = *pieceA;
    const FeatureGeometry& b = *pieceB;
    Vec3 u, v;
    planeBasis(normal, u, v);
    const Vec2& q = deepest.planar;
    auto planar = [&](const Vec3& p) { return Vec2(p.dot(u), p.dot(v)); };
    const double toleranceSquared = tolerance * tolerance;
    auto certifies = [&](const Vec3& m) {
        const double along = m.dot(normal);
        if (!(along > 1e-6 * m.norm())) return false;
        return pair.overlapAlong(m) / along <= deepest.depth + slack;
    };
    // Each feature's points projected once, for the vertex and the edge tests alike.
    // (Written through reserve()'s pointer: push_back would reload the vector after each store.)
    SmallVector<Vec2, 16> planarA, planarB;
    auto project = [&](const FeatureGeometry& feature, SmallVector<Vec2, 16>& out) {
        const std::size_t count = feature.points.size();
        Vec2* written = out.reserve(count);
        for (std::size_t i = 0; i < count; ++i) written[i] = planar(feature.points[i]);
        out.setSize(count);
    };
    project(a, planarA);
    project(b, planarB);
    auto isVertexOf = [&](const SmallVector<Vec2, 16>& points) {
        for (const Vec2& p : points)
            if ((p - q).squaredNorm() <= toleranceSquared) return true;
        return false;
    };
    if (b.type == FeatureType::Face && isVertexOf(planarA) && certifies(-b.planeNormal)) return true;
    if (a.type == FeatureType::Face && isVertexOf(planarB) && certifies(a.planeNormal)) return true;
    // Edges of a feature whose projection passes through q (within the tolerance).
    auto edgesThrough = [&](const FeatureGeometry& feature, const SmallVector<Vec2, 16>& points,
                            SmallVector<Vec3, 4>& out) {
        const int count = static_cast<int>(feature.points.size());
        const int edges = count >= 3 ? count : count - 1;
        for (int i = 0; i < edges && out.size() < 2; ++i) {
            const int next = i + 1 == count ? 0 : i + 1;
            const Vec2& e0 = points[i];
            const Vec2 d = points[next] - e0;
            const double lengthSquared = d.squaredNorm();
            if (!(lengthSquared > 0)) continue;
            const double t = std::clamp((q - e0).dot(d) / lengthSquared, 0.0, 1.0);
            if ((e0 + t * d - q).squaredNorm() <= toleranceSquared) out.push_back(feature.points[next] - feature.points[i]);
        }
    };
    SmallVector<Vec3, 4> edgesA, edgesB;
    edgesThrough(a, planarA, edgesA);
    edgesThrough(b, planarB, edgesB);
    for (const Vec3& edgeA : edgesA)
        for (const Vec3& edgeB : edgesB) {
            const Vec3 m = edgeA.cross(edgeB);
            if (certifies(m.dot(normal) < 0 ? Vec3(-m) : m)) return true;
        }
    return false;
}

}  // namespace gdc::detail
