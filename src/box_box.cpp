// Two boxes through the general pipeline's steps (collide.cpp, collideGeneral), each in the box's
// closed form where the general one searches or allocates: the growth distance over the 15 axes
// without vector temporaries, the Gauss-map feature from the signs and sizes of the direction's
// components, faces and edges straight from the box's numbering and intersected in fixed arrays,
// and, for the depth confirmation, the exit of the ray along n through A − B from the 15 slabs of
// that zonotope instead of a GJK ray cast. Every decision is made on the same numbers the general
// pipeline compares (the same expressions on the same inputs), so both return the same manifold,
// bit for bit on box_box_test's poses; where the general pipeline takes a rare branch (no
// growth-distance normal, the overhang check, an empty intersection, a depth confirmation that
// may add a point) the pair goes to it whole.
#include "box_box.hpp"

#include "box_shape.hpp"
#include "collide_general.hpp"
#include "feature_intersection.hpp"
#include "gauss_map.hpp"
#include "growth_distance.hpp"
#include "minkowski.hpp"
#include "reduction.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

// Largest angular tolerance served (rad): below π/4 a box face's neighbours on the Gauss map (90°
// away) are more than twice the tolerance away, so no face has a cap (faceCap) and no direction
// is within the tolerance of two faces' normals on opposite sides of the box.
constexpr double kMaxAngularTolerance = 0.7;

FeatureGeometry generalGeometry(const BoxFeature& feature) {
    FeatureGeometry geometry;
    geometry.type = feature.type;
    for (int i = 0; i < feature.count; ++i) geometry.points.push_back(feature.points[i]);
    geometry.planeNormal = feature.planeNormal;
    geometry.planeOffset = feature.planeOffset;
    return geometry;
}

// collide.cpp's refineNormal, on the same numbers: the least overlap among the picked faces'
// normals (a box face's cap is the face alone); edge–edge, the edges' common perpendicular.
void refineNormal(Vec3& normal, double& normalOverlap, const BoxFeature& a, const BoxFeature& b,
                  const MinkowskiDifference& pair) {
    Vec3 best = normal;
    double bestOverlap = INFINITY, bestCos = -2;
    auto consider = [&](const Vec3& candidate) {
        const double overlap = candidate == normal ? normalOverlap : pair.overlapAlong(candidate);
        const double cosine = candidate.dot(normal);
        if (overlap < bestOverlap || (overlap == bestOverlap && cosine > bestCos))
            bestOverlap = overlap, bestCos = cosine, best = candidate;
    };
    if (a.type == FeatureType::Face) consider(a.planeNormal);
    if (b.type == FeatureType::Face) consider(-b.planeNormal);
    if (bestCos > -2) {
        normal = best, normalOverlap = bestOverlap;
        return;
    }
    if (a.type == FeatureType::Edge && b.type == FeatureType::Edge)
        edgeEdgeNormal(a.points[0], a.points[1], b.points[0], b.points[1], pair, normal, normalOverlap);
}

// feature_intersection.cpp's intersectFeatures for two box features (no caps), step for step on
// the same numbers — projection (a face made counter-clockwise), the feature's lifting along n, the
// 2-D intersection (Sutherland–Hodgman clip of the smaller feature by a face, or two segments),
// de-duplication, lift, boundary crossings — in fixed arrays instead of growing vectors.
constexpr int kMaxClipPoints = 16;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// A box feature projected onto the contact plane, with its height along n above each planar
// point q: constant + gradient·q (feature_intersection.cpp's LiftedHeight).
struct ProjectedFeature {
    Vec2 points[4];
    int count;
    double constant;
    Vec2 gradient = Vec2::Zero();
    double height(const Vec2& q) const { return constant + gradient.dot(q); }
};

