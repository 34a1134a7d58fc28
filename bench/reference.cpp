#include "reference.hpp"

#include <ccd/ccd.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace gdcbench {

namespace {

struct Extent {
    double low = std::numeric_limits<double>::infinity();
    double high = -std::numeric_limits<double>::infinity();
};

Extent extentAlong(const std::vector<Vec3>& worldVertices, const Vec3& axis) {
    Extent e;
    for (const Vec3& v : worldVertices) {
        const double s = axis.dot(v);
        e.low = std::min(e.low, s);
        e.high = std::max(e.high, s);
    }
    return e;
}

std::vector<Vec3> worldVertices(const gdc::Polytope& p, const Pose& pose) {
    std::vector<Vec3> out;
    out.reserve(p.vertices().size());
    for (const Vec3& v : p.vertices()) out.push_back(pose.apply(v));
    return out;
}

}  // namespace

NormalAnswer exactMinimumNormal(const gdc::Polytope& a, const Pose& poseA, const gdc::Polytope& b,
                                const Pose& poseB) {
    const std::vector<Vec3> va = worldVertices(a, poseA), vb = worldVertices(b, poseB);
    std::vector<Vec3> axes;
    for (const auto& f : a.faces()) axes.push_back(poseA.rotation * f.normal);
    for (const auto& f : b.faces()) axes.push_back(poseB.rotation * f.normal);
    for (const auto& ea : a.edges()) {
        const Vec3 da = poseA.rotation * (a.vertices()[ea.head] - a.vertices()[ea.tail]);
        for (const auto& eb : b.edges()) {
            const Vec3 db = poseB.rotation * (b.vertices()[eb.head] - b.vertices()[eb.tail]);
            const Vec3 axis = da.cross(db);
            // Parallel edges span no Minkowski face of their own; their plane is some face's.
            if (axis.norm() > 1e-9 * da.norm() * db.norm()) axes.push_back(axis.normalized());
        }
    }
    NormalAnswer best;
    best.depth = std::numeric_limits<double>::infinity();
    for (const Vec3& axis : axes) {
        const Extent ea = extentAlong(va, axis), eb = extentAlong(vb, axis);
        // Along +axis (A towards B) the overlap is A's top minus B's bottom; along −axis the converse.
        const double forward = ea.high - eb.low, backward = eb.high - ea.low;
        if (forward < best.depth) best = {true, axis, forward};
        if (backward < best.depth) best = {true, -axis, backward};
    }
    best.overlapping = best.depth >= 0;
    return best;
}

namespace {

void supportOf(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* result) {
    const auto& placed = *static_cast<const PlacedPoints*>(object);
    const Vec3 local = placed.pose.rotation.transpose() * Vec3(direction->v[0], direction->v[1], direction->v[2]);
    const std::vector<Vec3>& vertices = *placed.vertices;
    std::size_t best = 0;
    double bestDot = local.dot(vertices[0]);
    for (std::size_t i = 1; i < vertices.size(); ++i) {
        const double d = local.dot(vertices[i]);
        if (d > bestDot) bestDot = d, best = i;
    }
    const Vec3 world = placed.pose.apply(vertices[best]);
    for (int k = 0; k < 3; ++k) result->v[k] = world[k];
}

void centerOf(const void* object, ccd_vec3_t* center) {
    const auto& placed = *static_cast<const PlacedPoints*>(object);
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : *placed.vertices) mean += v;
    const Vec3 world = placed.pose.apply(mean / static_cast<double>(placed.vertices->size()));
    for (int k = 0; k < 3; ++k) center->v[k] = world[k];
}

ccd_t makeCcd(double tolerance) {
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = supportOf;
    ccd.support2 = supportOf;
    ccd.center1 = centerOf;
    ccd.center2 = centerOf;
    ccd.max_iterations = 500;
    ccd.mpr_tolerance = tolerance;
    ccd.epa_tolerance = tolerance;
    return ccd;
}

NormalAnswer fromCcd(int status, ccd_real_t depth, const ccd_vec3_t& direction) {
    NormalAnswer answer;
    if (status != 0) return answer;
    const Vec3 normal(direction.v[0], direction.v[1], direction.v[2]);
    const double length = normal.norm();
    answer.overlapping = true;
    answer.depth = depth;
    // libccd reports a zero direction for exactly touching shapes: the +z default is kept, so the
    // accuracy column shows that as an error instead of a NaN.
    if (length > 0) answer.normal = normal / length;
    return answer;
}

}  // namespace

NormalAnswer mprNormal(const PlacedPoints& a, const PlacedPoints& b, double tolerance) {
    const ccd_t ccd = makeCcd(tolerance);
    ccd_real_t depth = 0;
    ccd_vec3_t direction, position;
    // "Translating obj2 by depth along dir separates them": dir points from A towards B.
    const int status = ccdMPRPenetration(&a, &b, &ccd, &depth, &direction, &position);
    return fromCcd(status, depth, direction);
}

