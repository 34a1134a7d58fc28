// The contact query: the general hooks of the paper's three stages (composed once, pipeline.hpp)
// and collide()'s dispatch. Everything is computed in A's frame (precision far from the origin)
// and mapped to the world at the end.
#include <gdcontact/collide.hpp>

#include "contact/box_box.hpp"
#include "contact/collide_general.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/gauss_map.hpp"
#include "geometry/growth_distance.hpp"
#include "contact/half_space.hpp"
#include "contact/pipeline.hpp"
#include "geometry/hull_gauge.hpp"
#include "geometry/minkowski.hpp"
#include "contact/reduction.hpp"
#include "geometry/separating_axis.hpp"

#include <algorithm>
#include <cmath>

namespace gdc {
namespace {

using namespace detail;

void requireFinite(const Pose& pose, const char* which) {
    if (!pose.isFinite()) throw InvalidInput(std::string("the pose of ") + which + " is not finite");
}

// Contact normal when the growth distance has no answer (coincident contraction points, or a
// failed cast): the face normal of either body along which the overlap is smallest — the
// direction a separating-axis test would push them apart. Deterministic and swap-symmetric.
Vec3 minimumOverlapFaceNormal(const MinkowskiDifference& pair) {
    Vec3 best = Vec3::UnitZ();
    double bestOverlap = INFINITY;
    for (const Polytope::Face& face : pair.a.faces()) {
        double overlap = pair.overlapAlong(face.normal);
        if (overlap < bestOverlap) bestOverlap = overlap, best = face.normal;
    }
    for (const Polytope::Face& face : pair.b.faces()) {
        Vec3 normal = -(pair.bInA.rotation * face.normal);
        double overlap = pair.overlapAlong(normal);
        if (overlap < bestOverlap) bestOverlap = overlap, best = normal;
    }
    return best;
}

// The pair's overlap along `direction`, reusing `normalOverlap` (the overlap along `normal`, which
// the caller already has) when the direction is the normal itself: the face the normal came from
// is usually among the candidates of each later step. overlapAlong is a deterministic function of
// the direction's value, so the reused number is the one it would compute. Likewise an overlap an
// earlier stage already knows along exactly this direction (`known`, nullptr for none: the hull
// enumeration's, along the selected faces' normals), equal to the search's within rounding.
double overlapAlong(const MinkowskiDifference& pair, const KnownOverlaps* known, const Vec3& direction,
                    const Vec3& normal, double normalOverlap) {
    if (direction == normal) return normalOverlap;
    if (known)
        for (int i = 0; i < known->count; ++i)
            if (direction == known->directions[i]) return known->overlaps[i];
    return pair.overlapAlong(direction);
}


// Stage 1, second half: the growth-distance normal checked against the face normals around it.
// The growth distance scales both bodies about their contraction points, so for an offset,
// elongated pair — a cube hanging mostly off a plank's edge — the ray through the contraction
// points leaves A − B through a side facet, and its normal is far from the direction in which the
// bodies actually rest on each other (the minimum-translation direction). The faces incident to
// the two selected features bound the Gauss-map regions the normal landed in, so they are the
// nearby directions in which a face rests on the other body; if one of them needs clearly less
// translation to separate the pair, it is the contact normal. Otherwise the paper's normal stays.
// Candidates within rounding of the same overlap go to the one closest to the growth-distance
// normal, so collide(A, B) and collide(B, A) choose alike. Returns true when `normal` changed.
// `normalOverlap` is the pair's overlap along `normal`; both are updated together.
bool preferNearbyFaceNormal(const MinkowskiDifference& pair, const Feature& featureA, const SmallVector<int, 8>& piecesA,
                            const Feature& featureB, const SmallVector<int, 8>& piecesB, double tolerance,
                            const KnownOverlaps* known, Vec3& normal, double& normalOverlap) {
    const double current = normalOverlap;
    if (!(current > tolerance)) return false;  // touching or apart along n: n already separates them
    const double limit = kClearlySmallerOverlap * current;
    // A face's cap or an edge's chain (`pieces`, more than one) is one feature of several pieces,
    // and rounding selects one piece in A's frame and maybe another in B's: the faces around the
    // selected piece made collide(A, B) and collide(B, A) see different candidates (issue 21: a
    // needle's ragged end of two faces 0.005 rad apart, 0.035·s against 0.015·s). The candidates are
    // those around the piece of lowest index, the same in both frames. (The faces around every
    // piece would do too, but cost 8 % more per query on hulls of 4096 vertices, whose caps are
    // large, to enumerate candidates that the bound below then skips.)
    auto representative = [](const Feature& feature, const SmallVector<int, 8>& pieces) {
        if (pieces.size() <= 1) return feature;
        return Feature{feature.type, *std::min_element(pieces.data(), pieces.data() + pieces.size())};
    };
    const Feature representativeA = representative(featureA, piecesA);
    const Feature representativeB = representative(featureB, piecesB);
    // The features' own vertices (A's frame) bound every candidate's overlap from below: along c
    // the pair overlaps by at least max c·(A's feature) − min c·(B's feature), since those points
    // belong to A and B. Where that bound already reaches the limit, the two support searches of
    // overlapAlong cannot change the verdict and are skipped — for a face resting on a face the
    // bound along each side face is its exact overlap, the extent of the bodies, far above it.
    // The bound must clear the limit by `tolerance`, so that rounding (the support search
    // evaluates B in its own frame) cannot turn a skipped candidate into an accepted one.
    int storageA[2], storageB[2];
    const int* indicesA = nullptr;
    const int* indicesB = nullptr;
    const int countA = featureVertices(pair.a, representativeA, &indicesA, storageA);
    const int countB = featureVertices(pair.b, representativeB, &indicesB, storageB);
    SmallVector<Vec3, 16> pointsB;  // B's feature in A's frame
    for (int i = 0; i < countB; ++i) pointsB.push_back(pair.bInA.apply(pair.b.vertices()[indicesB[i]]));
    const std::vector<Vec3>& verticesA = pair.a.vertices();
    auto overlapLowerBound = [&](const Vec3& candidate) {
        double highestA = -INFINITY, lowestB = INFINITY;
        for (int i = 0; i < countA; ++i) highestA = std::max(highestA, candidate.dot(verticesA[indicesA[i]]));
        for (const Vec3& q : pointsB) lowestB = std::min(lowestB, candidate.dot(q));
        return highestA - lowestB;
    };
    bool found = false;
    double bestOverlap = INFINITY, bestCos = -2;
    Vec3 best = normal;
    auto consider = [&](const Vec3& candidate) {
        if (overlapLowerBound(candidate) >= limit + tolerance) return;
        const double overlap = overlapAlong(pair, known, candidate, normal, current);
        if (!(overlap < limit)) return;
        const double cosine = candidate.dot(normal);
        if (!found || overlap < bestOverlap - tolerance || (overlap <= bestOverlap + tolerance && cosine > bestCos))
            found = true, bestOverlap = overlap, bestCos = cosine, best = candidate;
    };
    // The faces around the feature's vertices, each once, in the order the vertices and their face
    // lists meet them; a face feature has them precomputed (Polytope::faceNeighbourhoods).
    auto facesAround = [&](const Polytope& polytope, const Feature& feature, const int* indices, int count,
                           auto&& visit) {
        if (feature.type == FeatureType::Face) {
            const int* offsets = polytope.faceNeighbourhoodOffsets().data();
            const int* faces = polytope.faceNeighbourhoods().data();
            for (int k = offsets[feature.index], end = offsets[feature.index + 1]; k < end; ++k) visit(faces[k]);
            return;
        }
        const int* offsets = polytope.vertexFaceOffsets().data();
        const int* faces = polytope.vertexFaces().data();
        for (int i = 0; i < count; ++i)
            for (int k = offsets[indices[i]], end = offsets[indices[i] + 1]; k < end; ++k) {
                bool seen = false;  // an edge's two faces are around both of its ends
                for (int j = 0; j < i && !seen; ++j)
                    for (int l = offsets[indices[j]], e = offsets[indices[j] + 1]; l < e; ++l) seen |= faces[l] == faces[k];
                if (!seen) visit(faces[k]);
            }
    };
    facesAround(pair.a, representativeA, indicesA, countA, [&](int face) { consider(pair.a.faces()[face].normal); });
    facesAround(pair.b, representativeB, indicesB, countB,
                [&](int face) { consider(-(pair.bInA.rotation * pair.b.faces()[face].normal)); });
    if (!found) return false;
    normal = best;
    normalOverlap = bestOverlap;
    return true;
}

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
                                const Pose& toCommon, const Vec3* common = nullptr) {
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

}  // namespace

namespace detail {

bool separatedByEarlyOut(const MinkowskiDifference& pair, const Vec3& centreOffset, double centreDistance, double size,
                         double margin, double tolerance, bool closedFormBoxes) {
    // Bounding spheres about the centroids: the cheap early out for separated pairs.
    if (centreDistance > size + margin) return true;
    // The line of centres is the likeliest separating axis of a pair whose spheres overlap: two
    // support searches settle most separated pairs of a broad phase before the ray cast.
    if (!(centreDistance > 0)) return false;
    // Each body's support value about its centroid is at least its inradius, so the overlap along
    // the line of centres is at least r_A + r_B − |d|: where that is not below −margin, the searches
    // cannot find the pair apart by more than the margin and the tolerance (the bound's rounding is
    // far below the tolerance), and a resting pair (two stacked cubes: 1 − 0.99) spares them.
    // Only where the searches keep no state (a box's closed form, brute force): a hill climb's
    // later searches start from their vertices.
    const Polytope& a = pair.a;
    const Polytope& b = pair.b;
    if (a.inradius() + b.inradius() - centreDistance >= -margin) {
        const bool searchesWithoutState =
            (a.isBox() || static_cast<int>(a.vertices().size()) <= pair.bruteForceLimit) &&
            (b.isBox() || static_cast<int>(b.vertices().size()) <= pair.bruteForceLimit);
        if (searchesWithoutState) return false;
    }
    const Vec3 direction = centreOffset / centreDistance;
    const double limit = -margin - tolerance;
    if (closedFormBoxes && a.isBox() && b.isBox()) {
        // Two boxes: their overlap along the unit d in closed form, Σ halfA·|d| + Σ halfB·|Rᵀd| − d·p
        // (p B's centre, R its rotation, in A's frame), without the two support searches and B's
        // vertex placed. It differs from overlapAlong's value by rounding only — a few ulps of the
        // boxes' extents and of |p| — so where it is clear of the limit by 1e-12 of (size + |d|),
        // far above that, both are on the same side; within that band overlapAlong decides, as
        // before. tests/small_intersection_test.cpp checks the decisions equal on 10^5 poses.
        const Vec3 directionB = pair.bInA.rotation.transpose() * direction;
        const double overlap = a.boxHalfExtents().dot(direction.cwiseAbs()) +
                               b.boxHalfExtents().dot(directionB.cwiseAbs()) - direction.dot(pair.bInA.position);
        const double band = 1e-12 * (size + centreDistance);
        if (overlap < limit - band) return true;
        if (overlap > limit + band) return false;
    }
    return pair.overlapAlong(direction) < limit;
}

bool edgeEdgeNormal(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const MinkowskiDifference& pair,
                    Vec3& normal, double& normalOverlap) {
    Vec3 perpendicular = (a1 - a0).cross(b1 - b0);
    const double scale = (a1 - a0).norm() * (b1 - b0).norm();
    if (!(perpendicular.norm() > 1e-6 * scale)) return false;  // parallel edges: no single perpendicular
    perpendicular.normalize();
    normal = perpendicular.dot(normal) < 0 ? -perpendicular : perpendicular;
    normalOverlap = pair.overlapAlong(normal);
    return true;
}

// The Gauss-map features widen the normal into a region; where a face was picked the exact
// contact normal is a face normal (vertex–face, edge–face, face–face all rest on a face), and for
// edge–edge it is the edges' common perpendicular. The candidates are the picked faces and the
// other faces of their caps (all within the angular tolerance); the contact normal is the one
// along which the pair overlaps least — the separating-axis choice, as ODE's dBoxBox makes it.
// It depends on the geometry only: at tiny tilts the growth-distance normal lies between two
// near-parallel faces within rounding, and choosing the face closer to it let the normal flip
// between them from one tilt to the next (and between collide(A, B) and collide(B, A)). The
// comparison is exact: two overlaps cross only where their faces are parallel, so a choice made
// by rounding there picks between normals that agree to rounding. Equal overlaps fall back to the
// face closer to the growth-distance normal (the face the cast hit).
void refineNormal(Vec3& normal, double& normalOverlap, const FeatureView& a, const FeatureView& b,
                  const MinkowskiDifference& pair, const KnownOverlaps* known) {
    Vec3 best = normal;
    double bestOverlap = INFINITY, bestCos = -2;
    auto consider = [&](const Vec3& candidate) {
        const double overlap = overlapAlong(pair, known, candidate, normal, normalOverlap), cosine = candidate.dot(normal);
        if (overlap < bestOverlap || (overlap == bestOverlap && cosine > bestCos))
            bestOverlap = overlap, bestCos = cosine, best = candidate;
    };
    if (a.type == FeatureType::Face) {
        consider(a.planeNormal);
        for (int i = 0; i < a.pieceCount; ++i) consider(a.pieces[i].planeNormal);
    }
    if (b.type == FeatureType::Face) {
        consider(-b.planeNormal);
        for (int i = 0; i < b.pieceCount; ++i) consider(-b.pieces[i].planeNormal);
    }
    if (bestCos > -2) {
        normal = best, normalOverlap = bestOverlap;
        return;
    }
    if (a.type != FeatureType::Edge || b.type != FeatureType::Edge) return;
    if (a.pieceCount == 0 && b.pieceCount == 0) {
        edgeEdgeNormal(a.points[0], a.points[1], b.points[0], b.points[1], pair, normal, normalOverlap);
        return;
    }
    // Edge chains: each pair of their edges has its common perpendicular; the contact normal is the
    // one along which the pair overlaps least (as among a cap's faces above), so it depends on the
    // chains only, not on which of their nearly collinear edges rounding selected. An edge without
    // a chain is its own one piece.
    auto edge = [](const FeatureView& feature, int i) {
        return feature.pieceCount == 0 ? feature.points : feature.pieces[i].points.data();
    };
    const int countA = std::max(a.pieceCount, 1), countB = std::max(b.pieceCount, 1);
    for (int i = 0; i < countA; ++i)
        for (int j = 0; j < countB; ++j) {
            const Vec3* edgeA = edge(a, i);
            const Vec3* edgeB = edge(b, j);
            Vec3 candidate = normal;
            double overlap = normalOverlap;
            if (!edgeEdgeNormal(edgeA[0], edgeA[1], edgeB[0], edgeB[1], pair, candidate, overlap))
                continue;  // parallel edges
            const double cosine = candidate.dot(normal);
            if (overlap < bestOverlap || (overlap == bestOverlap && cosine > bestCos))
                bestOverlap = overlap, bestCos = cosine, best = candidate;
        }
    if (bestCos > -2) normal = best, normalOverlap = bestOverlap;
}

namespace {

// The manifold written out in world coordinates: the normal, and points[pick(i)] for i < count.
// Finite input can still overflow (a plane offset of 1e308, found by the fuzzer): refuse it rather
// than hand out an infinite or NaN contact. x·0 is 0 for every finite x and NaN otherwise: one
// test for all the coordinates written. emitManifold (ranked) and emitInLiftOrder (in lift order)
// share it, so both write the same bits.
template <class Pick>
[[gnu::always_inline]] inline void writeWorldManifold(const LiftedPoints& points, int count, Pick pick,
                                                      const Vec3& normal, const Pose& commonToWorld,
                                                      Manifold& manifold) {
    manifold.normal = commonToWorld.rotation * normal;
    manifold.pointCount = count;
    double nonFinite = 0;
    for (int i = 0; i < count; ++i) {
        const LiftedPoint& point = points[pick(i)];
        manifold.points[i] = {commonToWorld.apply(point.position), point.depth};
        nonFinite += (manifold.points[i].position * 0.0).sum() + point.depth * 0.0;
    }
    if (!(nonFinite == 0))
        throw InvalidInput("the contact overflows double precision (coordinates or offsets near 1e308)");
}

}  // namespace

void emitManifold(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                  double tolerance, const Vec3* centroids, int centroidCount, Manifold& manifold) {
    int chosen[kMaxManifoldPoints];
    const int maxCount = std::max(1, std::min(settings.maxContacts, kMaxManifoldPoints));
    const int total = static_cast<int>(points.size());
    // The bodies' centroids on the contact plane, for the centroid rule: needed only where points
    // are dropped.
    Vec2 planarCentroids[2];
    RankingRule rule{maxCount, settings.reductionHysteresis, tolerance,
                     commonToWorld.rotation.transpose() * identityDirection()};
    if (total > maxCount && maxCount >= 3 && centroidCount > 0) {
        Vec3 u, v;
        planeBasis(normal, u, v);
        for (int c = 0; c < std::min(centroidCount, 2); ++c)
            planarCentroids[c] = Vec2(centroids[c].dot(u), centroids[c].dot(v));
        rule.centroids = planarCentroids;
        rule.centroidCount = std::min(centroidCount, 2);
    }
    const int count = rankContacts(points, rule, chosen);
    writeWorldManifold(points, count, [&](int i) { return chosen[i]; }, normal, commonToWorld, manifold);
}

bool emitInLiftOrder(const LiftedPoints& points, const Vec3& normal, const Pose& commonToWorld, const Settings& settings,
                     Manifold& manifold) {
    // emitManifold's ranking keeps every point where there are at most maxCount (rankContacts);
    // then it only orders them.
    const int maxCount = std::max(1, std::min(settings.maxContacts, kMaxManifoldPoints));
    const int total = static_cast<int>(points.size());
    if (total > maxCount) return false;
    for (int i = 0; i < total; ++i)
        for (int j = i + 1; j < total; ++j)
            if (points[i].depth == points[j].depth) return false;
    writeWorldManifold(points, total, [](int i) { return i; }, normal, commonToWorld, manifold);
    return true;
}

namespace {

// Any two polytopes' hooks for the one composition (pipeline.hpp): the general pipeline, the
// reference every specialised hook is tested equal to. The flags choose the paths that the faster
// ones replaced, kept so that tests can prove the two equal (collide_general.hpp).
struct GeneralPairHooks {
    static constexpr bool kDelegatesRareCases = false;  // it is where the others delegate to
    GeneralPairHooks(const Settings& settings, bool alwaysConfirmDepth, bool enumerateSmallHulls, bool boundFaceOverlaps,
                     bool carryHullGauge)
        : settings(settings),
          alwaysConfirmDepth(alwaysConfirmDepth),
          enumerateSmallHulls(enumerateSmallHulls),
          boundFaceOverlaps(boundFaceOverlaps),
          carryHullGauge(carryHullGauge) {}
    const Settings& settings;
    bool alwaysConfirmDepth;
    bool enumerateSmallHulls;
    bool boundFaceOverlaps;
    bool carryHullGauge;
    // What the hull enumeration found (empty unless it ran with carryHullGauge), and the overlaps
    // along the selected faces' normals that refineNormal reads from it (knownOverlaps()), where
    // the enumeration ran with the carry.
    HullGaugeCarry carry;
    KnownOverlaps known;
    bool carrying = false;
    // featureA's findings for featureB, which decides whether refineNormal reads the carry.
    double faceOverlapA = NAN;
    Vec3 directionA = Vec3::Zero();
    FeatureType manifoldFeatureA = FeatureType::Vertex;
    bool separatingAxis = settings.normalMethod == NormalMethod::SeparatingAxis;
    // With each feature its pieces: a face's cap, an edge's chain.
    SmallVector<int, 8> piecesA, piecesB;

