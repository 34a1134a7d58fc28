// feature_intersection.cpp's stage 3 for small features (intersectSmallFeatures: the clip in fixed
// arrays, the uniqueness pass, the heights, the lift) as it was at ac53fc8, before the box speed
// work: its projection one dot product at a time, the clip's steps testing both crossings, the
// uniqueness pass a loop of its own after the clip (now made by the clip's last edge as it writes),
// the heights in arrays read by a second loop. Kept verbatim as the reference that
// tests/small_intersection_test.cpp compares detail::intersectSmallFeatures and
// detail::intersectFeatures with, bit for bit.
#pragma once

#include "contact/feature_intersection.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::reference::stage3 {
using namespace gdc::detail;

template <class T, int N>
class FixedVector {
public:
    T* reserve(std::size_t) { return data_; }
    void setSize(std::size_t count) { size_ = count; }
    void clear() { size_ = 0; }
    void push_back(const T& value) { data_[size_++] = value; }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    T* data() { return data_; }
    const T* data() const { return data_; }
    T& operator[](std::size_t i) { return data_[i]; }
    const T& operator[](std::size_t i) const { return data_[i]; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }

private:
    T data_[N];
    std::size_t size_ = 0;
};

// Features of at most four points: a clip by at most four sides at most doubles the subject's ≤ 4
// points per side, so no region exceeds 64 points (and 2 × 64 heights).
struct SmallFeatureStorage {
    static constexpr int kMaxRegion = 64;
    using Polygon = FixedVector<Vec2, kMaxRegion>;
    using Heights = FixedVector<double, 2 * kMaxRegion>;
};

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The feature's points in the plane (u, v), a face's loop made counter-clockwise (B's face arrives
// clockwise), written into the empty `out`; returns its points. Here and below the loops write through a plain pointer
// with the count in a local (SmallVector::reserve): push_back cost the box–box path 12 %.
template <class Polygon>
[[gnu::always_inline]] inline const Vec2* project(const FeatureView& feature, const Vec3& u, const Vec3& v,
                                                  Polygon& out) {
    const int n = feature.count;
    Vec2* points = out.reserve(n);
    for (int i = 0; i < n; ++i) points[i] = Vec2(feature.points[i].dot(u), feature.points[i].dot(v));
    out.setSize(n);
    if (n >= 3) {
        double area = cross2(points[n - 1], points[0]);
        for (int i = 0; i + 1 < n; ++i) area += cross2(points[i], points[i + 1]);
        if (area < 0)
            for (int i = 0, j = n - 1; i < j; ++i, --j) std::swap(points[i], points[j]);
    }
    return points;
}

// Sutherland–Hodgman: clip a convex polygon (or a segment, or a point) by the half-planes left
// of each CCW edge of `clip`, in the caller's two buffers in turn (the subject itself is read by
// the first edge, no copy). Returns the region: one of the buffers, or the subject where no edge
// of `clip` cut it.
template <class Polygon>
[[gnu::always_inline]] inline const Polygon& clipByConvexPolygon(const Polygon& subject, const Polygon& clip,
                                                                 double tolerance, Polygon (&buffers)[2]) {
    const Polygon* input = &subject;
    const Vec2* corners = clip.data();
    const std::size_t sides = clip.size();
    int written = 0;  // buffers filled so far: the next one is never the one being read
    for (std::size_t e = 0; e < sides && !input->empty(); ++e) {
        const Vec2* current = input->data();
        const std::size_t n = input->size();
        const Vec2& a = corners[e];
        const Vec2 edge = corners[e + 1 == sides ? 0 : e + 1] - a;
        const double length = edge.norm();
        if (!(length > 0)) continue;  // a repeated corner: no half-plane
        Polygon& next = buffers[written++ & 1];
        next.clear();
        Vec2* output = next.reserve(2 * n);  // each point adds itself and at most one crossing
        std::size_t count = 0;
        // Signed distance scaled by the edge length (> 0 inside); the slack is scaled to match.
        const double slack = tolerance * length;
        auto distance = [&](const Vec2& p) { return cross2(edge, p - a); };
        // Each point's distance is computed once and carried to the next step as `dp`; a closed
        // polygon's last step reuses the first point's (the same value the wrap recomputed).
        const double first = distance(current[0]);
        double dp = first;
        auto step = [&](const Vec2& p, const Vec2& q, double dq) {
            if (dp >= -slack) output[count++] = p;
            if ((dp < -slack && dq > slack) || (dp > slack && dq < -slack))
                output[count++] = p + (q - p) * (dp / (dp - dq));
            dp = dq;
        };
        for (std::size_t i = 0; i + 1 < n; ++i) step(current[i], current[i + 1], distance(current[i + 1]));
        if (n >= 3) {
            step(current[n - 1], current[0], first);
        } else if (dp >= -slack) {  // a segment's or a point's last point: no closing edge
            output[count++] = current[n - 1];
        }
        next.setSize(count);
        input = &next;
    }
    return *input;
}

// The segments' crossing, or their overlap where they are parallel and on one line, into `out`.
template <class Polygon>
inline void intersectSegments(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1, double tolerance,
                       Polygon& out) {
    Vec2 da = a1 - a0, db = b1 - b0;
    double denominator = cross2(da, db);
    double la = da.norm(), lb = db.norm();
    if (std::abs(denominator) <= 1e-9 * la * lb) {
        // Parallel: overlap interval along A, if B lies on A's line.
        if (std::abs(cross2(da, b0 - a0)) > tolerance * la) return;
        double t0 = (b0 - a0).dot(da) / (la * la), t1 = (b1 - a0).dot(da) / (la * la);
        double lo = std::max(0.0, std::min(t0, t1)), hi = std::min(1.0, std::max(t0, t1));
        if (hi < lo - tolerance / la) return;
        out.push_back(a0 + std::clamp(lo, 0.0, 1.0) * da);
        if ((hi - lo) * la > tolerance) out.push_back(a0 + std::clamp(hi, 0.0, 1.0) * da);
        return;
    }
    double s = cross2(b0 - a0, db) / denominator, t = cross2(b0 - a0, da) / denominator;
    if (s < -tolerance / la || s > 1 + tolerance / la || t < -tolerance / lb || t > 1 + tolerance / lb) return;
    out.push_back(a0 + std::clamp(s, 0.0, 1.0) * da);
}

inline bool pointOnSegment(const Vec2& p, const Vec2& a, const Vec2& b, double tolerance) {
    Vec2 d = b - a;
    double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (a + t * d - p).norm() <= tolerance;
}

// The intersection of two projected features (the one with more points clips the other; B's
// when as many), in the caller's buffers; returns the region.
template <class Polygon>
[[gnu::always_inline]] inline const Polygon& intersect2d(const Polygon& first, const Polygon& second,
                                                         double tolerance, Polygon (&buffers)[2]) {
    const bool firstHasMore = first.size() >= second.size();
    const Polygon& a = firstHasMore ? first : second;  // a has at least as many points
    const Polygon& b = firstHasMore ? second : first;
    if (a.size() >= 3) return clipByConvexPolygon(b, a, tolerance, buffers);
    Polygon& out = buffers[0];
    if (a.size() == 2 && b.size() == 2) {
        intersectSegments(a[0], a[1], b[0], b[1], tolerance, out);
    } else if (a.size() == 2) {
        if (pointOnSegment(b[0], a[0], a[1], tolerance)) out.push_back(b[0]);
    } else if ((a[0] - b[0]).norm() <= tolerance) {
        out.push_back(b[0]);
    }
    return out;
}

// Height along n of the point of a feature that projects to a planar point q. For every feature
// it is affine in q — a face's plane, an edge's line, a vertex's constant — so it is set up once
// per feature as height(q) = constant + gradient·q, and each point costs two multiply-adds.
class LiftedHeight {
public:
    // `projected`: the feature's points in the plane (project); an edge's are in its own order.
    [[gnu::always_inline]] LiftedHeight(const FeatureView& feature, const Vec2* projected, const Vec3& u,
                                        const Vec3& v, const Vec3& n) {
        if (feature.type == FeatureType::Face) {
            // planeNormal·(q.x·u + q.y·v + h·n) = planeOffset, solved for h.
            const double normalAlongN = feature.planeNormal.dot(n);
            constant_ = feature.planeOffset / normalAlongN;
            gradient_ = -Vec2(feature.planeNormal.dot(u), feature.planeNormal.dot(v)) / normalAlongN;
        } else if (feature.type == FeatureType::Edge) {
            // The point of the edge p0 + t·(p1 − p0) whose projection is nearest q (t affine in q).
            const Vec3 &p0 = feature.points[0], &p1 = feature.points[1];
            const Vec2& end0 = projected[0];
            const Vec2 along = projected[1] - end0;
            const double alongSquared = along.squaredNorm();
            const double rise = (p1 - p0).dot(n);
            constant_ = p0.dot(n);
            if (alongSquared > 0) {
                gradient_ = along * (rise / alongSquared);
                constant_ -= gradient_.dot(end0);
            }
        } else {
            constant_ = feature.points[0].dot(n);
        }
    }

    double operator()(const Vec2& q) const { return constant_ + gradient_.dot(q); }

private:
    double constant_ = 0;
    Vec2 gradient_ = Vec2::Zero();
};

// A feature (or one face of a cap) projected onto the contact plane once: its CCW polygon and its
// lifting back along n.
template <class Storage>
struct ProjectedPiece {
    typename Storage::Polygon polygon;
    LiftedHeight height;

    [[gnu::always_inline]] ProjectedPiece(const FeatureView& piece, const Vec3& u, const Vec3& v, const Vec3& n)
        : height(piece, project(piece, u, v, polygon), u, v, n) {}  // `polygon` is made first
};

// The intersection vertices of two projected pieces, lifted onto both; appended to `out`, skipping
// points within `tolerance` (in the plane) of one already there when `merge` (pieces of caps
// share their edges' points).
template <class Storage>
[[gnu::always_inline]] inline void intersectPieces(const ProjectedPiece<Storage>& a, const ProjectedPiece<Storage>& b,
                                                   int pieceA, int pieceB, const Vec3& u, const Vec3& v,
                                                   const Vec3& normal, double tolerance, double minimumDepth,
                                                   bool spanRegion, bool merge, LiftedPoints& out) {
    using Polygon = typename Storage::Polygon;
    Polygon buffers[2];
    const Polygon& region = intersect2d(a.polygon, b.polygon, tolerance, buffers);
    // Drop near-duplicate consecutive points produced where edges cross at a vertex.
    const double toleranceSquared = tolerance * tolerance;
    Polygon uniqueStorage;
    Vec2* unique = uniqueStorage.reserve(region.size());
    std::size_t count = 0;
    for (const Vec2& p : region)
        if (count == 0 || (p - unique[count - 1]).squaredNorm() > toleranceSquared) unique[count++] = p;
    while (count > 1 && (unique[0] - unique[count - 1]).squaredNorm() <= toleranceSquared) --count;

    // At most two points per vertex of the region: itself and a boundary crossing.
    std::size_t emitted = out.size();
    LiftedPoint* points = out.reserve(emitted + 2 * count);
    auto emit = [&](const Vec2& q, double heightA, double heightB) {
        if (merge) {
            bool known = false;
            for (std::size_t i = 0; i < emitted; ++i) known = known || (points[i].planar - q).squaredNorm() <= toleranceSquared;
            if (known) return;
        }
        points[emitted++] = {q.x() * u + q.y() * v + 0.5 * (heightA + heightB) * normal, heightA - heightB, q, pieceA,
                             pieceB};
    };
    // With `spanRegion`: the depth is affine along every edge of the region (both features are flat
    // there), so where an edge runs from contact into a clear gap, the contact region ends where
    // the depth crosses `minimumDepth`, and that point is a contact too. Without it the floating
    // vertices are simply dropped, which shrinks a slightly tilted face's support polygon to its
    // deepest corners (a cube resting 1° off flat keeps about half of its true contact area). An
    // edge whose far end floats by less than the tolerance adds nothing: its end is kept, and a
    // crossing there would be rounding noise.
    typename Storage::Heights heightStorage;
    double* heightsA = heightStorage.reserve(2 * count);
    double* heightsB = heightsA + count;
    for (std::size_t i = 0; i < count; ++i) heightsA[i] = a.height(unique[i]), heightsB[i] = b.height(unique[i]);
    const std::size_t edges = count >= 3 ? count : (count == 2 ? 1 : 0);  // a polygon closes; a segment has one edge
    const double keepDepth = minimumDepth - tolerance;
    for (std::size_t i = 0; i < count; ++i) {
        const double depth = heightsA[i] - heightsB[i];
        if (depth >= keepDepth) emit(unique[i], heightsA[i], heightsB[i]);
        if (!spanRegion || i >= edges) continue;
        const std::size_t next = i + 1 == count ? 0 : i + 1;
        const double t = contactBoundaryCrossing(depth, heightsA[next] - heightsB[next], minimumDepth, tolerance);
        if (std::isnan(t)) continue;
        const Vec2 crossing = unique[i] + t * (unique[next] - unique[i]);
        emit(crossing, a.height(crossing), b.height(crossing));
    }
    out.setSize(emitted);
}

inline void intersectSmallFeatures(const FeatureView& a, const FeatureView& b, const Vec3& normal, double tolerance,
                            double minimumDepth, bool spanRegion, LiftedPoints& out) {
    Vec3 u, v;
    planeBasis(normal, u, v);
    intersectPieces(ProjectedPiece<SmallFeatureStorage>(a, u, v, normal),
                    ProjectedPiece<SmallFeatureStorage>(b, u, v, normal), 0, 0, u, v, normal, tolerance, minimumDepth,
                    spanRegion, false, out);
}


}  // namespace gdc::reference::stage3