NormalAnswer epaNormal(const PlacedPoints& a, const PlacedPoints& b, double tolerance) {
    const ccd_t ccd = makeCcd(tolerance);
    ccd_real_t depth = 0;
    ccd_vec3_t direction, position;
    const int status = ccdGJKPenetration(&a, &b, &ccd, &depth, &direction, &position);
    return fromCcd(status, depth, direction);
}

bool intersects(const PlacedPoints& a, const PlacedPoints& b) {
    const ccd_t ccd = makeCcd(1e-9);
    return ccdGJKIntersect(&a, &b, &ccd) != 0;
}

double touchingDistance(const std::vector<Vec3>& a, const Mat3& rotationA, const std::vector<Vec3>& b,
                        const Mat3& rotationB, const Vec3& direction) {
    double radius = 0;
    for (const Vec3& v : a) radius = std::max(radius, v.norm());
    for (const Vec3& v : b) radius = std::max(radius, v.norm());
    const Vec3 u = direction.normalized();
    double inside = 0, outside = 2.01 * radius;
    const PlacedPoints placedB{&b, {rotationB, Vec3::Zero()}};
    for (int i = 0; i < 60; ++i) {
        const double middle = 0.5 * (inside + outside);
        const PlacedPoints placedA{&a, {rotationA, middle * u}};
        (intersects(placedA, placedB) ? inside : outside) = middle;
    }
    return 0.5 * (inside + outside);
}

std::vector<std::pair<Pose, Pose>> touchingPoses(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                                                 int count, double overlap, std::uint64_t seed) {
    Random random(seed);
    std::vector<std::pair<Pose, Pose>> poses;
    const Pose frame = commonFrame();
    for (int i = 0; i < count; ++i) {
        const Mat3 rotationA = random.rotation(), rotationB = random.rotation();
        const Vec3 direction = random.unitVector();
        const double distance = touchingDistance(a, rotationA, b, rotationB, direction) - overlap;
        poses.emplace_back(compose(frame, {rotationA, distance * direction}),
                           compose(frame, {rotationB, Vec3::Zero()}));
    }
    return poses;
}

// ---- 2-D polygons ----------------------------------------------------------------------------

void planeBasis(const Vec3& normal, Vec3& u, Vec3& v) {
    const Vec3 n = normal.normalized();
    const Vec3 helper = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    u = n.cross(helper).normalized();
    v = n.cross(u);
}

Polygon2 project(const std::vector<Vec3>& points, const Vec3& u, const Vec3& v) {
    Polygon2 out;
    for (const Vec3& p : points) out.emplace_back(u.dot(p), v.dot(p));
    return out;
}

namespace {
double cross2(const gdc::Vec2& o, const gdc::Vec2& a, const gdc::Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

double distanceToSegment(const gdc::Vec2& p, const gdc::Vec2& a, const gdc::Vec2& b) {
    const gdc::Vec2 ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

double distanceToRegion(const gdc::Vec2& p, const Polygon2& region) {
    if (region.empty()) return std::numeric_limits<double>::infinity();
    if (region.size() == 1) return (p - region[0]).norm();
    bool inside = region.size() >= 3;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < region.size(); ++i) {
        const gdc::Vec2& a = region[i];
        const gdc::Vec2& b = region[(i + 1) % region.size()];
        if (cross2(a, b, p) < 0) inside = false;
        nearest = std::min(nearest, distanceToSegment(p, a, b));
    }
    return inside ? 0.0 : nearest;
}
}  // namespace

Polygon2 convexHull2(Polygon2 points) {
    std::sort(points.begin(), points.end(), [](const gdc::Vec2& p, const gdc::Vec2& q) {
        return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
    });
    if (points.size() < 3) return points;
    Polygon2 hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

Polygon2 intersectConvex(const Polygon2& subject, const Polygon2& clip) {
    Polygon2 output = subject;
    for (std::size_t i = 0; i < clip.size() && !output.empty(); ++i) {
        const gdc::Vec2& a = clip[i];
        const gdc::Vec2& b = clip[(i + 1) % clip.size()];
        const Polygon2 input = output;
        output.clear();
        for (std::size_t j = 0; j < input.size(); ++j) {
            const gdc::Vec2& p = input[j];
            const gdc::Vec2& q = input[(j + 1) % input.size()];
            const double sp = cross2(a, b, p), sq = cross2(a, b, q);
            if (sp >= 0) output.push_back(p);
            if ((sp >= 0) != (sq >= 0)) output.push_back(p + (q - p) * (sp / (sp - sq)));
        }
    }
    return output;
}

double area(const Polygon2& polygon) {
    double twice = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const gdc::Vec2& p = polygon[i];
        const gdc::Vec2& q = polygon[(i + 1) % polygon.size()];
        twice += p.x() * q.y() - p.y() * q.x();
    }
    return 0.5 * std::abs(twice);
}

double hausdorff(const Polygon2& p, const Polygon2& q) {
    double worst = 0;
    for (const gdc::Vec2& x : p) worst = std::max(worst, distanceToRegion(x, q));
    for (const gdc::Vec2& x : q) worst = std::max(worst, distanceToRegion(x, p));
    return worst;
}

}  // namespace gdcbench
