// Stage 1 around the growth-distance normal (normal_choice.hpp): the fallback normal, the overhang
// check, the early outs and the refinement among the features' faces. Everything in A's frame.
#include "contact/normal_choice.hpp"

#include "contact/collide_general.hpp"
#include "contact/gauss_map.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {

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

bool separatedByEarlyOut(const MinkowskiDifference& pair, const Vec3& centreOffset, double centreDistance, double size,
                         double margin, double tolerance) {
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
    if (a.isBox() && b.isBox()) {
        // Two boxes: their overlap along the unit d in closed form, Σ halfA·|d| + Σ halfB·|Rᵀd| − d·p
        // (p B's centre, R its rotation, in A's frame), without the two support searches and B's
        // vertex placed. It differs from overlapAlong's value by rounding only — a few ulps of the
        // boxes' extents and of |p| — so where it is clear of the limit by 1e-12 of (size + |d|),
        // far above that, both are on the same side; within that band overlapAlong decides, as
        // before. tests/small_intersection_test.cpp checks the decisions against the searches.
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

}  // namespace gdc::detail
