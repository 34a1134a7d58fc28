// The random hulls and poses of the oracle. Each pair is generated from its own seed, so one pair
// can be rerun alone (GDCONTACT_ORACLE_SEED=<seed> GDCONTACT_ORACLE_PAIRS=1).
#pragma once

#include "reference.hpp"

#include <random>
#include <string>
#include <vector>

namespace gdc::oracle {

using Random = std::mt19937_64;

inline double uniform(Random& random, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random); }
inline double logUniform(Random& random, double lo, double hi) {
    return std::pow(10.0, uniform(random, std::log10(lo), std::log10(hi)));
}
inline int integer(Random& random, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); }
inline Vec3 onSphere(Random& random) {
    std::normal_distribution<double> gauss;
    Vec3 v;
    do v = Vec3(gauss(random), gauss(random), gauss(random));
    while (!(v.norm() > 1e-6));
    return v.normalized();
}
inline Mat3 randomRotation(Random& random) {
    std::normal_distribution<double> gauss;
    return Eigen::Quaterniond(gauss(random), gauss(random), gauss(random), gauss(random)).normalized().toRotationMatrix();
}

enum class ShapeFamily { Sphere, Needle, Plate, Wedge, Tetrahedron, NearlyCoplanar, CutCorner, Box, Count };
inline const char* name(ShapeFamily family) {
    static const char* names[] = {"sphere points", "needle", "1:50 plate", "wedge (flat roof)", "tetrahedron",
                                  "faces 1e-9..1e-4 rad apart", "corner cut by 1e-7..1e-2", "box"};
    return names[static_cast<int>(family)];
}

struct Shape {
    ShapeFamily family;
    std::vector<Vec3> points;  // empty for a box
    Vec3 halfExtents = Vec3::Zero();
};

// Unit-size point sets (about [-1, 1]³); the caller scales them.
inline std::vector<Vec3> shapePoints(ShapeFamily family, Random& random) {
    std::vector<Vec3> points;
    switch (family) {
        case ShapeFamily::Sphere:
            for (int i = 0, n = integer(random, 5, 40); i < n; ++i) points.push_back(onSphere(random));
            break;
        case ShapeFamily::Needle: {  // 1:1:L, L up to 50: a thin prism of 3–8 sides, slightly ragged ends
            const double width = 1.0 / uniform(random, 10, 50);
            const int sides = integer(random, 3, 8);
            for (double z : {-1.0, 1.0})
                for (int i = 0; i < sides; ++i) {
                    const double angle = 2 * M_PI * (i + 0.3 * uniform(random, 0, 1)) / sides;
                    points.emplace_back(width * std::cos(angle), width * std::sin(angle), z + 0.01 * uniform(random, -1, 1));
                }
            break;
        }
        case ShapeFamily::Plate: {  // a 1:50 polygon slab
            const double thickness = 1.0 / 50;
            const int sides = integer(random, 3, 12);
            for (int i = 0; i < sides; ++i) {
                const double angle = 2 * M_PI * (i + 0.4 * uniform(random, 0, 1)) / sides;
                for (double z : {-thickness, thickness}) points.emplace_back(std::cos(angle), std::sin(angle), z);
            }
            break;
        }
        case ShapeFamily::Wedge: {  // a triangular prism whose roof is nearly flat (1e-4..1 high)
            const double width = uniform(random, 0.2, 1), height = logUniform(random, 1e-4, 1);
            const double depth = uniform(random, 0.05, 0.5);
            for (double x : {-1.0, 1.0}) {
                points.emplace_back(x, -width, -depth);
                points.emplace_back(x, width, -depth);
                points.emplace_back(x, uniform(random, -0.5, 0.5) * width, height);
            }
            break;
        }
        case ShapeFamily::Tetrahedron:
            for (;;) {
                points.clear();
                for (int i = 0; i < 4; ++i) points.push_back(onSphere(random));
                if (std::abs((points[1] - points[0]).cross(points[2] - points[0]).dot(points[3] - points[0])) > 0.05) break;
            }
            break;
        case ShapeFamily::NearlyCoplanar: {  // a box whose top is a roof of two faces 1e-9..1e-4 rad apart,
            const double angle = logUniform(random, 1e-9, 1e-4);  // and (half the time) a side bent the same way
            const Vec3 h(uniform(random, 0.3, 1), uniform(random, 0.3, 1), uniform(random, 0.3, 1));
            for (double x : {-h.x(), h.x()})
                for (double y : {-h.y(), h.y()}) {
                    points.emplace_back(x, y, -h.z());
                    points.emplace_back(x, y, h.z());
                }
            const double ridge = uniform(random, -0.8, 0.8) * h.x();
            const double rise = angle * (h.x() - std::abs(ridge));
            for (double y : {-h.y(), h.y()}) points.emplace_back(ridge, y, h.z() + rise);
            if (integer(random, 0, 1))
                for (double z : {-h.z(), h.z()}) points.emplace_back(h.x() + angle * h.y(), 0, z);
            break;
        }
        case ShapeFamily::CutCorner: {  // a tetrahedron or box with a corner cut by 1e-7..1e-2 of its size
            const bool box = integer(random, 0, 1);
            std::vector<Vec3> corners;
            if (box) {
                const Vec3 h(uniform(random, 0.3, 1), uniform(random, 0.3, 1), uniform(random, 0.3, 1));
                for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
            } else {
                corners = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
                for (Vec3& c : corners) c -= Vec3(0.25, 0.25, 0.25);
            }
            const double cut = logUniform(random, 1e-7, 1e-2);
            const int corner = integer(random, 0, static_cast<int>(corners.size()) - 1);
            for (int i = 0; i < static_cast<int>(corners.size()); ++i) {
                if (i != corner) {
                    points.push_back(corners[i]);
                    continue;
                }
                // The corner's neighbours along the edges: the box's differ in one coordinate bit.
                std::vector<int> neighbours;
                if (box) neighbours = {i ^ 1, i ^ 2, i ^ 4};
                else
                    for (int j = 0; j < 4; ++j)
                        if (j != i) neighbours.push_back(j);
                for (int j : neighbours) points.push_back(corners[i] + cut * (corners[j] - corners[i]));
            }
            break;
        }
        case ShapeFamily::Box:
        case ShapeFamily::Count:
            break;
    }
    return points;
}

