#include "contact/disc_intersection.hpp"

#include <algorithm>
#include <cmath>

namespace gdc::detail {
namespace {

constexpr double kTwoPi = 6.283185307179586;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

struct PlaneFrame {
    Vec3 u, v, n;
    Vec2 project(const Vec3& p) const { return {p.dot(u), p.dot(v)}; }
    Vec3 place(const Vec2& q, double height) const { return q.x() * u + q.y() * v + height * n; }
};

// The disc's unit directions in its plane for the rim c + r(cos t·dir1 + sin t·dir2) seen along n:
// dir2 = axis × n ⟂ n, dir1 = dir2 × axis with dir1·n = |axis × n| ≥ 0, so t = 0 is the rim's
// deepest point along n. Where the disc lies flat to n (no deepest point), dir1 is its reference
// direction, fixed in the cylinder.
void rimDirections(const Disc& disc, const Vec3& n, Vec3& dir1, Vec3& dir2) {
    dir2 = disc.axis.cross(n);
    const double length = dir2.norm();
    if (length > 1e-12) {
        dir2 /= length;
        dir1 = dir2.cross(disc.axis);
    } else {
        dir1 = (disc.reference - disc.reference.dot(disc.axis) * disc.axis).normalized();
        dir2 = disc.axis.cross(dir1);
    }
}

// emit(cos t, sin t) at t = 2πk/count, k = 0 … count − 1: a regular polygon by turning (cos, sin)
// one step at a time, one sincos for all of it.
template <class Emit>
void regularPolygon(int count, Emit emit) {
    const double stepCos = std::cos(kTwoPi / count), stepSin = std::sin(kTwoPi / count);
    double c = 1, s = 0;
    for (int k = 0; k < count; ++k) {
        emit(c, s);
        const double next = c * stepCos - s * stepSin;
        s = s * stepCos + c * stepSin, c = next;
    }
}

// A disc seen along n: its rim c + cos t·e1 + sin t·e2 in the plane, e1 ⟂ e2 (the images of the
// disc's radius along dir1, in its plane and rising along n, and along dir2 ⟂ n). Normalised
// coordinates map the ellipse onto the unit circle.
struct Rim {
    Vec2 centre, e1, e2;
    double inverse1, inverse2;  // 1/|e1|², 1/|e2|²
    Vec3 discCentre, axis;

    Rim(const Disc& disc, const PlaneFrame& frame) : discCentre(disc.centre), axis(disc.axis) {
        Vec3 dir1, dir2;
        rimDirections(disc, frame.n, dir1, dir2);
        centre = frame.project(disc.centre);
        e1 = disc.radius * frame.project(dir1);
        e2 = disc.radius * frame.project(dir2);
        inverse1 = 1 / e1.squaredNorm();
        inverse2 = 1 / e2.squaredNorm();
    }
    Vec2 at(double t) const { return centre + std::cos(t) * e1 + std::sin(t) * e2; }
    Vec2 normalised(const Vec2& p) const {
        const Vec2 d = p - centre;
        return {d.dot(e1) * inverse1, d.dot(e2) * inverse2};
    }
    bool contains(const Vec2& p, double slack) const { return normalised(p).norm() <= 1 + slack; }
    double angleOf(const Vec2& p) const {
        const Vec2 q = normalised(p);
        return std::atan2(q.y(), q.x());
    }
    // Height along n of the disc's plane over the planar point q.
    double height(const Vec2& q, const PlaneFrame& frame) const {
        return (discCentre.dot(axis) - frame.place(q, 0).dot(axis)) / frame.n.dot(axis);
    }
};

// A polygon, a segment or a point (a feature without its pieces, or one piece) in the plane: its
// points counter-clockwise, and its height along n over a planar point (affine: a face's plane, an
// edge's line, a vertex's constant).
struct Flat {
    SmallVector<Vec2, 16> points;
    FeatureType type;
    Vec3 planeNormal;
    double planeOffset;
    Vec3 p0, p1;