ProjectedFeature project(const BoxFeature& feature, const Vec3& u, const Vec3& v, const Vec3& n) {
    ProjectedFeature out;
    out.count = feature.count;
    for (int i = 0; i < out.count; ++i) out.points[i] = Vec2(feature.points[i].dot(u), feature.points[i].dot(v));
    if (feature.type == FeatureType::Face) {
        double area = cross2(out.points[3], out.points[0]);
        for (int i = 0; i + 1 < 4; ++i) area += cross2(out.points[i], out.points[i + 1]);
        if (area < 0) std::swap(out.points[0], out.points[3]), std::swap(out.points[1], out.points[2]);
        // planeNormal·(q.x·u + q.y·v + h·n) = planeOffset, solved for h.
        const double normalAlongN = feature.planeNormal.dot(n);
        out.constant = feature.planeOffset / normalAlongN;
        out.gradient = -Vec2(feature.planeNormal.dot(u), feature.planeNormal.dot(v)) / normalAlongN;
    } else if (feature.type == FeatureType::Edge) {
        // The point of the edge whose projection is nearest q (affine in q).
        const Vec3 &p0 = feature.points[0], &p1 = feature.points[1];
        const Vec2 along = out.points[1] - out.points[0];
        const double alongSquared = along.squaredNorm();
        const double rise = (p1 - p0).dot(n);
        out.constant = p0.dot(n);
        if (alongSquared > 0) {
            out.gradient = along * (rise / alongSquared);
            out.constant -= out.gradient.dot(out.points[0]);
        }
    } else {
        out.constant = feature.points[0].dot(n);
    }
    return out;
}

// Clips `subject` (a point, a segment or a polygon) by the half-planes left of the CCW edges of
// the face `clip`, as clipByConvexPolygon does, two buffers in turn. Returns the size of the
// result in `region`, or −1 where the general clip must decide (a degenerate edge, or more points
// than the buffers hold — neither happens for a face within the angular tolerance of n).
int clipByFace(const ProjectedFeature& subject, const ProjectedFeature& clip, double tolerance,
               Vec2 (&buffers)[2][kMaxClipPoints], const Vec2*& region) {
    const Vec2* current = subject.points;
    int size = subject.count;
    for (int e = 0; e < clip.count && size > 0; ++e) {
        Vec2* output = buffers[e & 1];
        const Vec2& origin = clip.points[e];
        const Vec2 edge = clip.points[e + 1 == clip.count ? 0 : e + 1] - origin;
        const double length = edge.norm();
        if (!(length > 0)) return -1;
        const double slack = tolerance * length;
        int count = 0;
        const int n = size;
        const bool closed = n >= 3;
        double dp = cross2(edge, current[0] - origin);
        for (int i = 0; i < n; ++i) {
            const Vec2& p = current[i];
            if (count + 2 > kMaxClipPoints) return -1;
            if (dp >= -slack) output[count++] = p;
            if ((!closed && i + 1 == n) || n == 1) break;
            const Vec2& q = current[i + 1 == n ? 0 : i + 1];
            const double dq = cross2(edge, q - origin);
            if ((dp < -slack && dq > slack) || (dp > slack && dq < -slack))
                output[count++] = p + (q - p) * (dp / (dp - dq));
            dp = dq;
        }
        current = output, size = count;
    }
    region = current;
    return size;
}

// intersectSegments: the projected segments' crossing, or their overlap where they are parallel
// and on one line. Returns the number of points written to `out`.
int intersectSegments(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1, double tolerance,
                      Vec2* out) {
    const Vec2 da = a1 - a0, db = b1 - b0;
    const double denominator = cross2(da, db);
    const double la = da.norm(), lb = db.norm();
    int size = 0;
    if (std::abs(denominator) <= 1e-9 * la * lb) {
        if (std::abs(cross2(da, b0 - a0)) > tolerance * la) return 0;
        const double t0 = (b0 - a0).dot(da) / (la * la), t1 = (b1 - a0).dot(da) / (la * la);
        const double lo = std::max(0.0, std::min(t0, t1)), hi = std::min(1.0, std::max(t0, t1));
        if (hi < lo - tolerance / la) return 0;
        out[size++] = a0 + std::clamp(lo, 0.0, 1.0) * da;
        if ((hi - lo) * la > tolerance) out[size++] = a0 + std::clamp(hi, 0.0, 1.0) * da;
        return size;
    }
    const double s = cross2(b0 - a0, db) / denominator, t = cross2(b0 - a0, da) / denominator;
    if (s < -tolerance / la || s > 1 + tolerance / la || t < -tolerance / lb || t > 1 + tolerance / lb) return 0;
    out[size++] = a0 + std::clamp(s, 0.0, 1.0) * da;
    return size;
}

