// Stage 3 of the one composition (pipeline.hpp) where B is a half-space: A's feature against a
// plane is the feature's own points, each lifted to its depth (its vertices, or its cap's, and with
// Settings::spanContactRegion the points where its edges cross the contact depth), the deepest
// vertex where all of them float; then ranked and written out by emitManifold's rule. Every shape's
// half-space hooks (half_space.cpp: a box, a small hull, any polytope) share it. The points go to
// fixed arrays in scalar code (DirectPoints) where they cannot outnumber the caller's budget — the
// same IEEE operations in Eigen's grouping, so the same bits — and to emitManifold otherwise
// (GatheredPoints).
#pragma once

#include <gdcontact/collide.hpp>

#include "contact/collide_general.hpp"
#include "contact/feature_intersection.hpp"
#include "contact/gauss_map.hpp"
#include "contact/half_space.hpp"
#include "contact/rank_few.hpp"
#include "contact/reduction.hpp"
#include "geometry/small_vector.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace gdc::detail {

// The half-space in A's frame: the solid is {x : m·x ≤ offset}; the contact normal is −m.
struct PlaneInA {
    Vec3 m;
    double offset;
    // m·x as Eigen's dot evaluates it ((m₀x₀ + m₁x₁) + m₂x₂), in scalar code.
    double depthOf(const Vec3& x) const { return offset - (m.x() * x.x() + m.y() * x.y() + m.z() * x.z()); }
};

// the general hooks' change of frame, expression for expression (so to the bit), of the plane
// normaliseHalfSpace made.
inline PlaneInA planeInA(const UnitHalfSpace& b, const Pose& poseA) {
    return {poseA.rotation.transpose() * b.normal, b.offset - b.normal.dot(poseA.position)};
}

// The contacts as the general hooks' `add` makes them (x lifted half its depth onto the plane), kept
// in fixed arrays when they cannot outnumber the caller's maximum, then ranked and written to the
// manifold in the world frame as emitManifold writes them (no reduction: the centroid rule only
// acts where points are dropped).
class DirectPoints {
public:
    DirectPoints(const Vec3& m) : mx_(m.x()), my_(m.y()), mz_(m.z()) {}
    // Scalar code throughout (here and in emit): the same IEEE operations, in the same order, as
    // the Eigen expressions the general hooks evaluate (x + 0.5·depth·m; a dot product is
    // (x₀y₀ + x₁y₁) + x₂y₂; R·x + p row by row, see emit), so the same bits (manifold_dump) — but without the packet
    // shuffles Eigen's SSE code spends on 3-vectors, which were the larger part of a box–plane
    // call's lifting and emitting.
    void add(const Vec3& x, double depth) {
        const double half = 0.5 * depth;
        x_[count_] = x.x() + half * mx_;
        y_[count_] = x.y() + half * my_;
        z_[count_] = x.z() + half * mz_;
        depth_[count_++] = depth;
    }
    bool empty() const { return count_ == 0; }
    // Always inlined into liftFeature: the points stay where the lift left them, the settings are
    // read once, and planar coordinates (a plane basis: a square root and a division) are made only
    // where the ranking reads them (3 or more points).
    // `order`: AmongEqualDepths leaves the points in lift order where no two depths are equal
    // (half_space.hpp; the caller orders them by depth, and every point is kept here anyway).
    template <ImportanceOrder order>
    [[gnu::always_inline]] void emit(const Vec3& normal, const Pose& poseA, int maxCount, double hysteresis,
                                     double tolerance, Manifold& manifold) {
        // Here count_ ≤ maxCount (liftFeature's condition; a lone deepest vertex: 1 ≤ maxCount), so
        // the ranking keeps every point and only orders them.
        const int n = count_;
        const Mat3& r = poseA.rotation;
        int chosen[kMaxManifoldPoints];
        int count = n;
        if (n == 1) {  // one point: nothing to order
            chosen[0] = 0;
        } else if (order == ImportanceOrder::AmongEqualDepths && n >= 3 && allDepthsDiffer()) {
            // (Two points take the comparison below, cheaper than the test.)
            for (int i = 0; i < n; ++i) chosen[i] = i;
        } else {
            // rule.identity = Rᵀ·identityDirection(), column by column (for two points only where
            // both are within the tolerance of the deepest).
            const Vec3& world = identityDirection();
            auto identityAxis = [&](int k) { return r(0, k) * world.x() + r(1, k) * world.y() + r(2, k) * world.z(); };
            if (n == 2) {
                // rankContacts' choice for two points, comparison for comparison (rankAllOfFew's first
                // slot: the point of largest identity among those within `tolerance` of the deepest;
                // the identities are computed only where both are): no rule, no call.
                double deepest = -INFINITY;
                deepest = std::max(deepest, depth_[0]);
                deepest = std::max(deepest, depth_[1]);
                const double threshold = deepest - tolerance;
                bool secondFirst = false;
                if (depth_[1] >= threshold) {
                    if (depth_[0] < threshold) {
                        secondFirst = true;
                    } else {
                        const double ix = identityAxis(0), iy = identityAxis(1), iz = identityAxis(2);
                        secondFirst = x_[1] * ix + y_[1] * iy + z_[1] * iz > x_[0] * ix + y_[0] * iy + z_[0] * iz;
                    }
                }
                chosen[0] = secondFirst ? 1 : 0;
                chosen[1] = secondFirst ? 0 : 1;
            } else {
                const double ix = identityAxis(0), iy = identityAxis(1), iz = identityAxis(2);
                RankPoint ranked[kMaxManifoldPoints];
                const RankingRule rule{maxCount, hysteresis, tolerance, Vec3(ix, iy, iz)};
                Vec3 u, v;
                planeBasis(normal, u, v);
                for (int i = 0; i < n; ++i)
                    ranked[i] = {Vec2(x_[i] * u.x() + y_[i] * u.y() + z_[i] * u.z(),
                                      x_[i] * v.x() + y_[i] * v.y() + z_[i] * v.z()),
                                 depth_[i], x_[i] * ix + y_[i] * iy + z_[i] * iz};
                // rankContacts' own dispatch for a few points, each kept (no prefix given).
                count = n <= 4 ? rankAllOfFew(ranked, n, rule, chosen) : rankContacts(ranked, n, rule, chosen);
            }
        }
        manifold.normal = r * normal;
        manifold.pointCount = count;
        double nonFinite = 0;  // emitManifold's overflow check
        ContactPoint* out = manifold.points.data();
        const Vec3& p = poseA.position;
        for (int i = 0; i < count; ++i) {
            const int k = chosen[i];
            const double lx = x_[k], ly = y_[k], lz = z_[k];
            const double px = r(0, 0) * lx + r(0, 1) * ly + r(0, 2) * lz + p.x();
            const double py = r(1, 0) * lx + r(1, 1) * ly + r(1, 2) * lz + p.y();
            // Eigen's 3×3 product takes rows 0 and 1 as one packet and sums the third row's tail
            // as r₂₀x + (r₂₁y + r₂₂z): the same grouping here, so the same bits.
            const double pz = r(2, 0) * lx + (r(2, 1) * ly + r(2, 2) * lz) + p.z();
            const double depth = depth_[k];
            out[i].position = Vec3(px, py, pz);
            out[i].depth = depth;
            nonFinite += px * 0.0 + py * 0.0 + pz * 0.0 + depth * 0.0;
        }
        if (!(nonFinite == 0))
            throw InvalidInput("the contact overflows double precision (coordinates or offsets near 1e308)");
    }

private:
    // Whether no two depths compare equal (== as the caller's depth order compares them: 0 and −0
    // are equal, and so tie).
    bool allDepthsDiffer() const {
        for (int i = 1; i < count_; ++i)
            for (int j = 0; j < i; ++j)
                if (depth_[i] == depth_[j]) return false;
        return true;
    }

