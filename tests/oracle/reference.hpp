// The exact reference of the random-hull oracle: whether two posed hulls touch, by how much they
// overlap (the minimum translational distance), the penetration along any direction, and the
// penetration along a line through a given point — all from the separating-axis theorem over the
// complete set of facet normals of the Minkowski difference A − B (A's face normals, B's face
// normals negated, and the cross product of every pair of edges whose Gauss-map arcs cross),
// evaluated in long double. Written independently of the library's algorithms: no growth distance,
// no Gauss-map feature selection, no support climbing — brute force over vertices and planes.
#pragma once

#include <gdcontact/gdcontact.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gdc::oracle {

using Real = long double;
using Vec3L = Eigen::Matrix<Real, 3, 1>;

inline Vec3L toLong(const Vec3& v) { return v.cast<Real>(); }

/// A hull posed in the world, in long double: vertices, face planes (outward unit normal, offset =
/// the largest normal·vertex of the face, so the hull is the intersection of the half-spaces), and
/// each edge's two adjacent face normals (its arc on the Gauss map).
struct PosedHull {
    std::vector<Vec3L> vertices;
    std::vector<Vec3L> normals;
    std::vector<Real> offsets;
    struct Edge {
        Vec3L direction;  // head − tail
        Vec3L left, right;  // adjacent face normals
    };
    std::vector<Edge> edges;
    Real radius = 0;
};

/// The hull as the collider sees it: the pose is applied in long double to the double data.
inline PosedHull posed(const Polytope& polytope, const Pose& pose) {
    PosedHull out;
    const Eigen::Matrix<Real, 3, 3> rotation = pose.rotation.cast<Real>();
    const Vec3L position = toLong(pose.position);
    for (const Vec3& v : polytope.vertices()) out.vertices.push_back(rotation * toLong(v) + position);
    for (const Polytope::Face& face : polytope.faces()) {
        // The stored normal is the collider's (Newell's, rounded); the offset is recomputed over the
        // face's posed vertices so the plane passes through the hull exactly as posed.
        Vec3L normal = rotation * toLong(face.normal);
        normal /= normal.norm();
        Real offset = -INFINITY;
        for (int i = 0; i < face.count; ++i)
            offset = std::max(offset, normal.dot(out.vertices[polytope.faceVertices()[face.first + i]]));
        out.normals.push_back(normal);
        out.offsets.push_back(offset);
    }
    for (const Polytope::Edge& edge : polytope.edges())
        out.edges.push_back({out.vertices[edge.head] - out.vertices[edge.tail], out.normals[edge.leftFace],
                             out.normals[edge.rightFace]});
    Vec3L centre = Vec3L::Zero();
    for (const Vec3L& v : out.vertices) centre += v;
    centre /= static_cast<Real>(out.vertices.size());
    for (const Vec3L& v : out.vertices) out.radius = std::max(out.radius, (v - centre).norm());
    return out;
}

inline Real support(const PosedHull& hull, const Vec3L& direction) {
    Real best = -INFINITY;
    for (const Vec3L& v : hull.vertices) best = std::max(best, direction.dot(v));
    return best;
}

/// How far A must move along −axis (axis unit) for the projections of A and B onto it to stop
/// overlapping: max over A of axis·x − min over B of axis·x (negative: a gap along the axis).
inline Real overlapAlong(const PosedHull& a, const PosedHull& b, const Vec3L& axis) {
    return support(a, axis) + support(b, -axis);
}

/// Whether the Gauss-map arcs (a→b) of A's edge and (c→d) of −B's edge may cross (Gregorius, GDC
/// 2013): their cross product is then a facet normal of A − B. Deliberately generous (a margin on
/// every sign test): a superfluous axis only adds an upper bound that is never below the true
/// answer, while a missing one could make the reference wrong.
inline bool arcsMayCross(const Vec3L& a, const Vec3L& b, const Vec3L& c, const Vec3L& d) {
    constexpr Real slack = 1e-12L;
    const Vec3L bxa = b.cross(a), dxc = d.cross(c);
    const Real cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
    return cba * dba < slack && adc * bdc < slack && cba * bdc > -slack;
}

