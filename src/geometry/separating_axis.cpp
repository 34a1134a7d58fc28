#include "geometry/separating_axis.hpp"

#include <cmath>
#include <vector>

namespace gdc::detail {
namespace {

// Whether the Gauss-map arc a→b (an edge of A, between its faces' normals) crosses the arc c→d
// (an edge of B, its faces' normals negated: the Gauss map of −B). Both arcs are shorter than a
// half circle; they cross when each one's great circle separates the other's ends and the two
// crossings lie on the same hemisphere (Gregorius 2013).
bool arcsCross(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3 planeAB = b.cross(a), planeCD = d.cross(c);
    const double cba = c.dot(planeAB), dba = d.dot(planeAB);
    const double adc = a.dot(planeCD), bdc = b.dot(planeCD);
    return cba * dba < 0 && adc * bdc < 0 && cba * bdc > 0;
}

}  // namespace

SeparatingAxis minimumOverlapAxis(const MinkowskiDifference& pair) {
    SeparatingAxis best;
    best.overlap = INFINITY;
    auto consider = [&](const Vec3& normal, double overlap) {
        if (overlap < best.overlap) best.normal = normal, best.overlap = overlap;
    };
    for (const Polytope::Face& face : pair.a.faces()) consider(face.normal, pair.overlapAlong(face.normal));
    // B's face normals and edges in A's frame, once (not once per edge pair).
    const Mat3& rotation = pair.bInA.rotation;
    std::vector<Vec3> normalsB;
    normalsB.reserve(pair.b.faces().size());
    for (const Polytope::Face& face : pair.b.faces()) {
        normalsB.push_back(rotation * face.normal);
        consider(-normalsB.back(), pair.overlapAlong(-normalsB.back()));
    }
    std::vector<Vec3> verticesB;
    verticesB.reserve(pair.b.vertices().size());
    for (const Vec3& vertex : pair.b.vertices()) verticesB.push_back(pair.bInA.apply(vertex));

    for (const Polytope::Edge& edgeA : pair.a.edges()) {
        const Vec3& normalA1 = pair.a.faces()[edgeA.leftFace].normal;
        const Vec3& normalA2 = pair.a.faces()[edgeA.rightFace].normal;
        const Vec3& tailA = pair.a.vertices()[edgeA.tail];
        const Vec3 alongA = pair.a.vertices()[edgeA.head] - tailA;
        for (const Polytope::Edge& edgeB : pair.b.edges()) {
            if (!arcsCross(normalA1, normalA2, -normalsB[edgeB.leftFace], -normalsB[edgeB.rightFace])) continue;
            const Vec3& tailB = verticesB[edgeB.tail];
            Vec3 axis = alongA.cross(verticesB[edgeB.head] - tailB);
            const double length = axis.norm();
            // Parallel edges span no Minkowski face of their own; their plane is some face's.
            if (!(length > 1e-9 * alongA.norm() * (verticesB[edgeB.head] - tailB).norm())) continue;
            axis /= length;
            // The crossing direction is an outward direction of A at its edge: orient it so.
            if (axis.dot(tailA - pair.centreA) < 0) axis = -axis;
            // Along it the two edges are the supports (that is what the crossing arcs say).
            consider(axis, axis.dot(tailA) - axis.dot(tailB));
        }
    }
    return best;
}

}  // namespace gdc::detail