    Flat(const FeatureGeometry& feature, const PlaneFrame& frame)
        : type(feature.type), planeNormal(feature.planeNormal), planeOffset(feature.planeOffset) {
        for (const Vec3& p : feature.points) points.push_back(frame.project(p));
        p0 = feature.points[0];
        p1 = feature.points[feature.points.size() > 1 ? 1 : 0];
        const std::size_t n = points.size();
        if (n >= 3) {
            double area = 0;
            for (std::size_t i = 0; i < n; ++i) area += cross2(points[i], points[(i + 1) % n]);
            if (area < 0) std::reverse(points.begin(), points.end());
        }
    }
    double height(const Vec2& q, const PlaneFrame& frame) const {
        if (type == FeatureType::Face)
            return (planeOffset - frame.place(q, 0).dot(planeNormal)) / planeNormal.dot(frame.n);
        if (type == FeatureType::Edge) {
            const Vec2 a = frame.project(p0), along = frame.project(p1) - a;
            const double squared = along.squaredNorm();
            const double t = squared > 0 ? std::clamp((q - a).dot(along) / squared, 0.0, 1.0) : 0.0;
            return (p0 + t * (p1 - p0)).dot(frame.n);
        }
        return p0.dot(frame.n);
    }
    // Whether q is in the polygon (a segment or a point: within `slack` of it).
    bool contains(const Vec2& q, double slack) const {
        const std::size_t n = points.size();
        if (n >= 3) {
            for (std::size_t i = 0; i < n; ++i) {
                const Vec2 edge = points[(i + 1) % n] - points[i];
                if (cross2(edge, q - points[i]) < -slack * edge.norm()) return false;
            }
            return true;
        }
        if (n == 2) {
            const Vec2 along = points[1] - points[0];
            const double squared = along.squaredNorm();
            const double t = squared > 0 ? std::clamp((q - points[0]).dot(along) / squared, 0.0, 1.0) : 0.0;
            return (points[0] + t * along - q).norm() <= slack;
        }
        return (points[0] - q).norm() <= slack;
    }
};

// Points evenly on the rim from angle `from` to `to` (to > from), ends excluded, at most `step` apart
// and at least `least` pieces (a short arc still gets as many points as the budget can keep).
void arcPoints(const Rim& rim, double from, double to, double step, int least, SmallVector<Vec2, 32>& out) {
    const int pieces = std::max(least, static_cast<int>(std::ceil((to - from) / step - 1e-9)));
    for (int j = 1; j < pieces; ++j) out.push_back(rim.at(from + (to - from) * j / pieces));
}

// How the points on a rim are spread: at most `step` apart on an arc (and an arc in at least
// whole − 1 pieces), `whole` of them on a whole rim.
struct RimSpacing {
    double step;
    int whole;
};

// The arcs of a rim between its crossings `angles` (any order) whose middle lies inside `inside`;
// with no crossing the whole rim if its point at t = 0 is inside.
template <class Inside>
void insideArcs(const Rim& rim, SmallVector<double, 16>& angles, const RimSpacing& spacing, Inside inside,
                SmallVector<Vec2, 32>& out) {
    const double step = spacing.step;
    if (angles.empty()) {
        if (!inside(rim.at(0))) return;
        regularPolygon(spacing.whole, [&](double c, double s) { out.push_back(rim.centre + c * rim.e1 + s * rim.e2); });
        return;
    }
    std::sort(angles.begin(), angles.end());
    const std::size_t n = angles.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double from = angles[i];
        const double to = i + 1 < n ? angles[i + 1] : angles[0] + kTwoPi;
        if (!(to - from > 1e-12)) continue;
        if (inside(rim.at(0.5 * (from + to)))) arcPoints(rim, from, to, step, spacing.whole - 1, out);
    }
}

// The disc ∩ a polygon, a segment or a point, as planar points.
// `angles` holds the rim's other arc ends already (its depth crossings), `keep` what else an arc's
// points must satisfy (to be in contact), both for spanContactRegion.
template <class Keep>
void discWithFlat(const Rim& rim, const Flat& flat, double slack, double normalisedSlack, const RimSpacing& step,
                  SmallVector<double, 16>& angles, Keep keep, SmallVector<Vec2, 32>& out) {
    const std::size_t n = flat.points.size();
    for (const Vec2& p : flat.points)
        if (rim.contains(p, normalisedSlack)) out.push_back(p);
    if (n == 1) return;
    const std::size_t edges = n == 2 ? 1 : n;
    for (std::size_t i = 0; i < edges; ++i) {
        const Vec2 &p = flat.points[i], &q = flat.points[(i + 1) % n];
        const Vec2 from = rim.normalised(p), along = rim.normalised(q) - from;
        const double a = along.squaredNorm(), b = 2 * from.dot(along), c = from.squaredNorm() - 1;
        const double discriminant = b * b - 4 * a * c;
        if (!(a > 0) || discriminant < 0) continue;
        const double root = std::sqrt(discriminant);
        for (const double s : {(-b - root) / (2 * a), (-b + root) / (2 * a)}) {
            if (s < 0 || s > 1) continue;
            const Vec2 crossing = p + s * (q - p);
            out.push_back(crossing);
            const Vec2 onCircle = from + s * along;
            angles.push_back(std::atan2(onCircle.y(), onCircle.x()));
        }
    }
    if (n < 3) return;  // a segment has no inside for an arc to run through
    insideArcs(rim, angles, step, [&](const Vec2& q) { return flat.contains(q, slack) && keep(q); }, out);
}

// Two discs' lens: the crossings of their rims (roots of |rimA-normalised(rimB(s))|² − 1, found by
// bracketing and bisection: at most four), and each rim's arcs inside the other.
template <class Keep>
void discWithDisc(const Rim& rimA, const Rim& rimB, double slackA, double slackB, const RimSpacing& step,
                  SmallVector<double, 16>& anglesA, SmallVector<double, 16>& anglesB, Keep keep,
                  SmallVector<Vec2, 32>& out) {
    constexpr int kSamples = 64;
    // How far outside rim A rim B's point at s is (|normalised|² − 1), and its derivative, for
    // Newton's steps inside a bracket.
    auto outsideWithSlope = [&](double s, double& slope) {
        const double c = std::cos(s), si = std::sin(s);
        const Vec2 q = rimA.normalised(rimB.centre + c * rimB.e1 + si * rimB.e2);
        const Vec2 along = rimA.normalised(rimA.centre - si * rimB.e1 + c * rimB.e2);  // d/ds, linear part
        slope = 2 * q.dot(along);
        return q.squaredNorm() - 1;
    };
    const std::size_t givenA = anglesA.size(), givenB = anglesB.size();
    // The samples at 2πk/kSamples by turning (cos, sin) one step at a time (a rotation each, not a
    // sincos): only the signs bracket the roots, which the steps below then solve exactly.
    constexpr double kStepCos = 0.99518472667219688624, kStepSin = 0.098017140329560601994;  // of 2π/64
    static_assert(kSamples == 64, "kStepCos and kStepSin are those of 2π/64");
    auto outsideAt = [&](double c, double s) {
        return rimA.normalised(rimB.centre + c * rimB.e1 + s * rimB.e2).squaredNorm() - 1;
    };
    double sampleCos = 1, sampleSin = 0;
    double previous = outsideAt(sampleCos, sampleSin);
    for (int k = 1; k <= kSamples && anglesB.size() <= givenB + 8; ++k) {
        double low = kTwoPi * (k - 1) / kSamples, high = kTwoPi * k / kSamples;
        const double turned = sampleCos * kStepCos - sampleSin * kStepSin;
        sampleSin = sampleSin * kStepCos + sampleCos * kStepSin, sampleCos = turned;
        const double value = outsideAt(sampleCos, sampleSin);
        if ((previous < 0) != (value < 0)) {
            // Newton's steps from the bracket's middle, each kept inside the bracket (a step that
            // leaves it bisects instead), until the step is below rounding.
            const bool lowNegative = previous < 0;
            double root = 0.5 * (low + high);
            for (int i = 0; i < 60; ++i) {
                double slope;
                const double f = outsideWithSlope(root, slope);
                ((f < 0) == lowNegative ? low : high) = root;
                double next = root - f / slope;
                if (!(next > low && next < high)) next = 0.5 * (low + high);
                const bool done = std::abs(next - root) <= 1e-15 * kTwoPi || high - low <= 1e-15 * kTwoPi;
                root = next;
                if (done) break;
            }
            const Vec2 crossing = rimB.at(root);
            out.push_back(crossing);
            anglesB.push_back(root);
            anglesA.push_back(rimA.angleOf(crossing));
        }
        previous = value;
    }
    if (anglesB.size() > givenB + 4) {
        // Rims that coincide within rounding (two equal coaxial cans): A's rim is the region's.
        anglesA.setSize(givenA);
        anglesB.setSize(givenB);
    }
    const bool crossed = anglesA.size() > givenA;
    const std::size_t before = out.size();
    insideArcs(rimA, anglesA, step, [&](const Vec2& q) { return rimB.contains(q, slackB) && keep(q); }, out);
    if (!crossed && out.size() > before) return;  // A's whole rim inside B: B's cannot be inside A too
    insideArcs(rimB, anglesB, step, [&](const Vec2& q) { return rimA.contains(q, slackA) && keep(q); }, out);
}

// With spanContactRegion, where the region's boundary crosses `minimumDepth`: the depth is affine
// in the planar point where both features are flat (a disc, a face), so along a rim it is
// d₀ + A·cos t + B·sin t, crossing the contact depth at most twice (solved exactly), and along a
// polygon edge affine. Each crossing inside the other feature is a vertex of the contact region.
template <class Depth, class InsideOther>
void rimDepthCrossings(const Rim& rim, Depth depth, double minimumDepth, InsideOther insideOther,
                       SmallVector<double, 16>& angles, SmallVector<Vec2, 32>& out) {
    const double d0 = depth(rim.centre);
    const double a = depth(rim.centre + rim.e1) - d0, b = depth(rim.centre + rim.e2) - d0;
    const double amplitude = std::hypot(a, b);
    if (!(amplitude > 0) || std::abs(minimumDepth - d0) > amplitude) return;
    const double phase = std::atan2(b, a), spread = std::acos((minimumDepth - d0) / amplitude);
    for (const double t : {phase + spread, phase - spread}) {
        const Vec2 q = rim.at(t);
        angles.push_back(std::remainder(t, kTwoPi));  // an arc end either way; a vertex if inside
        if (insideOther(q)) out.push_back(q);
    }
}

template <class Depth>
void edgeDepthCrossings(const Flat& flat, const Rim& rim, Depth depth, double minimumDepth, double normalisedSlack,
                        SmallVector<Vec2, 32>& out) {
    const std::size_t n = flat.points.size();
    if (n < 3) return;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 &p = flat.points[i], &q = flat.points[(i + 1) % n];
        const double dp = depth(p) - minimumDepth, dq = depth(q) - minimumDepth;
        if (!((dp < 0) != (dq < 0))) continue;
        const Vec2 x = p + dp / (dp - dq) * (q - p);
        if (rim.contains(x, normalisedSlack)) out.push_back(x);
    }
}

}  // namespace