/// The facet normals of A − B (unit, pointing out of A − B, i.e. from A towards B), with a few
/// harmless extras. Every one depends on the orientations only, so the set holds for every
/// translation of B.
inline std::vector<Vec3L> minkowskiAxes(const PosedHull& a, const PosedHull& b) {
    std::vector<Vec3L> axes = a.normals;
    for (const Vec3L& n : b.normals) axes.push_back(-n);
    for (const PosedHull::Edge& ea : a.edges)
        for (const PosedHull::Edge& eb : b.edges) {
            if (!arcsMayCross(ea.left, ea.right, -eb.left, -eb.right)) continue;
            Vec3L axis = ea.direction.cross(eb.direction);
            const Real length = axis.norm();
            // Parallel edges have no common perpendicular of their own: the facet of A − B they make
            // is a parallelogram whose normal lies between the edges' faces, which are already axes.
            if (!(length > 1e-30L * ea.direction.norm() * eb.direction.norm())) continue;
            axis /= length;
            // Orient it out of A − B: along the arc of A's edge (between its two faces).
            if (axis.dot(ea.left + ea.right) < 0) axis = -axis;
            axes.push_back(axis);
        }
    return axes;
}

/// The exact overlap of the pair: the minimum translational distance when they overlap (> 0), the
/// largest separation along any axis when apart (< 0; a lower bound of their distance, enough to
/// say they are apart by more than it). `direction`, when given, receives the minimising axis.
inline Real minimumOverlap(const PosedHull& a, const PosedHull& b, const std::vector<Vec3L>& axes,
                           Vec3L* direction = nullptr) {
    Real best = INFINITY;
    for (const Vec3L& axis : axes) {
        const Real overlap = overlapAlong(a, b, axis);
        if (overlap < best) {
            best = overlap;
            if (direction) *direction = axis;
        }
    }
    return best;
}

/// The penetration along unit n: the largest t with A − t·n still touching B (how far A must move
/// along −n to separate; the exit of the ray along n through A − B). A − B is the intersection of
/// {y : axis·y ≤ overlapAlong(axis)} over its facet normals, so t = min over axes with axis·n > 0 of
/// overlap/(axis·n). −INFINITY never arises: A's own face normals surround every direction.
inline Real penetrationAlong(const PosedHull& a, const PosedHull& b, const std::vector<Vec3L>& axes, const Vec3L& n) {
    Real best = INFINITY;
    for (const Vec3L& axis : axes) {
        const Real along = axis.dot(n);
        if (along > 1e-12L) best = std::min(best, overlapAlong(a, b, axis) / along);
    }
    return best;
}

/// Signed distance from a point to the hull by its planes (> 0 outside; exact outside a face's
/// region, a lower bound near edges and corners, exact inside).
inline Real signedDistance(const PosedHull& hull, const Vec3L& x) {
    Real distance = -INFINITY;
    for (std::size_t f = 0; f < hull.normals.size(); ++f) distance = std::max(distance, hull.normals[f].dot(x) - hull.offsets[f]);
    return distance;
}

/// Along the line x + s·n: the highest s of the hull's upper envelope (the min over faces facing
/// along n of where the line crosses their plane) — the exit of the line from the hull when it
/// crosses it, continued as the faces' planes just outside. Every plane is moved out by `grow`
/// (negative: in). Faces within 1e-12 of parallel to n are skipped (the line runs along them: they
/// bound it sideways, not along n).
inline Real topAlong(const PosedHull& hull, const Vec3L& x, const Vec3L& n, Real grow = 0) {
    Real top = INFINITY;
    for (std::size_t f = 0; f < hull.normals.size(); ++f) {
        const Real c = hull.normals[f].dot(n);
        if (c > 1e-12L) top = std::min(top, (hull.offsets[f] + grow - hull.normals[f].dot(x)) / c);
    }
    return top;
}
inline Real bottomAlong(const PosedHull& hull, const Vec3L& x, const Vec3L& n, Real grow = 0) {
    return -topAlong(hull, x, -n, grow);
}

/// The exact penetration along the line through x in direction n: how far A must move along −n
/// for A's part of that line to clear B's (top of A minus bottom of B), with both hulls grown by
/// `grow`. Near a face almost parallel to n it changes fast with x (by 1/cos of the face's angle
/// to n per unit of sideways motion), so a point that may be off by a tolerance sideways is judged
/// between the penetrations of the hulls shrunk and grown by that tolerance.
inline Real penetrationAt(const PosedHull& a, const PosedHull& b, const Vec3L& x, const Vec3L& n, Real grow = 0) {
    return topAlong(a, x, n, grow) - bottomAlong(b, x, n, grow);
}

}  // namespace gdc::oracle
