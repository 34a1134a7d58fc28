// The growth distance of two small polytopes by enumerating the facet normals of their Minkowski
// difference (hull_gauge.hpp). K = (A − c_A) − (B − c_B) contains the origin; the ray from it along
// d = c_B − c_A leaves K through the facet m of largest (m·d)/h_K(m), and that ratio is the growth
// σ (the gauge of K at d). K's facets are face ⊕ vertex (A's face normals, B's negated) and edge ⊕
// edge, the latter exactly the edge pairs whose arcs cross on the Gauss maps of A and −B (Gottschalk;
// Gregorius, "The Separating Axis Test between Convex Polyhedra", GDC 2013). Taking the maximum over
// a superset of the facet normals changes nothing ((n·d)/h_K(n) ≤ σ for every n). The edge pairs'
// h_K below is exact only for crossing arcs; rounding can let through only a pair whose arcs nearly
// meet at an end, where the two edges are supports to within that rounding. Parallel edges (their
// facet is a face's) are the only crossing pairs skipped.
//
// The support values need no search for an edge pair: where m lies on both arcs, A's support along
// m is its edge and −B's is B's edge, so h_K(m) = m·(a − c_A) + m·(c_B − b) for a point a of the one
// and b of the other. The sign of m is that of the A term (h_{A − c_A}(m) > 0: c_A is interior).
// A facet with m·d ≤ 0 cannot be the exit; m on the arc between face normals n₁, n₂ is a positive
// combination of them, so an edge whose two faces both face away from d is skipped whole — about half
// the edges of each body, three quarters of the pairs.
#include "geometry/hull_gauge.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace gdc::detail {

namespace {

// Where `exit` (a point on the plane of a facet of K, A's frame) lies against the facet of K made by
// `face` of A (with B's support vertex along −its normal) or of B (A's along its normal, negated).
// The facet is the face translated, so the point is mapped back onto the face's plane and tested
// against its edges (counter-clockwise seen from outside: inside is to the left of each), each by
// more than 1e-9 of the pair's size: `inside` when within all, else `outside` has a bit for each
// edge k (face vertex k to k + 1) it is not within. `support` is the other body's vertex (its first
// of least value along the face's normal, which the face's evaluation found).
struct FaceCheck {
    bool inside = false;
    int support = 0;
    std::uint64_t outside = 0;
};

FaceCheck checkFaceExit(const MinkowskiDifference& pair, int face, bool ofA, const Vec3& exit, const Vec3* verticesB,
                        int support, double size) {
    FaceCheck check;
    check.support = support;
    const Polytope& polytope = ofA ? pair.a : pair.b;
    const Polytope::Face& f = polytope.faces()[face];
    const std::vector<Vec3>& vertices = polytope.vertices();
    const int* indices = polytope.faceVertices().data() + f.first;
    Vec3 onFace;  // the point of the face (its own polytope's frame) that the exit point is the image of
    if (ofA) {
        // K's facet (face − c_A) + (c_B − v_B), v_B B's support along −n: p + c_A − c_B + v_B on A's face.
        onFace = exit + pair.centreA - pair.centreB + verticesB[check.support];
    } else {
        // K's facet (v_A − c_A) + (c_B − face), v_A A's support along −n (n = R·n_B): v_A − c_A + c_B − p
        // on B's face.
        const std::vector<Vec3>& verticesA = pair.a.vertices();
        onFace = pair.bInA.applyInverse(verticesA[check.support] - pair.centreA + pair.centreB - exit);
    }
    const double margin = 1e-9 * size;
    for (int k = 0; k < f.count; ++k) {
        const Vec3& from = vertices[indices[k]];
        const Vec3& to = vertices[indices[k + 1 == f.count ? 0 : k + 1]];
        const Vec3 edge = to - from;
        // (edge × (q − from))·n = distance to the edge's line × |edge|, positive inside.
        if (!(edge.cross(onFace - from).dot(f.normal) > margin * edge.norm())) check.outside |= std::uint64_t(1) << k;
    }
    check.inside = check.outside == 0;
    return check;
}

// min over the points of n·p and the first point of that value, as scalar code with Eigen's order
// of operations ((n₀p₀ + n₁p₁) + n₂p₂, as n.dot(p)), so the same bits: the face loops below are the
// enumeration's largest part, and Eigen spends packet shuffles on 3-vectors.
struct Lowest {
    double value;
    int index;
};
Lowest lowestAlong(const Vec3& n, const Vec3* points, int count) {
    const double x = n.x(), y = n.y(), z = n.z();
    Lowest lowest{INFINITY, 0};
    for (int i = 0; i < count; ++i) {
        const double value = (x * points[i].x() + y * points[i].y()) + z * points[i].z();
        if (value < lowest.value) lowest = {value, i};  // the value of std::min(lowest, value)
    }
    return lowest;
}

// The index of the edge between vertices `from` and `to` of `polytope` (−1 if none).
int edgeBetween(const Polytope& polytope, int from, int to) {
    const int* edges = polytope.vertexEdges().data();
    for (int k = polytope.vertexFaceOffsets()[from], end = polytope.vertexFaceOffsets()[from + 1]; k < end; ++k) {
        const Polytope::Edge& edge = polytope.edges()[edges[k]];
        if ((edge.tail == from && edge.head == to) || (edge.tail == to && edge.head == from)) return edges[k];
    }
    return -1;
}

}  // namespace

