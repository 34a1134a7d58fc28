#include "contact/feature_intersection.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

using Polygon2 = SmallVector<Vec2, 16>;

// Stage 3's storage, chosen by the features: growable vectors (SmallVector, inline for the common
// sizes, spilling for large faces and caps), or — for features of at most four points without
// pieces, a box's — fixed arrays of the worst case, with no capacity check and no spill.
// One algorithm serves both: the functions below are templates on the storage.

// SmallVector's interface (the part stage 3 uses) over a fixed array of N: the caller guarantees
// that no count exceeds N.
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

struct GrowableStorage {
    using Polygon = Polygon2;
};

// Features of at most four points: a clip by at most four sides at most doubles the subject's ≤ 4
// points per side, so no region exceeds 64 points.
struct SmallFeatureStorage {
    static constexpr int kMaxRegion = 64;
    using Polygon = FixedVector<Vec2, kMaxRegion>;
};

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The feature's points in the plane (u, v), a face's loop made counter-clockwise (B's face arrives
// clockwise), written into the empty `out`; returns its points. Here and below the loops write through a plain pointer
// with the count in a local (SmallVector::reserve): push_back cost the box–box path 12 %.
template <class Polygon>
[[gnu::always_inline]] inline const Vec2* project(const FeatureView& feature, const Vec3& u, const Vec3& v,
                                                  Polygon& out) {
    const int n = feature.count;
    Vec2* points = out.reserve(n);
    // Both coordinates at once: (p·u, p·v) = p.x·(u.x, v.x) + p.y·(u.y, v.y) + p.z·(u.z, v.z), each
    // coordinate the dot product's own sum in its own order ((x + y) + z), so the same bits in
    // half the instructions.
    const Vec2 alongX(u.x(), v.x()), alongY(u.y(), v.y()), alongZ(u.z(), v.z());
    for (int i = 0; i < n; ++i) {
        const Vec3& p = feature.points[i];
        points[i] = p.x() * alongX + p.y() * alongY + p.z() * alongZ;
    }
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
// With kDropRepeats, the last edge of `clip` writes a point only where it is more than `tolerance`
// from the point written before it — intersectPieces' pass over the region, made as the region is
// written (the same points kept, one loop less) — and `repeatsDropped` says whether it did (the last
// edge ran); the caller makes the pass itself otherwise.
template <bool kDropRepeats = false, class Polygon>
[[gnu::always_inline]] inline const Polygon& clipByConvexPolygon(const Polygon& subject, const Polygon& clip,
                                                                 double tolerance, Polygon (&buffers)[2],
                                                                 bool* repeatsDropped = nullptr) {
    const Polygon* input = &subject;
    const Vec2* corners = clip.data();
    const std::size_t sides = clip.size();
    int written = 0;  // buffers filled so far: the next one is never the one being read
    const double toleranceSquared = tolerance * tolerance;
    if constexpr (kDropRepeats) *repeatsDropped = false;
    for (std::size_t e = 0; e < sides && !input->empty(); ++e) {
        const Vec2* current = input->data();
        const std::size_t n = input->size();
        const Vec2& a = corners[e];
        const Vec2 edge = corners[e + 1 == sides ? 0 : e + 1] - a;
        const double length = edge.norm();
        if (!(length > 0)) continue;  // a repeated corner: no half-plane
        Polygon& next = buffers[written++ & 1];
        next.clear();
        Vec2* const output = next.reserve(2 * n);  // each point adds itself and at most one crossing
        Vec2* end = output;  // past the last point written
        // Signed distance scaled by the edge length (> 0 inside); the slack is scaled to match.
        const double slack = tolerance * length;
        auto distance = [&](const Vec2& p) { return cross2(edge, p - a); };
        // Each point's distance is computed once and carried to the next step as `dp`; a closed
        // polygon's last step reuses the first point's (the same value the wrap recomputed).
        const double first = distance(current[0]);
        double dp = first;
        // A point is kept or dropped, and an edge crosses from outside in or from inside out: one
        // test of p's side decides which crossing to look for (a NaN takes neither, as both
        // conditions written together did).
        auto cut = [&](auto&& write) __attribute__((always_inline)) {
            auto step = [&](const Vec2& p, const Vec2& q, double dq) __attribute__((always_inline)) {
                if (dp >= -slack) {
                    write(p);
                    if (dp > slack && dq < -slack) write(p + (q - p) * (dp / (dp - dq)));
                } else if (dp < -slack && dq > slack) {
                    write(p + (q - p) * (dp / (dp - dq)));
                }
                dp = dq;
            };
            for (std::size_t i = 0; i + 1 < n; ++i) step(current[i], current[i + 1], distance(current[i + 1]));
            if (n >= 3) {
                step(current[n - 1], current[0], first);
            } else if (dp >= -slack) {  // a segment's or a point's last point: no closing edge
                write(current[n - 1]);
            }
        };
        if (kDropRepeats && e + 1 == sides) {
            cut([&](const Vec2& p) {
                if (end == output || (p - end[-1]).squaredNorm() > toleranceSquared) *end++ = p;
            });
            if constexpr (kDropRepeats) *repeatsDropped = true;
        } else {
            cut([&](const Vec2& p) { *end++ = p; });
        }
        next.setSize(static_cast<std::size_t>(end - output));
        input = &next;
    }
    return *input;
}

// The segments' crossing, or their overlap where they are parallel and on one line, into `out`.
template <class Polygon>
void intersectSegments(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1, double tolerance,
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

bool pointOnSegment(const Vec2& p, const Vec2& a, const Vec2& b, double tolerance) {
    Vec2 d = b - a;
    double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (a + t * d - p).norm() <= tolerance;
}

// The intersection of two projected features (the one with more points clips the other; B's
// when as many), in the caller's buffers; returns the region.
// `repeatsDropped`: whether the region's near-repeated consecutive points were dropped on the way
// (clipByConvexPolygon's kDropRepeats).
template <class Polygon>
[[gnu::always_inline]] inline const Polygon& intersect2d(const Polygon& first, const Polygon& second,
                                                         double tolerance, Polygon (&buffers)[2],
                                                         bool& repeatsDropped) {
    const bool firstHasMore = first.size() >= second.size();
    const Polygon& a = firstHasMore ? first : second;  // a has at least as many points
    const Polygon& b = firstHasMore ? second : first;
    if (a.size() >= 3) return clipByConvexPolygon<true>(b, a, tolerance, buffers, &repeatsDropped);
    repeatsDropped = false;
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

}  // namespace

double contactBoundaryCrossing(double from, double to, double contactDepth, double tolerance) {
    const double gap = contactDepth - tolerance;
    const bool leaves = from >= contactDepth && to < gap;
    const bool enters = from < gap && to >= contactDepth;
    return leaves || enters ? (from - contactDepth) / (from - to) : NAN;
}

namespace {

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
    bool repeatsDropped;
    const Polygon& region = intersect2d(a.polygon, b.polygon, tolerance, buffers, repeatsDropped);
    // Drop near-duplicate consecutive points produced where edges cross at a vertex (the clip's
    // last edge did, where it ran).
    const double toleranceSquared = tolerance * tolerance;
    Polygon uniqueStorage;
    const Vec2* unique = region.data();
    std::size_t count = region.size();
    if (!repeatsDropped) {
        Vec2* kept = uniqueStorage.reserve(region.size());
        count = 0;
        for (const Vec2& p : region)
            if (count == 0 || (p - kept[count - 1]).squaredNorm() > toleranceSquared) kept[count++] = p;
        unique = kept;
    }
    while (count > 1 && (unique[0] - unique[count - 1]).squaredNorm() <= toleranceSquared) --count;

    // At most two points per vertex of the region: itself and a boundary crossing.
    LiftedPoint* const points = out.reserve(out.size() + 2 * count);
    LiftedPoint* end = points + out.size();  // past the last point emitted
    auto emit = [&](const Vec2& q, double heightA, double heightB) {
        if (merge) {
            bool known = false;
            for (const LiftedPoint* point = points; point != end; ++point)
                known = known || (point->planar - q).squaredNorm() <= toleranceSquared;
            if (known) return;
        }
        *end++ = {q.x() * u + q.y() * v + 0.5 * (heightA + heightB) * normal, heightA - heightB, q, pieceA, pieceB};
    };
    // With `spanRegion`: the depth is affine along every edge of the region (both features are flat
    // there), so where an edge runs from contact into a clear gap, the contact region ends where
    // the depth crosses `minimumDepth`, and that point is a contact too. Without it the floating
    // vertices are simply dropped, which shrinks a slightly tilted face's support polygon to its
    // deepest corners (a cube resting 1° off flat keeps about half of its true contact area). An
    // edge whose far end floats by less than the tolerance adds nothing: its end is kept, and a
    // crossing there would be rounding noise.
    // One pass: each vertex's heights are made once, as the next vertex's of the step before (the
    // first vertex's kept for the closing edge), and read where they are made — no arrays of them.
    const std::size_t edges = count >= 3 ? count : (count == 2 ? 1 : 0);  // a polygon closes; a segment has one edge
    const double keepDepth = minimumDepth - tolerance;
    if (count > 0) {
        const double firstA = a.height(unique[0]), firstB = b.height(unique[0]);
        double heightA = firstA, heightB = firstB;
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t next = i + 1 == count ? 0 : i + 1;
            const double nextA = next == 0 ? firstA : a.height(unique[next]);
            const double nextB = next == 0 ? firstB : b.height(unique[next]);
            const double depth = heightA - heightB;
            if (depth >= keepDepth) emit(unique[i], heightA, heightB);
            if (spanRegion && i < edges) {
                const double t = contactBoundaryCrossing(depth, nextA - nextB, minimumDepth, tolerance);
                if (!std::isnan(t)) {
                    const Vec2 crossing = unique[i] + t * (unique[next] - unique[i]);
                    emit(crossing, a.height(crossing), b.height(crossing));
                }
            }
            heightA = nextA, heightB = nextB;
        }
    }
    out.setSize(static_cast<std::size_t>(end - points));
}

}  // namespace

void intersectFeatures(const FeatureView& a, const FeatureView& b, const Vec3& normal, double tolerance,
                       double minimumDepth, bool spanRegion, LiftedPoints& out) {
    Vec3 u, v;
    planeBasis(normal, u, v);
    if (a.pieceCount == 0 && b.pieceCount == 0) {
        intersectPieces(ProjectedPiece<GrowableStorage>(a, u, v, normal), ProjectedPiece<GrowableStorage>(b, u, v, normal),
                        0, 0, u, v, normal, tolerance, minimumDepth, spanRegion, false, out);
        return;
    }
    // A cap bends at its inner edges, so its outline alone would miss the deepest point (an inner
    // vertex of a tessellated sphere) and lift points onto the wrong face where the cap's
    // projection is not convex. Face by face, every vertex of the arrangement is found — outline
    // corners, inner vertices, crossings of inner edges — and lifted onto the faces it lies on.
    // Points shared by neighbouring faces are kept once. Each face is projected once, and pairs
    // whose projections' bounds do not meet are skipped.
    struct Bounded {
        ProjectedPiece<GrowableStorage> piece;
        Vec2 lower, upper;
        Bounded(const FeatureView& feature, const Vec3& u, const Vec3& v, const Vec3& n) : piece(feature, u, v, n) {
            lower = upper = piece.polygon[0];
            for (const Vec2& p : piece.polygon) lower = lower.cwiseMin(p), upper = upper.cwiseMax(p);
        }
        bool meets(const Bounded& other, double tolerance) const {
            return (lower.array() <= other.upper.array() + tolerance).all() &&
                   (other.lower.array() <= upper.array() + tolerance).all();
        }
    };
    auto project = [&](const FeatureView& feature, std::vector<Bounded>& pieces) {
        if (feature.pieceCount == 0) {
            pieces.emplace_back(feature, u, v, normal);
            return;
        }
        pieces.reserve(feature.pieceCount);
        for (int i = 0; i < feature.pieceCount; ++i) pieces.emplace_back(view(feature.pieces[i]), u, v, normal);
    };
    std::vector<Bounded> piecesA, piecesB;
    project(a, piecesA);
    project(b, piecesB);
    for (std::size_t i = 0; i < piecesA.size(); ++i)
        for (std::size_t j = 0; j < piecesB.size(); ++j)
            if (piecesA[i].meets(piecesB[j], tolerance))
                intersectPieces(piecesA[i].piece, piecesB[j].piece, static_cast<int>(i), static_cast<int>(j), u, v,
                                normal, tolerance, minimumDepth, spanRegion, true, out);
}

// The same intersection for features of at most four points without pieces (a box's vertex, edge
// or face): the same algorithm on fixed arrays (SmallFeatureStorage), so the same points to the bit.
// The bits matter beyond rounding: the centroid rule's choice among the equal-area triangles of a
// rectangular region is decided by the clip's last bits (docs/algorithm.md).
// tests/small_intersection_test.cpp checks both on 10^5 poses of each kind of box pair.
void intersectSmallFeatures(const FeatureView& a, const FeatureView& b, const Vec3& normal, double tolerance,
                            double minimumDepth, bool spanRegion, LiftedPoints& out) {
    Vec3 u, v;
    planeBasis(normal, u, v);
    intersectPieces(ProjectedPiece<SmallFeatureStorage>(a, u, v, normal),
                    ProjectedPiece<SmallFeatureStorage>(b, u, v, normal), 0, 0, u, v, normal, tolerance, minimumDepth,
                    spanRegion, false, out);
}

SmallVector<Vec2, 16> clipConvexPolygon(const Vec2* subject, int n, const Vec2* clip, int sides, double tolerance) {
    Polygon2 subjectPolygon, clipPolygon, buffers[2];
    for (int i = 0; i < n; ++i) subjectPolygon.push_back(subject[i]);
    for (int i = 0; i < sides; ++i) clipPolygon.push_back(clip[i]);
    return clipByConvexPolygon(subjectPolygon, clipPolygon, tolerance, buffers);
}

LiftedPoints intersectFeatures(const FeatureGeometry& a, const FeatureGeometry& b, const Vec3& normal,
                               double tolerance, double minimumDepth, bool spanRegion) {
    LiftedPoints all;
    intersectFeatures(view(a), view(b), normal, tolerance, minimumDepth, spanRegion, all);
    return all;
}

}  // namespace gdc::detail