void intersectAnyFeatures(const AnyFeature& a, const AnyFeature& b, const Vec3& normal, double tolerance,
                          double minimumDepth, bool spanRegion, int arcPointsPerTurn, int wholeRimPoints,
                          LiftedPoints& out) {
    if (!a.isDisc && !b.isDisc)
        return intersectFeatures(view(a.geometry), view(b.geometry), normal, tolerance, minimumDepth, spanRegion, out);
    PlaneFrame frame{Vec3::Zero(), Vec3::Zero(), normal};
    planeBasis(normal, frame.u, frame.v);
    const RimSpacing step{kTwoPi / std::max(arcPointsPerTurn, 3), std::max(wholeRimPoints, 3)};
    const double toleranceSquared = tolerance * tolerance;

    // Lifts the planar points onto both features (heights along n) and appends those deep enough.
    auto lift = [&](const SmallVector<Vec2, 32>& planar, auto heightA, auto heightB) {
        for (const Vec2& q : planar) {
            bool known = false;
            for (const LiftedPoint& point : out) known = known || (point.planar - q).squaredNorm() <= toleranceSquared;
            if (known) continue;
            const double ha = heightA(q), hb = heightB(q);
            const double depth = ha - hb;
            if (!(depth >= minimumDepth - tolerance) || !std::isfinite(depth)) continue;
            out.push_back({frame.place(q, 0.5 * (ha + hb)), depth, q, 0, 0});
        }
    };

    // With spanContactRegion the contact region is clipped by depth ≥ minimumDepth too: its
    // crossings on a rim end arcs, and an arc's points must be in contact (`keep`).
    const double keepDepth = minimumDepth - tolerance;
    if (a.isDisc && b.isDisc) {
        const Rim rimA(a.disc, frame), rimB(b.disc, frame);
        const double slackA = tolerance / a.disc.radius, slackB = tolerance / b.disc.radius;
        auto heightA = [&](const Vec2& q) { return rimA.height(q, frame); };
        auto heightB = [&](const Vec2& q) { return rimB.height(q, frame); };
        auto depth = [&](const Vec2& q) { return heightA(q) - heightB(q); };
        SmallVector<Vec2, 32> planar;
        SmallVector<double, 16> anglesA, anglesB;
        if (spanRegion) {
            rimDepthCrossings(rimA, depth, minimumDepth, [&](const Vec2& q) { return rimB.contains(q, slackB); },
                              anglesA, planar);
            rimDepthCrossings(rimB, depth, minimumDepth, [&](const Vec2& q) { return rimA.contains(q, slackA); },
                              anglesB, planar);
        }
        discWithDisc(rimA, rimB, slackA, slackB, step, anglesA, anglesB,
                     [&](const Vec2& q) { return !spanRegion || depth(q) >= keepDepth; }, planar);
        lift(planar, heightA, heightB);
        return;
    }
    const AnyFeature& disc = a.isDisc ? a : b;
    const AnyFeature& other = a.isDisc ? b : a;
    const Rim rim(disc.disc, frame);
    const double discSlack = tolerance / disc.disc.radius;
    auto discHeight = [&](const Vec2& q) { return rim.height(q, frame); };
    // A face with a cap: the disc against each of its faces, each point lifted onto its own face.
    const std::vector<FeatureGeometry>& pieces = other.geometry.capFaces;
    const int pieceCount = pieces.empty() ? 1 : static_cast<int>(pieces.size());
    for (int i = 0; i < pieceCount; ++i) {
        const Flat flat(pieces.empty() ? other.geometry : pieces[i], frame);
        auto flatHeight = [&](const Vec2& q) { return flat.height(q, frame); };
        const double sign = a.isDisc ? 1 : -1;  // depth = height on A − height on B
        auto depth = [&](const Vec2& q) { return sign * (discHeight(q) - flatHeight(q)); };
        const bool span = spanRegion && flat.points.size() >= 3;
        SmallVector<Vec2, 32> planar;
        SmallVector<double, 16> angles;
        if (span) {
            rimDepthCrossings(rim, depth, minimumDepth, [&](const Vec2& q) { return flat.contains(q, tolerance); },
                              angles, planar);
            edgeDepthCrossings(flat, rim, depth, minimumDepth, discSlack, planar);
        }
        discWithFlat(rim, flat, tolerance, discSlack, step, angles,
                     [&](const Vec2& q) { return !span || depth(q) >= keepDepth; }, planar);
        if (a.isDisc)
            lift(planar, discHeight, flatHeight);
        else
            lift(planar, flatHeight, discHeight);
    }
}