GrowthDistance hullGrowth(const MinkowskiDifference& pair, HullGaugeCarry* carry) {
    // A closed polytope has V − E + F = 2 and every face at least three edges, so V, F ≤ 2E/3 + 2.
    constexpr int kMax = kHullGaugeMaxEdges;
    GrowthDistance result;
    const Polytope& a = pair.a;
    const Polytope& b = pair.b;
    const Vec3 d = pair.centreB - pair.centreA;
    const double size = a.radius() + b.radius();
    if (!(d.squaredNorm() > 1e-24 * size * size)) return result;  // coincident contraction points
    const Mat3& rotation = pair.bInA.rotation;
    const std::vector<Vec3>& verticesA = a.vertices();
    const int countA = static_cast<int>(verticesA.size()), countB = static_cast<int>(b.vertices().size());
    // B's vertices in A's frame (the carry's, for the features' geometry later).
    std::array<Vec3, kMax> ownVerticesB;
    Vec3* verticesB = carry ? carry->verticesB.data() : ownVerticesB.data();
    for (int i = 0; i < countB; ++i) verticesB[i] = pair.vertexB(i);

    // The exit so far as the ratio exitAlong/exitSupport = (m·d)/h_K(m) (0/1: none yet), compared by
    // cross-multiplication, with boxGrowth's tie rule: a facet within 1e-12 of the best joins it and
    // the normal is the normalised sum of the tied ones (the middle of their cone).
    // `exitDirection` is the facet's normal as `along` and `supportValue` measure it (for the carry).
    double exitSupport = 1, exitAlong = 0;
    Vec3 tiedNormals = Vec3::Zero(), exitDirection = Vec3::Zero();
    auto consider = [&](double along, double supportValue, const Vec3& direction, auto&& normal) {
        const double distance = supportValue * exitAlong, exit = exitSupport * along;
        if (distance < exit * (1 - 1e-12)) {
            if (distance > exit * (1 - 2e-12)) tiedNormals += normal();
            else tiedNormals = normal();
            exitSupport = supportValue, exitAlong = along, exitDirection = direction;
        } else if (distance <= exit * (1 + 1e-12)) {
            tiedNormals += normal();
        }
    };

    // Gauss normals of −B in A's frame (filled by the first loop over the faces below, before any use).
    const std::vector<Polytope::Face>& facesA = a.faces();
    const std::vector<Polytope::Face>& facesB = b.faces();
    std::array<Vec3, kMax> gaussB;  // −R·n_B
    // One edge pair (indices into A's and B's edges): considered if its arcs cross on the Gauss maps
    // (Gregorius's test, below); true when it became the best.
    auto considerEdgePair = [&](int indexA, int indexB) {
        const Polytope::Edge& edgeA = a.edges()[indexA];
        const Polytope::Edge& edgeB = b.edges()[indexB];
        const Vec3& firstA = facesA[edgeA.leftFace].normal;
        const Vec3& secondA = facesA[edgeA.rightFace].normal;
        const Vec3& firstB = gaussB[edgeB.leftFace];
        const Vec3& secondB = gaussB[edgeB.rightFace];
        const Vec3 planeA = secondA.cross(firstA), planeB = secondB.cross(firstB);
        const double cba = firstB.dot(planeA), dba = secondB.dot(planeA);
        const double adc = firstA.dot(planeB), bdc = secondA.dot(planeB);
        if (!(cba * dba < 0) || !(adc * bdc < 0) || !(cba * bdc > 0)) return false;
        const Vec3 directionA = verticesA[edgeA.head] - verticesA[edgeA.tail];
        const Vec3 directionB = verticesB[edgeB.head] - verticesB[edgeB.tail];
        Vec3 m = directionA.cross(directionB);
        const double lengthSquared = m.squaredNorm();
        if (!(lengthSquared > 1e-18 * directionA.squaredNorm() * directionB.squaredNorm())) return false;
        double supportA = m.dot(verticesA[edgeA.tail] - pair.centreA);
        if (supportA < 0) m = -m, supportA = -supportA;
        const double along = m.dot(d);
        if (!(along > 0)) return false;
        const double supportB = m.dot(pair.centreB - verticesB[edgeB.tail]);
        const double before = exitAlong;
        consider(along, supportA + supportB, m, [&] { return Vec3(m / std::sqrt(lengthSquared)); });
        return exitAlong != before;
    };
    // Whether `exit` lies inside the parallelogram facet (edge A − c_A) + (c_B − edge B) of K by more
    // than 1e-9 of the size from its sides: exit − corner = s·e_A − t·e_B with s, t ∈ (0, 1).
    auto edgePairHoldsExit = [&](int indexA, int indexB, const Vec3& exit) {
        const Polytope::Edge& edgeA = a.edges()[indexA];
        const Polytope::Edge& edgeB = b.edges()[indexB];
        const Vec3 directionA = verticesA[edgeA.head] - verticesA[edgeA.tail];
        const Vec3 directionB = verticesB[edgeB.head] - verticesB[edgeB.tail];
        const Vec3 m = directionA.cross(directionB);
        const double lengthSquared = m.squaredNorm();
        const Vec3 r = exit - (verticesA[edgeA.tail] - pair.centreA + pair.centreB - verticesB[edgeB.tail]);
        const double s = r.cross(directionB).dot(m) / lengthSquared, t = -directionA.cross(r).dot(m) / lengthSquared;
        const double marginA = 1e-9 * size / directionA.norm(), marginB = 1e-9 * size / directionB.norm();
        return s > marginA && s < 1 - marginA && t > marginB && t < 1 - marginB;
    };

    // Each body's face of largest ratio (m·d)/h_K(m) among its faces evaluated, as along/support
    // (cross-multiplied; 0/1: none yet): the carry's proposal for stage 2's features (faceA, faceB).
    double proposedAlongA = 0, proposedSupportA = 1, proposedAlongB = 0, proposedSupportB = 1;
    int bestFace = -1;  // the face whose facet of K is the best so far, whose it is, the other's support
    bool bestFaceOfA = true;
    int bestSupport = 0;
    auto finish = [&] {
        const double growth = exitAlong / exitSupport;
        result.valid = std::isfinite(growth) && growth > 0 && tiedNormals.norm() > 1e-6;
        if (!result.valid) return result;
        result.normal = tiedNormals.normalized();
        result.growth = growth;
        if (carry) {
            // The exit facet's plane: K's support along it less its reach along d, the pair's overlap.
            carry->exitKnown = true;
            carry->exitDirection = exitDirection;
            carry->exitOverlap = exitSupport - exitAlong;
        }
        return result;
    };
    // Every face's reach along d first: A's normals n_A, B's turned into A's frame and negated.
    const int faceCountA = static_cast<int>(facesA.size());
    const int faceCountB = static_cast<int>(facesB.size());
    std::array<double, kMax> alongA, alongB;  // n·d of each face normal of A and of −B
    for (int f = 0; f < faceCountA; ++f) alongA[f] = facesA[f].normal.dot(d);
    for (int f = 0; f < faceCountB; ++f) {
        const Vec3 n = rotation * facesB[f].normal;
        gaussB[f] = -n;
        alongB[f] = -n.dot(d);
    }
    // A face's h_K is at least the two inradii about the centroids (each body's support value about
    // its centroid is), so its ratio is at most along/(r_A + r_B). The face of largest reach is
    // evaluated first; every face whose bound stays clearly (1e-9) below its ratio — below the
    // final σ's, then, and outside the tie margin — cannot be the exit nor join a tie, and is skipped
    // below without its support loop (the sides of a resting pair). The others run in order.
    int firstFace = -1;
    bool firstOfA = true;
    double firstAlong = 0, threshold = 0;
    Lowest firstLowest{0, 0};
    for (int f = 0; f < faceCountA; ++f)
        if (alongA[f] > firstAlong) firstAlong = alongA[f], firstFace = f;
    for (int f = 0; f < faceCountB; ++f)
        if (alongB[f] > firstAlong) firstAlong = alongB[f], firstFace = f, firstOfA = false;
    if (firstFace >= 0) {
        double support;
        if (firstOfA) {
            firstLowest = lowestAlong(facesA[firstFace].normal, verticesB, countB);
            support = facesA[firstFace].offset - firstLowest.value + firstAlong;
        } else {
            const Vec3 n = -gaussB[firstFace];
            firstLowest = lowestAlong(n, verticesA.data(), countA);
            support = facesB[firstFace].offset + n.dot(pair.bInA.position) - firstLowest.value + firstAlong;
        }
        const double radii = a.inradius() + b.inradius() - 1e-12 * size;
        if (support > 0 && radii > 0) threshold = firstAlong / support * radii * (1 - 1e-9);
    }
    // The least overlap among the faces evaluated, for the carry's bound of every face's overlap.
    double leastOverlap = INFINITY;
    // A's faces: h_K(n) = (offset − n·c_A) + (n·c_B − min n·B) = offset − min n·B + n·d.
    for (int f = 0; f < faceCountA; ++f) {
        const Vec3& n = facesA[f].normal;
        const double along = alongA[f];
        if (!(along > 0) || along < threshold) continue;
        const Lowest lowestB = firstOfA && f == firstFace ? firstLowest : lowestAlong(n, verticesB, countB);
        const double overlap = facesA[f].offset - lowestB.value;  // max n·A − min n·B
        if (carry) {
            carry->overlapA[f] = overlap, carry->knownA |= std::uint64_t(1) << f;
            leastOverlap = std::min(leastOverlap, overlap);
            if (along * proposedSupportA > proposedAlongA * (overlap + along))
                carry->faceA = f, proposedAlongA = along, proposedSupportA = overlap + along;
        }
        const double before = exitAlong;
        consider(along, overlap + along, n, [&] { return n; });
        if (exitAlong != before) bestFace = f, bestFaceOfA = true, bestSupport = lowestB.index;
    }
    // B's faces, turned into A's frame and negated (the Gauss map of −B): with n = R·n_B,
    // h_K(−n) = (max −n·A + n·c_A) + (offset_B + n·p − n·c_B) = offset_B + n·p − min n·A − n·d.
    for (int f = 0; f < faceCountB; ++f) {
        const Vec3 n = -gaussB[f];
        const double along = alongB[f];
        if (!(along > 0) || along < threshold) continue;
        const Lowest lowestA = !firstOfA && f == firstFace ? firstLowest : lowestAlong(n, verticesA.data(), countA);
        const double overlap = facesB[f].offset + n.dot(pair.bInA.position) - lowestA.value;  // max −n·A − min −n·B
        if (carry) {
            carry->overlapB[f] = overlap, carry->knownB |= std::uint64_t(1) << f;
            leastOverlap = std::min(leastOverlap, overlap);
            if (along * proposedSupportB > proposedAlongB * (overlap + along))
                carry->faceB = f, proposedAlongB = along, proposedSupportB = overlap + along;
        }
        const double before = exitAlong;
        consider(along, overlap + along, gaussB[f], [&] { return gaussB[f]; });
        if (exitAlong != before) bestFace = f, bestFaceOfA = false, bestSupport = lowestA.index;
    }

    // Every face's overlap is at least the bound: an evaluated face's is known (to rounding, the
    // 1e-12 of the size taken off), and a face not evaluated reaches along d less than the threshold
    // (or not at all), while its h_K is at least the inradii, so its overlap h_K − along exceeds
    // r_A + r_B − threshold. The overhang check (pipeline.hpp) needs no search where it clears it.
    if (carry) carry->faceOverlapBound = std::min(leastOverlap, a.inradius() + b.inradius() - threshold) - 1e-12 * size;

    // Where the ray's exit point p = d/σ lies inside the best face's facet of K (face ⊕ the other
    // body's support vertex) by more than rounding, that facet is the exit and σ is final: p is then
    // on K's boundary, so σ is its gauge. A face resting on a face mostly exits so; the edge pairs are
    // then skipped. Otherwise one step of a walk over K's boundary: p left the facet across edges of
    // the face, and the facets beyond them are edge–edge facets of those face edges with the edges
    // around the other body's support vertex. If the best of those holds p (a parallelogram), σ is
    // final too; else every edge pair is enumerated below.
    if (bestFace < 0) return finish();
    const FaceCheck check =
        checkFaceExit(pair, bestFace, bestFaceOfA, d * (exitSupport / exitAlong), verticesB, bestSupport, size);
    if (check.inside) return finish();
    const double faceSupport = exitSupport, faceAlong = exitAlong;
    const Vec3 faceNormals = tiedNormals, faceDirection = exitDirection;
    {
        const Polytope& faceOwner = bestFaceOfA ? a : b;
        const Polytope& other = bestFaceOfA ? b : a;
        const Polytope::Face& face = faceOwner.faces()[bestFace];
        const int* indices = faceOwner.faceVertices().data() + face.first;
        const int* otherEdges = other.vertexEdges().data();
        const int otherBegin = other.vertexFaceOffsets()[check.support], otherEnd = other.vertexFaceOffsets()[check.support + 1];
        int bestEdgeA = -1, bestEdgeB = -1;
        for (int k = 0; k < face.count; ++k) {
            if (!((check.outside >> k) & 1)) continue;
            const int faceEdge = edgeBetween(faceOwner, indices[k], indices[k + 1 == face.count ? 0 : k + 1]);
            if (faceEdge < 0) continue;
            for (int o = otherBegin; o < otherEnd; ++o) {
                const int edgeA = bestFaceOfA ? faceEdge : otherEdges[o], edgeB = bestFaceOfA ? otherEdges[o] : faceEdge;
                if (considerEdgePair(edgeA, edgeB)) bestEdgeA = edgeA, bestEdgeB = edgeB;
            }
        }
        if (bestEdgeA >= 0 && exitSupport != faceSupport &&
            edgePairHoldsExit(bestEdgeA, bestEdgeB, d * (exitSupport / exitAlong)))
            return finish();
    }
    // Back to the faces' answer: every edge pair follows, the ones just tried among them.
    exitSupport = faceSupport, exitAlong = faceAlong, tiedNormals = faceNormals, exitDirection = faceDirection;
    // Edge pairs. The edges that can carry an exit facet (a face normal with n·d > 0), each with its
    // direction, a point, its arc's end normals and their cross product.
    struct ArcEdge {
        Vec3 direction, point, first, second, plane;  // plane = second × first
        int index;                                    // the edge's
    };
    std::array<ArcEdge, kMax> arcsA, arcsB;
    std::array<std::uint64_t, kMax> leftBit, rightBit;  // a B edge's faces as bits
    int arcCountA = 0, arcCountB = 0;
    for (int e = 0, count = static_cast<int>(a.edges().size()); e < count; ++e) {
        const Polytope::Edge& edge = a.edges()[e];
        if (!(alongA[edge.leftFace] > 0) && !(alongA[edge.rightFace] > 0)) continue;
        ArcEdge& arc = arcsA[arcCountA++];
        arc.index = e;
        arc.point = verticesA[edge.tail];
        arc.direction = verticesA[edge.head] - arc.point;
        arc.first = facesA[edge.leftFace].normal, arc.second = facesA[edge.rightFace].normal;
        arc.plane = arc.second.cross(arc.first);
    }
    for (int e = 0, count = static_cast<int>(b.edges().size()); e < count; ++e) {
        const Polytope::Edge& edge = b.edges()[e];
        if (!(alongB[edge.leftFace] > 0) && !(alongB[edge.rightFace] > 0)) continue;
        leftBit[arcCountB] = std::uint64_t(1) << edge.leftFace, rightBit[arcCountB] = std::uint64_t(1) << edge.rightFace;
        ArcEdge& arc = arcsB[arcCountB++];
        arc.index = e;
        arc.point = verticesB[edge.tail];
        arc.direction = verticesB[edge.head] - arc.point;
        arc.first = gaussB[edge.leftFace], arc.second = gaussB[edge.rightFace];
        arc.plane = arc.second.cross(arc.first);
    }
    // The first test of each pair — B's arc ends on either side of A's great circle — rejects most
    // pairs. It is made once per A edge and B face instead of twice per pair: the signs of every
    // Gauss normal of −B against A's great circle as two bit sets (a polytope served here has at most
    // 2E/3 + 2 ≤ 44 faces), and a B edge's arc crosses the circle where its two faces' bits differ.
    static_assert(2 * kMax / 3 + 2 <= 64, "the faces of B must fit a 64-bit set");
    const Vec3 pointOffsetA = -pair.centreA, pointOffsetB = pair.centreB;
    for (int i = 0; i < arcCountA; ++i) {
        const ArcEdge& edgeA = arcsA[i];
        std::uint64_t above = 0, below = 0;  // −B's Gauss normals on either side of A's great circle
        for (int f = 0; f < faceCountB; ++f) {
            const double side = gaussB[f].dot(edgeA.plane);
            above |= std::uint64_t(side > 0) << f;
            below |= std::uint64_t(side < 0) << f;
        }
        for (int j = 0; j < arcCountB; ++j) {
            // The arcs cross: B's ends on either side of A's great circle, A's on either side of B's,
            // and on the same hemisphere (Gregorius's test; strict, so that a pair whose arcs only
            // touch at an end — a facet that is a face's — is left to the face).
            const bool firstAbove = (above & leftBit[j]) != 0;
            if (!(firstAbove ? (below & rightBit[j]) != 0 : (below & leftBit[j]) != 0 && (above & rightBit[j]) != 0))
                continue;
            const ArcEdge& edgeB = arcsB[j];
            const double cba = firstAbove ? 1.0 : -1.0;  // only its sign is used below
            const double adc = edgeA.first.dot(edgeB.plane), bdc = edgeA.second.dot(edgeB.plane);
            if (!(adc * bdc < 0) || !(cba * bdc > 0)) continue;
            Vec3 m = edgeA.direction.cross(edgeB.direction);
            const double lengthSquared = m.squaredNorm();
            if (!(lengthSquared > 1e-18 * edgeA.direction.squaredNorm() * edgeB.direction.squaredNorm()))
                continue;  // parallel edges: the facet is a face's
            double supportA = m.dot(edgeA.point + pointOffsetA);
            if (supportA < 0) m = -m, supportA = -supportA;
            const double along = m.dot(d);
            if (!(along > 0)) continue;
            const double supportB = m.dot(pointOffsetB - edgeB.point);
            consider(along, supportA + supportB, m, [&] { return Vec3(m / std::sqrt(lengthSquared)); });
        }
    }
    return finish();
}

}  // namespace gdc::detail