/// A random shape of a random family (or the given one) scaled to `scale`.
inline Shape randomShape(Random& random, double scale, int family = -1) {
    Shape shape;
    shape.family = static_cast<ShapeFamily>(family >= 0 ? family : integer(random, 0, static_cast<int>(ShapeFamily::Count) - 1));
    if (shape.family == ShapeFamily::Box) {
        shape.halfExtents = scale * Vec3(uniform(random, 0.05, 1), uniform(random, 0.05, 1), uniform(random, 0.05, 1));
        return shape;
    }
    // A random orientation of the points in the hull's own frame, so faces are not axis-aligned.
    const Mat3 turn = randomRotation(random);
    for (const Vec3& p : shapePoints(shape.family, random)) shape.points.push_back(scale * (turn * p));
    return shape;
}

inline Polytope build(const Shape& shape) {
    return shape.family == ShapeFamily::Box ? Polytope::box(shape.halfExtents) : Polytope::fromPoints(shape.points);
}

enum class PoseFamily { Resting, Deep, EdgeEdge, VertexFace, Grazing, Separated, Count };
inline const char* name(PoseFamily family) {
    static const char* names[] = {"resting face-face", "deep overlap", "edge-edge", "vertex-face", "grazing", "separated"};
    return names[static_cast<int>(family)];
}

inline Mat3 rotationAbout(const Vec3& unitAxis, double angle) { return Eigen::AngleAxisd(angle, unitAxis).toRotationMatrix(); }

/// Rotation taking unit `from` onto unit `to`.
inline Mat3 rotationOnto(const Vec3& from, const Vec3& to) {
    return Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
}

inline Vec3 faceCentre(const Polytope& p, int f) {
    const Polytope::Face& face = p.faces()[f];
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < face.count; ++i) c += p.vertices()[p.faceVertices()[face.first + i]];
    return c / face.count;
}

struct PairPose {
    Pose a, b;
    PoseFamily family;
};