void liftOntoPlane(const AnyFeature& a, const Vec3& normal, double planeOffset, double tolerance,
                   double minimumDepth, bool spanRegion, int arcPointsPerTurn, int wholeRimPoints, LiftedPoints& out) {
    Vec3 u, v;
    planeBasis(normal, u, v);
    auto depthOf = [&](const Vec3& p) { return planeOffset + normal.dot(p); };
    const double keepDepth = minimumDepth - tolerance;
    const double toleranceSquared = tolerance * tolerance;
    // A point of A moved half its depth back along n: midway between A and the plane.
    auto add = [&](const Vec3& p, bool mayRepeat) {
        const double depth = depthOf(p);
        if (!(depth >= keepDepth) || !std::isfinite(depth)) return;
        const Vec3 position = p - 0.5 * depth * normal;
        const Vec2 planar(position.dot(u), position.dot(v));
        if (mayRepeat)
            for (const LiftedPoint& point : out)
                if ((point.planar - planar).squaredNorm() <= toleranceSquared) return;
        out.push_back({position, depth, planar, 0, 0});
    };
    if (!a.isDisc) {
        const auto& points = a.geometry.points;
        for (const Vec3& p : points) add(p, false);
        if (!spanRegion || points.size() < 2) return;
        // Where an edge runs from contact into a gap, the point where it crosses minimumDepth.
        const std::size_t n = points.size(), edges = n == 2 ? 1 : n;
        for (std::size_t i = 0; i < edges; ++i) {
            const Vec3 &p = points[i], &q = points[(i + 1) % n];
            const double dp = depthOf(p) - minimumDepth, dq = depthOf(q) - minimumDepth;
            if ((dp < 0) != (dq < 0)) add(p + dp / (dp - dq) * (q - p), true);
        }
        return;
    }
    // The rim c + cos t·e1 + sin t·e2, t = 0 at its deepest point (as Rim places it): its depth is
    // d0 + amplitude·cos t.
    const Disc& disc = a.disc;
    Vec3 dir1, dir2;
    rimDirections(disc, normal, dir1, dir2);
    const Vec3 e1 = disc.radius * dir1, e2 = disc.radius * dir2;
    const int whole = std::max(wholeRimPoints, 3);
    const double d0 = depthOf(disc.centre), amplitude = normal.dot(e1);
    if (spanRegion && amplitude > 0 && std::abs(minimumDepth - d0) < amplitude) {
        // The rim crosses minimumDepth at ±spread: those two points and the arc between them
        // through the deepest point, spread as an arc of intersectAnyFeatures is.
        const double spread = std::acos((minimumDepth - d0) / amplitude);
        auto rimAt = [&](double t) { return Vec3(disc.centre + std::cos(t) * e1 + std::sin(t) * e2); };
        add(rimAt(spread), true);
        add(rimAt(-spread), true);
        const double step = kTwoPi / std::max(arcPointsPerTurn, 3);
        const int pieces = std::max(whole - 1, static_cast<int>(std::ceil(2 * spread / step - 1e-9)));
        for (int j = 1; j < pieces; ++j) add(rimAt(-spread + 2 * spread * j / pieces), true);
        return;
    }
    // The whole rim: a regular polygon from the deepest point.
    regularPolygon(whole, [&](double c, double s) { add(disc.centre + c * e1 + s * e2, false); });
}

}  // namespace gdc::detail