// intersectPieces' last steps: near-duplicate consecutive points dropped (edges crossing at a
// vertex), each point lifted onto both features, floating points dropped and, with `spanRegion`,
// the boundary crossings added.
void liftRegion(const Vec2* region, int size, const ProjectedFeature& a, const ProjectedFeature& b, const Vec3& u,
                const Vec3& v, const Vec3& normal, double tolerance, double minimumDepth, bool spanRegion,
                LiftedPoints& out) {
    const double toleranceSquared = tolerance * tolerance;
    Vec2 unique[kMaxClipPoints];
    int count = 0;
    for (int i = 0; i < size; ++i)
        if (count == 0 || (region[i] - unique[count - 1]).squaredNorm() > toleranceSquared) unique[count++] = region[i];
    while (count > 1 && (unique[0] - unique[count - 1]).squaredNorm() <= toleranceSquared) --count;

    auto emit = [&](const Vec2& q, double heightA, double heightB) {
        out.push_back({q.x() * u + q.y() * v + 0.5 * (heightA + heightB) * normal, heightA - heightB, q});
    };
    double heightsA[kMaxClipPoints], heightsB[kMaxClipPoints];
    for (int i = 0; i < count; ++i) heightsA[i] = a.height(unique[i]), heightsB[i] = b.height(unique[i]);
    const int edges = count >= 3 ? count : (count == 2 ? 1 : 0);  // a polygon closes; a segment has one edge
    const double keepDepth = minimumDepth - tolerance;
    for (int i = 0; i < count; ++i) {
        const double depth = heightsA[i] - heightsB[i];
        if (depth >= keepDepth) emit(unique[i], heightsA[i], heightsB[i]);
        if (!spanRegion || i >= edges) continue;
        const int next = i + 1 == count ? 0 : i + 1;
        const double t = contactBoundaryCrossing(depth, heightsA[next] - heightsB[next], minimumDepth, tolerance);
        if (std::isnan(t)) continue;
        const Vec2 crossing = unique[i] + t * (unique[next] - unique[i]);
        emit(crossing, a.height(crossing), b.height(crossing));
    }
}

// The intersection of A's and B's features, lifted; false where the general intersection must
// run instead (a vertex against an edge or a vertex, and the degenerate clips above).
bool intersectBoxFeatures(const BoxFeature& featureA, const BoxFeature& featureB, const Vec3& normal,
                          double tolerance, double minimumDepth, bool spanRegion, LiftedPoints& out) {
    if (featureA.type != FeatureType::Face && featureB.type != FeatureType::Face &&
        !(featureA.type == FeatureType::Edge && featureB.type == FeatureType::Edge))
        return false;
    Vec3 u, v;
    planeBasis(normal, u, v);
    const ProjectedFeature a = project(featureA, u, v, normal), b = project(featureB, u, v, normal);
    Vec2 buffers[2][kMaxClipPoints];
    const Vec2* region = buffers[0];
    int size;
    if (a.count == 2 && b.count == 2) {
        size = intersectSegments(a.points[0], a.points[1], b.points[0], b.points[1], tolerance, buffers[0]);
    } else {
        // intersect2d: the feature with fewer points is clipped by the other (B's when as many).
        const bool aClips = a.count >= b.count;
        size = clipByFace(aClips ? b : a, aClips ? a : b, tolerance, buffers, region);
        if (size < 0) return false;
    }
    liftRegion(region, size, a, b, u, v, normal, tolerance, minimumDepth, spanRegion, out);
    return true;
}