    static bool acceptsPoses(const Pose& poseA, const Pose& poseB) {
        requireFinite(poseA, "A");
        requireFinite(poseB, "B");
        return true;
    }

    // Stage 1: contact normal from the growth distance (or, to measure the trade, the SAT's).
    Stage1 growthNormal(const PairFrame& frame, const Vec3&) {
        const MinkowskiDifference& pair = frame.pair;
        Stage1 stage1;
        if (separatingAxis) {
            const SeparatingAxis axis = minimumOverlapAxis(pair);
            stage1.normal = axis.normal, stage1.normalOverlap = axis.overlap;
            return stage1;  // no overhang check: no face overlaps less than the SAT's normal
        }
        const Polytope& a = frame.a;
        const Polytope& b = frame.b;
        const bool searchesWithoutState =
            (a.isBox() || static_cast<int>(a.vertices().size()) <= pair.bruteForceLimit) &&
            (b.isBox() || static_cast<int>(b.vertices().size()) <= pair.bruteForceLimit);
        // The hull's hook: two small polytopes enumerate K's facets (hull_gauge.hpp), the same σ and
        // facet the ray cast converges to; large ones (and two boxes, in closed form) cast. What the
        // enumeration evaluated on the way is carried to the later stages (refineNormal's overlaps,
        // the depth certificate) where no search keeps state: a skipped search of a hill climb
        // would move the later climbs' starting vertices, and with them the ray cast's answer.
        const bool enumerates = enumerateSmallHulls && hullGaugeApplies(a, b);
        carrying = enumerates && carryHullGauge && searchesWithoutState;
        const GrowthDistance growth = enumerates ? hullGrowth(pair, carrying ? &carry : nullptr)
                                                 : growthDistance(pair, settings, /*needWitnesses=*/false);
        stage1.normal = growth.valid ? growth.normal : minimumOverlapFaceNormal(pair);
        stage1.normalOverlap = pair.overlapAlong(stage1.normal);
        stage1.growthNormal = growth.valid;
        // A lower bound of every face's overlap, for the overhang check. Any pair has one: along a
        // unit c the overlap is h_{A−c_A}(c) + h_{B−c_B}(−c) − c·d (d = c_B − c_A), and each
        // support value about a centroid is at least the body's inradius, so every overlap is at
        // least r_A + r_B − |d|. For two bodies resting face to face about their centroids (a
        // stack of boxes, as hulls) that is the penetration itself, and the check — 11 % of an
        // 8-vertex hull pair's query — never runs. Only where the supports are searched without a
        // warm start (boxes, brute force): the check's searches move the hill climb's starting
        // vertices, and a climb from elsewhere may stop at another vertex of a face the direction
        // is normal to, which changes later values by a rounding.
        stage1.faceOverlapLowerBound =
            boundFaceOverlaps && searchesWithoutState
                ? std::max(growth.faceOverlapLowerBound, a.inradius() + b.inradius() - frame.centreDistance)
                : growth.faceOverlapLowerBound;
        // The enumeration's bound of every face's overlap (HullGaugeCarry::faceOverlapBound): on a
        // stack of slabs and prisms the inradius bound above is weak (a slab's inradius is half its
        // thickness), and the overhang check was a quarter of the query (callgrind, solver_seeds
        // hulls scene).
        if (carrying && growth.valid)
            stage1.faceOverlapLowerBound = std::max(stage1.faceOverlapLowerBound, carry.faceOverlapBound);
        return stage1;
    }

