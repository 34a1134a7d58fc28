// Independent answers for the core tests: brute-force polygon intersection, signed distance to
// a polytope, random poses. Deliberately written differently from the library's algorithms.
#pragma once

#include <gdcontact/gdcontact.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace gdc::testing {

inline Pose makePose(const Vec3& position, const Mat3& rotation = Mat3::Identity()) { return Pose{rotation, position}; }

inline Mat3 rotationAbout(const Vec3& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// Uniformly distributed rotation (normalised Gaussian quaternion) from any standard random engine.
template <class RandomEngine>
Mat3 randomRotation(RandomEngine& random) {
    std::normal_distribution<double> gauss;
    Eigen::Quaterniond q(gauss(random), gauss(random), gauss(random), gauss(random));
    return q.normalized().toRotationMatrix();
}

/// Signed distance from a world point to a posed polytope's surface (> 0 outside), by its planes.
inline double signedDistance(const Polytope& polytope, const Pose& pose, const Vec3& world) {
    Vec3 local = pose.applyInverse(world);
    double distance = -INFINITY;
    for (const auto& face : polytope.faces()) distance = std::max(distance, face.normal.dot(local) - face.offset);
    return distance;
}

/// Intersection of two convex polygons by brute force: the vertices of each inside the other and
/// every pairwise edge crossing. Unordered, duplicates removed.
inline std::vector<Vec2> convexPolygonIntersection(const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
    auto cross = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
    auto inside = [&](const std::vector<Vec2>& poly, const Vec2& x) {
        for (std::size_t i = 0; i < poly.size(); ++i)
            if (cross(poly[(i + 1) % poly.size()] - poly[i], x - poly[i]) < -1e-12) return false;
        return true;
    };
    std::vector<Vec2> out;
    for (const Vec2& x : p)
        if (inside(q, x)) out.push_back(x);
    for (const Vec2& x : q)
        if (inside(p, x)) out.push_back(x);
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = 0; j < q.size(); ++j) {
            Vec2 a0 = p[i], a1 = p[(i + 1) % p.size()], b0 = q[j], b1 = q[(j + 1) % q.size()];
            double d = cross(a1 - a0, b1 - b0);
            if (std::abs(d) < 1e-14) continue;
            double s = cross(b0 - a0, b1 - b0) / d, t = cross(b0 - a0, a1 - a0) / d;
            if (s > 0 && s < 1 && t > 0 && t < 1) out.push_back(a0 + s * (a1 - a0));
        }
    std::vector<Vec2> unique;
    for (const Vec2& x : out)
        if (std::none_of(unique.begin(), unique.end(), [&](const Vec2& y) { return (x - y).norm() < 1e-9; }))
            unique.push_back(x);
    return unique;
}

/// True when every point of `expected` has a point of `actual` within `tolerance`, and vice versa.
inline bool sameSets(const std::vector<Vec3>& actual, const std::vector<Vec3>& expected, double tolerance) {
    auto covered = [&](const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
        for (const Vec3& x : from)
            if (std::none_of(to.begin(), to.end(), [&](const Vec3& y) { return (x - y).norm() <= tolerance; }))
                return false;
        return true;
    };
    return covered(actual, expected) && covered(expected, actual);
}

inline std::vector<Vec3> positions(const Manifold& m) {
    std::vector<Vec3> out;
    for (int i = 0; i < m.pointCount; ++i) out.push_back(m.points[i].position);
    return out;
}

/// Area of the convex hull of 2-D points (Andrew's monotone chain); 0 for fewer than three.
inline double convexHullArea(std::vector<Vec2> p) {
    if (p.size() < 3) return 0;
    auto cross2 = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
    std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    std::vector<Vec2> h(2 * p.size());
    int k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross2(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
        h[k++] = p[i];
    }
    for (int i = static_cast<int>(p.size()) - 2, lower = k + 1; i >= 0; --i) {
        while (k >= lower && cross2(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
        h[k++] = p[i];
    }
    double area = 0;
    for (int i = 0; i + 1 < k; ++i) area += 0.5 * cross2(h[i], h[i + 1]);
    return area;
}

}  // namespace gdc::testing