// Whether the ray along n leaves A − B (B at `bInA`, all in A's frame) no later than `limit` plus
// what a ray cast stopping within `castTolerance` of A − B can add: then the general pipeline's
// depth confirmation cannot add a point. A − B is the zonotope spanned by the boxes' half-edges,
// the intersection of the slabs |m·x + m·p| ≤ r(m) over its facet normals m — the 3 + 3 face
// normals and the 9 edge cross products e_i × (column j of R), each of length ≤ 1 — with
// r(m) = halfA·|m| + halfB·|Rᵀm| and p B's centre (the separating-axis radii of Gottschalk's OBB
// test). Along the line t·n the slab bounds t by (r − s·m·p)/|m·n| (s the sign of m·n), so one
// slab with r − s·m·p + castTolerance ≤ limit·|m·n| settles it: the line leaves (or misses) the
// slab by then, and a point within castTolerance of A − B is within castTolerance/|m·n| (|m| ≤ 1)
// of the slab along the line. The edge slabs come first: an overhanging face's deepest point is
// where an edge of one box crosses an edge of the other.
bool exitsBy(const Vec3& halfA, const Vec3& halfB, const Pose& bInA, const Vec3& n, double limit,
             double castTolerance) {
    const Mat3& r = bInA.rotation;
    const Vec3& p = bInA.position;
    const Mat3 absR = r.cwiseAbs();
    auto settles = [&](double radius, double mp, double mn) {
        return radius - (mn < 0 ? -mp : mp) + castTolerance <= limit * std::abs(mn);
    };
    for (int i = 0; i < 3; ++i) {
        const int i1 = i == 2 ? 0 : i + 1, i2 = i == 0 ? 2 : i - 1;
        for (int j = 0; j < 3; ++j) {
            const int j1 = j == 2 ? 0 : j + 1, j2 = j == 0 ? 2 : j - 1;
            // m = e_i × c_j has m[i1] = −R(i2, j), m[i2] = R(i1, j); Rᵀm = (row i) × e_j.
            const double mn = r(i1, j) * n[i2] - r(i2, j) * n[i1];
            const double mp = r(i1, j) * p[i2] - r(i2, j) * p[i1];
            const double radius = halfA[i1] * absR(i2, j) + halfA[i2] * absR(i1, j) + halfB[j1] * absR(i, j2) +
                                  halfB[j2] * absR(i, j1);
            if (settles(radius, mp, mn)) return true;
        }
    }
    for (int i = 0; i < 3; ++i)
        if (settles(halfA[i] + halfB.dot(absR.row(i).transpose()), p[i], n[i])) return true;
    for (int j = 0; j < 3; ++j)
        if (settles(halfA.dot(absR.col(j)) + halfB[j], r.col(j).dot(p), r.col(j).dot(n))) return true;
    return false;
}

}  // namespace