    // Stage 2: the Gauss-map search from the support vertex. `first`: the last support searches
    // were along n and −n (stage 1 ends in overlapAlong(n)), so their vertices (pair.lastSupportA,
    // lastSupportB) are what the searches here would return — the same directions, and a search
    // started at its answer stays there — and two searches are spared.
    void selectFeatures(const PairFrame& frame, const Vec3& n, bool first, Manifold& manifold) {
        const MinkowskiDifference& pair = frame.pair;
        // Here rather than with the hooks: a pair the early out or stage 1 finds apart never needs
        // it (callgrind, separated 8-vertex hull pair: its series was 42 of the call's 946).
        const AngularTolerance angularTolerance(settings.angularTolerance);
        const bool supportsKnown = first && !separatingAxis;
        const Vec3 directionB = frame.bInA.rotation.transpose() * -n;
        const int supportA = supportsKnown ? pair.lastSupportA : pair.supportA(n);
        const int supportB = supportsKnown ? pair.lastSupportB : pair.supportBInB(directionB);
        // The enumeration's face of each body, where it carried one, proved rather than searched
        // (faceIsSelected: the same feature; the search where the proof fails).
        manifold.featureA = carry.faceA >= 0 && faceIsSelected(frame.a, carry.faceA, n, supportA, angularTolerance)
                                ? Feature{FeatureType::Face, carry.faceA}
                                : selectFeature(frame.a, n, supportA, angularTolerance);
        manifold.featureB =
            carry.faceB >= 0 && faceIsSelected(frame.b, carry.faceB, directionB, supportB, angularTolerance)
                ? Feature{FeatureType::Face, carry.faceB}
                : selectFeature(frame.b, directionB, supportB, angularTolerance);
        featurePieces(frame.a, manifold.featureA, n, angularTolerance, piecesA);
        featurePieces(frame.b, manifold.featureB, directionB, angularTolerance, piecesB);
    }
    // Stage 1's check of the growth-distance normal against the faces around the two features.
    bool preferNearbyFace(const PairFrame& frame, Vec3& normal, double& normalOverlap, const Manifold& manifold) const {
        return preferNearbyFaceNormal(frame.pair, manifold.featureA, piecesA, manifold.featureB, piecesB,
                                      frame.tolerance, knownOverlaps(), normal, normalOverlap);
    }
    // The overlaps the enumeration's carry knows (filled as the features are placed), for the
    // overhang check and refineNormal; nullptr where it did not carry.
    const KnownOverlaps* knownOverlaps() const { return carrying ? &known : nullptr; }
    // The features in A's frame. A's vertices need no placing (the identity; it differs only in
    // turning −0 into +0), B's were placed by the enumeration where it carries.
    FeatureGeometry featureA(const PairFrame& frame, const Feature& feature) {
        FeatureGeometry geometry =
            featureGeometry(frame.a, feature, piecesA, Pose{}, carryHullGauge ? frame.a.vertices().data() : nullptr);
        faceOverlapA = carriedFaceOverlap(feature, piecesA, carry.knownA, carry.overlapA);
        manifoldFeatureA = feature.type;
        directionA = geometry.planeNormal;
        return geometry;
    }
    // refineNormal's candidates are the selected faces' normals (A's planeNormal, B's negated, which
    // is how the known overlaps are spelled) and their caps' pieces. The carried overlaps may differ
    // from the searches' in the last bits (B's support among vertices tied along the normal, found
    // in the other frame), so they are used only where that cannot change refineNormal's choice:
    // no caps, and with two faces the overlaps more than 1e-9 of the size apart (an aligned pair,
    // whose two faces overlap alike, searches as before).
    FeatureGeometry featureB(const PairFrame& frame, const Feature& feature) {
        FeatureGeometry geometry =
            featureGeometry(frame.b, feature, piecesB, frame.bInA, carry.exitKnown ? carry.verticesB.data() : nullptr);
        const double faceOverlapB = carriedFaceOverlap(feature, piecesB, carry.knownB, carry.overlapB);
        const bool faceA = manifoldFeatureA == FeatureType::Face, faceB = feature.type == FeatureType::Face;
        const bool knownA = !std::isnan(faceOverlapA), knownB = !std::isnan(faceOverlapB);
        const bool decisive = faceA && faceB ? knownA && knownB && std::abs(faceOverlapA - faceOverlapB) > 1e-9 * frame.size
                                             : (faceA && knownA) || (faceB && knownB);
        if (decisive) {
            if (knownA) known.add(directionA, faceOverlapA);
            if (knownB) known.add(-geometry.planeNormal, faceOverlapB);
        }
        return geometry;
    }
    // The enumeration's overlap along a selected face's normal: NaN where it has none, the feature
    // is no face or has a cap (more than one piece). A face index beyond the carry's 64 bits (a
    // polytope too large for the enumeration, whose `known` is empty) is never shifted by: a shift
    // of 64 or more is undefined (UBSan in the sanitize run found it on 68- and 4529-face hulls).
    static double carriedFaceOverlap(const Feature& feature, const SmallVector<int, 8>& pieces, std::uint64_t known,
                                     const std::array<double, HullGaugeCarry::kMaxFaces>& overlaps) {
        if (feature.type != FeatureType::Face || pieces.size() > 1 || feature.index >= HullGaugeCarry::kMaxFaces ||
            !((known >> feature.index) & 1))
            return NAN;
        return overlaps[feature.index];
    }
    bool refinesNormal() const { return !separatingAxis; }  // SAT's is exact already