    double mx_, my_, mz_;
    double x_[kMaxManifoldPoints], y_[kMaxManifoldPoints], z_[kMaxManifoldPoints];
    double depth_[kMaxManifoldPoints];
    int count_ = 0;
};

// The contacts gathered in A's frame as the general hooks gather them, then reduced and written as
// its emit does: used when there may be more than the caller's maximum (or a cap's crossings
// need the points found so far).
class GatheredPoints {
public:
    explicit GatheredPoints(const Vec3& m) : m_(m) {}
    void add(const Vec3& x, double depth) { kept_.push_back({x + 0.5 * depth * m_, depth, Vec2::Zero()}); }
    bool empty() const { return kept_.empty(); }
    // Whether a crossing is within `tolerance` of a point already found (cap faces share edges).
    bool knows(const Vec3& crossing, double tolerance) const {
        for (const LiftedPoint& point : kept_)
            if ((point.position - 0.5 * point.depth * m_ - crossing).squaredNorm() <= tolerance * tolerance) return true;
        return false;
    }
    void emit(const Vec3& normal, const Pose& poseA, const Settings& settings, double tolerance, const Vec3& centroid,
              Manifold& manifold) {
        // Planar coordinates serve only the ranking: computed where it compares distances and areas.
        if (kept_.size() >= 3) {
            Vec3 u, v;
            planeBasis(normal, u, v);
            for (LiftedPoint& point : kept_) point.planar = Vec2(point.position.dot(u), point.position.dot(v));
        }
        emitManifold(kept_, normal, poseA, settings, tolerance, &centroid, 1, manifold);
    }

private:
    const Vec3& m_;
    LiftedPoints kept_;
};

// Stage 3 against a plane, the same for every shape once its support and feature are known: the
// feature's vertices (or its cap's) lifted onto the plane at their depths, the boundary crossings,
// the deepest vertex where all float, then ranked and written out.
struct PlaneLift {
    const Polytope& a;
    const PlaneInA& plane;
    const Settings& settings;
    double tolerance;  // 1e-9 × A's radius, as in the general hooks
    double keepDepth;  // −margin − tolerance