/// A pose of the pair in one family. B starts with its centroid on a point of A (so they overlap),
/// then moves along a direction d to where it just touches (the exact exit, from the reference's
/// axes), then by a signed offset: negative overlaps, positive separates.
inline PairPose randomPairPose(Random& random, const Polytope& a, const Polytope& b, PoseFamily family) {
    PairPose out;
    out.family = family;
    out.a = Pose{randomRotation(random), Vec3(uniform(random, -1, 1), uniform(random, -1, 1), uniform(random, -1, 1)) *
                                             a.radius() * uniform(random, 0, 3)};
    const double size = a.radius() + b.radius();
    const double smaller = std::min(a.radius(), b.radius());
    Mat3 rotationB = randomRotation(random);      // world
    Vec3 direction = onSphere(random);            // world
    Vec3 anchor = out.a.apply(a.centroid());      // a point of A where B's centroid starts
    // Geometric features chosen in A's frame, then expressed in the world.
    PoseFamily shapeOfContact = family;
    if (family == PoseFamily::Grazing || family == PoseFamily::Separated)
        shapeOfContact = static_cast<PoseFamily>(integer(random, 0, 3));  // grazing/separated in any arrangement
    const double blend = uniform(random, 0, 0.9);
    switch (shapeOfContact) {
        case PoseFamily::Resting: {
            const int fa = integer(random, 0, static_cast<int>(a.faces().size()) - 1);
            const int fb = integer(random, 0, static_cast<int>(b.faces().size()) - 1);
            const Vec3 na = out.a.rotation * a.faces()[fa].normal;
            rotationB = rotationOnto(rotationB * b.faces()[fb].normal, -na) * rotationB;
            const Vec3 tiltAxis = na.cross(onSphere(random));
            if (tiltAxis.norm() > 1e-6) rotationB = rotationAbout(tiltAxis.normalized(), logUniform(random, 1e-7, 1e-2)) * rotationB;
            direction = na;
            anchor += blend * (out.a.apply(faceCentre(a, fa)) - anchor);
            break;
        }
        case PoseFamily::EdgeEdge: {
            // Half the time each body's flattest edge (the ridge of a nearly flat roof, whose two
            // faces are nearly parallel): where edge–edge depth was overestimated 2.4× (issue 21).
            auto pickEdge = [&](const Polytope& p) -> const Polytope::Edge& {
                if (integer(random, 0, 1)) return p.edges()[integer(random, 0, static_cast<int>(p.edges().size()) - 1)];
                int flattest = 0;
                double best = -2;
                for (int e = 0; e < static_cast<int>(p.edges().size()); ++e) {
                    const double cosine = p.faces()[p.edges()[e].leftFace].normal.dot(p.faces()[p.edges()[e].rightFace].normal);
                    if (cosine > best) best = cosine, flattest = e;
                }
                return p.edges()[flattest];
            };
            const Polytope::Edge& ea = pickEdge(a);
            const Polytope::Edge& eb = pickEdge(b);
            const Vec3 outA = out.a.rotation * (a.faces()[ea.leftFace].normal + a.faces()[ea.rightFace].normal).normalized();
            const Vec3 outB = (b.faces()[eb.leftFace].normal + b.faces()[eb.rightFace].normal).normalized();
            rotationB = rotationOnto(rotationB * outB, -outA) * rotationB;
            // The edges crossed at any angle, or (half the time) nearly parallel: 1e-6..0.1 rad.
            const double crossing = integer(random, 0, 1) ? uniform(random, 0, 2 * M_PI)
                                                          : integer(random, 0, 1) * M_PI + (integer(random, 0, 1) ? 1 : -1) * logUniform(random, 1e-6, 0.1);
            const Vec3 edgeA = (out.a.rotation * (a.vertices()[ea.head] - a.vertices()[ea.tail])).normalized();
            const Vec3 edgeB = rotationB * (b.vertices()[eb.head] - b.vertices()[eb.tail]);
            // Turn B about outA so its edge lies along A's (projected on the plane ⟂ outA), then by the crossing angle.
            const Vec3 projectedB = (edgeB - edgeB.dot(outA) * outA).normalized();
            const double aligned = std::atan2(outA.dot(projectedB.cross(edgeA)), projectedB.dot(edgeA));
            rotationB = rotationAbout(outA, (std::isfinite(aligned) ? aligned : 0) + crossing) * rotationB;
            direction = outA;
            const Vec3 middle = 0.5 * (a.vertices()[ea.tail] + a.vertices()[ea.head]);
            anchor += blend * (out.a.apply(middle) - anchor);
            break;
        }
        case PoseFamily::VertexFace: {
            const int fa = integer(random, 0, static_cast<int>(a.faces().size()) - 1);
            const Vec3 vb = b.vertices()[integer(random, 0, static_cast<int>(b.vertices().size()) - 1)] - b.centroid();
            const Vec3 na = out.a.rotation * a.faces()[fa].normal;
            rotationB = rotationOnto((rotationB * vb).normalized(), -na) * rotationB;
            direction = na;
            anchor += blend * (out.a.apply(faceCentre(a, fa)) - anchor);
            break;
        }
        default:
            break;
    }
    // Products of rotations (and FromTwoVectors for nearly opposite vectors) drift from orthonormal
    // by up to 1e-11: back through a unit quaternion, so the pose is a rotation to rounding.
    rotationB = Eigen::Quaterniond(rotationB).normalized().toRotationMatrix();
    out.b = Pose{rotationB, anchor - rotationB * b.centroid()};
    // The exact touching distance along `direction`, from the reference.
    const PosedHull pa = posed(a, out.a), pb = posed(b, out.b);
    const std::vector<Vec3L> axes = minkowskiAxes(pa, pb);
    // B moved by +t·d: A − B moves by −t·d, so B touches A until A − B stops containing t·d.
    const double touch = static_cast<double>(penetrationAlong(pa, pb, axes, toLong(direction)));
    double offset = 0;
    switch (family) {
        case PoseFamily::Deep: offset = -uniform(random, 0.05, 1) * touch; break;
        case PoseFamily::Grazing: offset = (integer(random, 0, 1) ? 1 : -1) * logUniform(random, 1e-9, 1e-3) * size; break;
        case PoseFamily::Separated: offset = logUniform(random, 1e-6, 1) * size; break;
        default: offset = -logUniform(random, 1e-6, 0.2) * smaller; break;
    }
    out.b.position += (touch + offset) * direction;
    return out;
}

}  // namespace gdc::oracle