// growth_distance.cpp's boxGrowthDistance (the closed-form growth distance of two boxes), on the
// same numbers, without its vector temporaries: the facet normals e_i × (column j of R) and
// (row i of R) × e_j each have one zero component, so their cross products, norms and dot
// products are written out on the other two — the same products and sums, the zero terms (exact)
// left out. Only what collide needs: whether it is valid, the normal, the face-overlap bound.
// box_box_test checks it equal, bit for bit, to growthDistance on random poses.
BoxGrowth boxGrowth(const Vec3& halfA, const Vec3& halfB, const Mat3& rotationB, const Vec3& centreOffset,
                    double separation, double size) {
    BoxGrowth result;
    if (!(separation > 1e-12 * size)) return result;  // coincident contraction points
    const Vec3 w = centreOffset / separation;
    const Mat3 absoluteR = rotationB.cwiseAbs();
    double exitDistance = INFINITY;
    Vec3 tiedNormals = Vec3::Zero();
    // `normal()` makes the axis's unit normal, only when it becomes (or ties) the exit facet.
    auto consider = [&](double along, double supportValue, auto&& normal) {
        if (std::abs(along) < 1e-12) return;
        const double distance = supportValue / std::abs(along);
        if (distance < exitDistance * (1 - 1e-12)) {
            const Vec3 n = normal();
            const Vec3 outward = along > 0 ? n : -n;
            if (distance > exitDistance * (1 - 2e-12)) tiedNormals += outward;
            else tiedNormals = outward;
            exitDistance = std::min(distance, exitDistance);
        } else if (distance <= exitDistance * (1 + 1e-12)) {
            const Vec3 n = normal();
            tiedNormals += along > 0 ? n : -n;
        }
    };
    double faceOverlap = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const double supportValue = halfA[i] + halfB.dot(absoluteR.row(i).transpose());
        faceOverlap = std::min(faceOverlap, supportValue - std::abs(centreOffset[i]));
        consider(w[i], supportValue, [&] { return Vec3(Vec3::Unit(i)); });
    }
    for (int j = 0; j < 3; ++j) {
        const Vec3 n = rotationB.col(j);
        const double supportValue = halfA.dot(absoluteR.col(j)) + halfB[j];
        faceOverlap = std::min(faceOverlap, supportValue - std::abs(n.dot(centreOffset)));
        consider(n.dot(w), supportValue, [&] { return n; });
    }
    for (int i = 0; i < 3; ++i) {
        // e_i × c has components −c[i2] at i1 and c[i1] at i2 ((i, i1, i2) cyclic).
        const int i1 = i == 2 ? 0 : i + 1, i2 = i == 0 ? 2 : i - 1;
        for (int j = 0; j < 3; ++j) {
            const int j1 = j == 2 ? 0 : j + 1, j2 = j == 0 ? 2 : j - 1;
            const double n1 = -rotationB(i2, j), n2 = rotationB(i1, j);
            const double length = std::sqrt(n1 * n1 + n2 * n2);
            if (!(length > 1e-9)) continue;  // parallel edges: covered by the face normals
            // (row i) × e_j has components row[j2] at j1 and −row[j1] at j2.
            const double supportValue = (halfA[i1] * std::abs(n1) + halfA[i2] * std::abs(n2) +
                                         (halfB[j1] * absoluteR(i, j2) + halfB[j2] * absoluteR(i, j1))) /
                                        length;
            const double u1 = n1 / length, u2 = n2 / length;
            consider(u1 * w[i1] + u2 * w[i2], supportValue, [&] {
                Vec3 n = Vec3::Zero();
                n[i1] = u1, n[i2] = u2;
                return n;
            });
        }
    }
    result.valid = std::isfinite(exitDistance) && exitDistance > 0 && tiedNormals.norm() > 1e-6;
    result.normal = tiedNormals.normalized();
    result.faceOverlapLowerBound = faceOverlap;
    return result;
}

bool boxBoxApplies(const Polytope& a, const Polytope& b, const Settings& settings) {
    return a.isBox() && b.isBox() && settings.normalMethod == NormalMethod::GrowthDistance &&
           settings.angularTolerance >= 0 && settings.angularTolerance <= kMaxAngularTolerance;
}