    // With Settings::spanContactRegion: where an edge runs from contact into a clear gap, the
    // point where it crosses the contact depth (the general hooks' addCrossing).
    template <class Points>
    void addCrossing(const Vec3& x, double depthX, const Vec3& y, double depthY, bool checkKnown, Points& points) const {
        const double t = contactBoundaryCrossing(depthX, depthY, -settings.margin, tolerance);
        if (std::isnan(t)) return;
        const Vec3 crossing = x + t * (y - x);
        if constexpr (std::is_same_v<Points, GatheredPoints>)
            if (checkKnown && points.knows(crossing, tolerance)) return;
        points.add(crossing, plane.depthOf(crossing));
    }

    // One vertex, an edge, or a face's loop: each depth once (`depths`, in loop order), each
    // point in loop order, a crossing after its edge's first vertex.
    template <class Points>
    void liftLoop(const int* indices, const double* depths, int count, Points& points) const {
        const int edges = count >= 3 ? count : count - 1;  // a face's loop closes; an edge is one edge
        const Vec3* vertices = a.vertices().data();
        for (int i = 0; i < count; ++i) {
            const Vec3& x = vertices[indices[i]];
            if (depths[i] >= keepDepth) points.add(x, depths[i]);
            if (!settings.spanContactRegion || i >= edges) continue;
            const int next = i + 1 == count ? 0 : i + 1;
            addCrossing(x, depths[i], vertices[indices[next]], depths[next], false, points);
        }
    }

    // A face's cap of near-coplanar faces: every cap vertex, then the crossings of every cap
    // face's edges, each crossing once.
    template <class VertexDepth>
    void liftCap(const SmallVector<int, 8>& cap, VertexDepth depthOfVertex, GatheredPoints& points) const {
        SmallVector<int, 32> vertices;
        capVertices(a, cap, vertices);
        for (int v : vertices) {
            const double depth = depthOfVertex(v);
            if (depth >= keepDepth) points.add(a.vertices()[v], depth);
        }
        if (!settings.spanContactRegion) return;
        for (int f : cap) {
            const Polytope::Face& loop = a.faces()[f];
            const int* corners = a.faceVertices().data() + loop.first;
            for (int i = 0; i < loop.count; ++i) {
                const int x = corners[i], y = corners[i + 1 == loop.count ? 0 : i + 1];
                addCrossing(a.vertices()[x], depthOfVertex(x), a.vertices()[y], depthOfVertex(y), true, points);
            }
        }
    }

    // The feature's points into the manifold, ranked (and reduced) as the general hooks' emit does:
    // in fixed arrays when they cannot outnumber the caller's maximum, gathered otherwise. A
    // tilted face whose points all float keeps the deepest vertex.
    // `order`: the order the caller needs (half_space.hpp).
    template <ImportanceOrder order = ImportanceOrder::Full, class VertexDepth>
    void liftFeature(const Feature& feature, int deepest, const SmallVector<int, 8>* cap, VertexDepth depthOfVertex,
                     const Pose& poseA, Manifold& manifold) const {
        const Vec3 normal = -plane.m;  // stage 1's, the plane's own (made here: not kept in memory for the call)
        int storage[2];
        const int* indices = nullptr;
        const int count = featureVertices(a, feature, &indices, storage);
        const int maxCount = std::max(1, std::min(settings.maxContacts, kMaxManifoldPoints));
        const int mostPoints = settings.spanContactRegion ? 2 * count : count;
        auto keepDeepestIfNone = [&](auto& points) {
            if (points.empty()) points.add(a.vertices()[deepest], depthOfVertex(deepest));
        };
        if (!cap && mostPoints <= maxCount) {
            DirectPoints points(plane.m);
            if (settings.spanContactRegion) {
                double depths[kMaxManifoldPoints];  // count ≤ maxCount ≤ kMaxManifoldPoints
                for (int i = 0; i < count; ++i) depths[i] = depthOfVertex(indices[i]);
                liftLoop(indices, depths, count, points);
            } else {  // liftLoop without crossings: each vertex's depth, and the vertex if it is kept
                const Vec3* vertices = a.vertices().data();
                const double keep = keepDepth;
                for (int i = 0; i < count; ++i) {
                    const double depth = depthOfVertex(indices[i]);
                    if (depth >= keep) points.add(vertices[indices[i]], depth);
                }
            }
            keepDeepestIfNone(points);
            points.template emit<order>(normal, poseA, maxCount, settings.reductionHysteresis, tolerance, manifold);
            return;
        }
        GatheredPoints points(plane.m);
        if (cap) {
            liftCap(*cap, depthOfVertex, points);
        } else {
            SmallVector<double, 32> depths;
            for (int i = 0; i < count; ++i) depths.push_back(depthOfVertex(indices[i]));
            liftLoop(indices, depths.data(), count, points);
        }
        keepDeepestIfNone(points);
        points.emit(normal, poseA, settings, tolerance, a.centroid(), manifold);
    }
};

}  // namespace gdc::detail