    // The deepest contact must carry the whole penetration along n — the distance B must move
    // along n to clear A, the exit of the ray along n through A − B (ODE's contract: moving by
    // 0.96·depth still touches, 1.04·depth separates). The intersection misses it when the
    // projections do not meet (a vertex–vertex touch, or deep overlap, where the features that
    // touch when the bodies are shrunk to the growth distance drift apart at full size), or when
    // the deepest overlap lies beyond the selected features (a face–edge pair whose edge dips
    // below a neighbouring face). The supports' overlap along n bounds that distance from above, so
    // the composition asks only when the lifted points fall short of it, and the ray cast's point
    // is added only when it is deeper by more than 1 % (ODE's contract allows 4 %; the slack
    // absorbs the ray cast's accuracy on the nearly coplanar facets of A − B that near-parallel
    // faces make, where it is a few times the tilt times the size rather than the cast's
    // tolerance). The added point lies midway between the two touching witnesses, so its points on
    // A and B are position ± depth/2·n like every contact; it is never a silently missing contact.
    DepthCheck confirmDepth(const PairFrame& frame, LiftedPoints& kept, double deepest,
                            const LiftedPoint* deepestPoint, const Vec3& normal,
                            const FeatureGeometry& featureA, const FeatureGeometry& featureB) const {
        constexpr double kDepthSlack = 0.01;
        const double slack = (std::isfinite(deepest) ? kDepthSlack * std::abs(deepest) : 0.0) + frame.tolerance;
        // The ray cast converges to within its tolerance of the exit: the certificate keeps that much
        // on the safe side, so that it skips the cast only where the cast could not have added a point.
        const double certifiedSlack = slack - 2 * settings.rayCastTolerance * frame.size;
        // The exit facet of the enumeration first: a plane of A − B, so it bounds the penetration
        // along n like penetrationCertified's candidates (t* ≤ overlap(m)/(m·n) for m·n > 0), and for
        // a resting pair it is mostly the facet the line along n leaves by too (the centre line and
        // n nearly agree): the certificate without projecting the features or searching a support.
        if (!alwaysConfirmDepth && deepestPoint && carry.exitKnown) {
            const Vec3& m = carry.exitDirection;
            const double along = m.dot(normal);
            if (along > 1e-6 * m.norm() && carry.exitOverlap / along <= deepestPoint->depth + certifiedSlack)
                return DepthCheck::Confirmed;
        }
        if (!alwaysConfirmDepth && deepestPoint &&
            penetrationCertified(*deepestPoint, featureA, featureB, normal, frame.pair, certifiedSlack,
                                 frame.tolerance))
            return DepthCheck::Confirmed;
        const SeparationAlong separation = separationAlong(frame.pair, normal, settings);
        if (kept.empty() && separation.valid && separation.distance < -settings.margin - frame.tolerance)
            return DepthCheck::Separated;  // apart along n by more than the margin
        if (separation.valid && separation.distance > deepest + slack) {
            const Vec3 middle = 0.5 * (separation.witnessA + separation.witnessB);
            Vec3 u, v;
            planeBasis(normal, u, v);
            kept.push_back({middle, separation.distance, Vec2(middle.dot(u), middle.dot(v))});
        }
        return DepthCheck::Confirmed;
    }
};

}  // namespace

Manifold collideGeneral(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings, bool alwaysConfirmDepth, bool enumerateSmallHulls,
                        bool boundFaceOverlaps, bool carryHullGauge) {
    Manifold manifold;
    GeneralPairHooks hooks(settings, alwaysConfirmDepth, enumerateSmallHulls, boundFaceOverlaps, carryHullGauge);
    composeStages(hooks, a, poseA, b, poseB, settings, manifold);  // never delegates
    return manifold;
}

namespace {
// The general hooks (default paths) for a caller that needs the points only in `order`.
template <ImportanceOrder order>
struct GeneralPairHooksIn : GeneralPairHooks {
    static constexpr ImportanceOrder kOrder = order;
    explicit GeneralPairHooksIn(const Settings& settings) : GeneralPairHooks(settings, false, true, true, true) {}
};
}  // namespace

template <ImportanceOrder order>
void collideGeneralInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                        const Settings& settings, Manifold& out) {
    GeneralPairHooksIn<order> hooks(settings);
    composeStages(hooks, a, poseA, b, poseB, settings, out);  // never delegates
}
template void collideGeneralInto<ImportanceOrder::AmongEqualDepths>(const Polytope&, const Pose&, const Polytope&,
                                                                    const Pose&, const Settings&, Manifold&);

}  // namespace detail

// The public queries: the specialised paths where they apply, the general pipeline otherwise.
Manifold collide(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                 const Settings& settings) {
    if (detail::boxBoxApplies(a, b, settings)) return detail::collideBoxBox(a, poseA, b, poseB, settings);
    return detail::collideGeneral(a, poseA, b, poseB, settings);
}

Manifold collide(const Polytope& a, const Pose& poseA, const HalfSpace& b, const Settings& settings) {
    // Boxes and small hulls: a vertex loop, tested equal to the general path (half_space.hpp).
    if (detail::halfSpaceFastPathApplies(a, settings)) return detail::collideHalfSpace(a, poseA, b, settings);
    return detail::collideGeneral(a, poseA, b, settings);
}

}  // namespace gdc