void collideBoxBoxInto(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings, Manifold& manifold) {
    auto general = [&] { manifold.assignUsed(collideGeneral(a, poseA, b, poseB, settings)); };
    if (!poseA.isFinite() || !poseB.isFinite()) return general();  // it says what is wrong
    // The empty answer a new Manifold is (the points beyond pointCount are never read).
    manifold.normal = Vec3::UnitZ();
    manifold.pointCount = 0;
    manifold.featureA = Feature{};
    manifold.featureB = Feature{};
    const Pose bInA = poseA.relative(poseB);
    const MinkowskiDifference pair(a, b, bInA, settings.bruteForceSupportLimit);
    const double size = a.radius() + b.radius();
    const double tolerance = 1e-9 * size;
    const Vec3 centreOffset = pair.centreB - pair.centreA;
    const double centreDistance = centreOffset.norm();
    if (separatedByEarlyOut(pair, centreOffset, centreDistance, size, settings.margin, tolerance)) return;

    // Stage 1: the closed-form growth distance of two boxes.
    const BoxGrowth growth =
        boxGrowth(a.boxHalfExtents(), b.boxHalfExtents(), bInA.rotation, centreOffset, centreDistance, size);
    if (!growth.valid) return general();  // coincident centres: the general fallback normal
    Vec3 normal = growth.normal;
    double normalOverlap = pair.overlapAlong(normal);
    if (normalOverlap < -settings.margin - tolerance) return;
    // The overhang check can only act where the box pair's bound leaves room for a face of less
    // than half the normal's overlap (deep overlap): then the general pipeline runs it.
    if (!(growth.faceOverlapLowerBound >= kClearlySmallerOverlap * normalOverlap + tolerance)) return general();

    // Stage 2: one feature per box (B's with −n in its own frame).
    LazyAngularTolerance angularTolerance(settings.angularTolerance);
    const Vec3 directionB = bInA.rotation.transpose() * -normal;
    manifold.featureA = selectBoxFeature(normal, boxSupport(normal), angularTolerance);
    manifold.featureB = selectBoxFeature(directionB, boxSupport(directionB), angularTolerance);
    const BoxFeature featureA = boxFeature(a, manifold.featureA, nullptr);
    const BoxFeature featureB = boxFeature(b, manifold.featureB, &bInA);
    refineNormal(normal, normalOverlap, featureA, featureB, pair);

    // Stage 3: the intersection in the contact plane (the general one for a vertex against an
    // edge or a vertex).
    LiftedPoints kept;
    if (!intersectBoxFeatures(featureA, featureB, normal, tolerance, -settings.margin, settings.spanContactRegion,
                              kept)) {
        kept.clear();
        kept = intersectFeatures(generalGeometry(featureA), generalGeometry(featureB), normal, tolerance,
                                 -settings.margin, settings.spanContactRegion);
    }
    if (kept.empty()) return general();  // its fallbacks: the ray cast's witnesses or the supports' gap
    double deepest = -INFINITY;
    for (const LiftedPoint& point : kept) deepest = std::max(deepest, point.depth);
    // The depth confirmation: the general pipeline casts a ray along n through A − B where the
    // lifted points fall short of the supports' overlap, and adds a point where the cast's exit is
    // deeper than the deepest lifted point by more than 1 % of it. Where one box's face, edge or
    // corner overhangs the other's feature the exit is the deepest lifted point itself (the region
    // of overlap ends where the features' edges cross, and those crossings are lifted points), so
    // the exact exit, within rounding of the deepest point, settles it — leaving the whole slack to
    // the cast's own inaccuracy (it stops outside A − B, within its tolerance). Otherwise (the
    // overlap reaches beyond the features, 22 of the 105000 poses of box_box_test) the general
    // pipeline runs and decides.
    if (deepest < normalOverlap - tolerance &&
        !exitsBy(a.boxHalfExtents(), b.boxHalfExtents(), bInA, normal, deepest + 2 * tolerance,
                 2 * settings.rayCastTolerance * size))
        return general();
    const Vec3 centroids[2] = {pair.centreA, pair.centreB};
    emitManifold(kept, normal, poseA, settings, tolerance, centroids, 2, manifold);
}

Manifold collideBoxBox(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB,
                       const Settings& settings) {
    Manifold manifold;
    collideBoxBoxInto(a, poseA, b, poseB, settings, manifold);
    return manifold;
}

}  // namespace gdc::detail
