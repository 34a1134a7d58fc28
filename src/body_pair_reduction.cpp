// gdc::reduceBodyPairContacts: the per-body-pair contact budget (include/gdcontact/body_pair.hpp).
//
// Why: a body of several parts resting on another gets the whole support polygon of every pair of
// parts — the composites scene had 35–39 coplanar contacts between two bodies, and ODE's Dantzig
// LCP (dWorldStep) met degenerate pivots on those nearly dependent rows ("LCP internal error") and
// spent most of the step on them. A resting body needs a stable support region, not every vertex
// of it: a few points spanning the region, the deepest among them, the centre of mass above them.
//
// Mirror symmetry: the swapped call sees every normal negated. Clustering compares |dot| values
// that negation leaves bit for bit; the reduction works in a plane basis built from the cluster's
// normal turned to a canonical sign, and in coordinates relative to the cluster's first point, so
// both calls compute with the same numbers and choose the same points.
#include <gdcontact/body_pair.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace gdc {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The normal turned so that its largest component (the first of equal ones) is positive: the same
// vector for n and −n.
Vec3 canonicalSign(const Vec3& n) {
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    return n[axis] < 0 ? Vec3(-n) : n;
}

// Two unit vectors spanning the plane ⟂ m, chosen from m alone.
void planeBasis(const Vec3& m, Vec3& u, Vec3& v) {
    int smallest = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(m[k]) < std::abs(m[smallest])) smallest = k;
    u = m.cross(Vec3::Unit(smallest)).normalized();
    v = m.cross(u);
}

// Convex hull (counter-clockwise, monotone chain) of the points `indices` of `points`, as indices;
// collinear points are left out. One or two points give themselves.
std::vector<int> hullOf(const std::vector<Vec2>& points, std::vector<int> indices) {
    std::sort(indices.begin(), indices.end(), [&](int a, int b) {
        const Vec2& p = points[a];
        const Vec2& q = points[b];
        return p.x() < q.x() || (p.x() == q.x() && (p.y() < q.y() || (p.y() == q.y() && a < b)));
    });
    const int n = static_cast<int>(indices.size());
    if (n < 3) return indices;
    std::vector<int> hull(2 * n);
    int k = 0;
    for (int i = 0; i < n; ++i) {
        while (k >= 2 && cross2(points[hull[k - 1]] - points[hull[k - 2]], points[indices[i]] - points[hull[k - 2]]) <= 0) --k;
        hull[k++] = indices[i];
    }
    for (int i = n - 2, lower = k + 1; i >= 0; --i) {
        while (k >= lower && cross2(points[hull[k - 1]] - points[hull[k - 2]], points[indices[i]] - points[hull[k - 2]]) <= 0)
            --k;
        hull[k++] = indices[i];
    }
    hull.resize(std::max(1, k - 1));
    return hull;
}

// Whether `p` lies inside the counter-clockwise polygon `hull` (≥ 3 vertices), by more than `slack`
// from every edge (slack in length units: with slack ≥ 0 a centre on the boundary counts as
// outside; a negative slack admits the boundary).
bool strictlyInside(const std::vector<Vec2>& points, const std::vector<int>& hull, const Vec2& p, double slack) {
    if (hull.size() < 3) return false;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const Vec2& a = points[hull[i]];
        const Vec2& b = points[hull[(i + 1) % hull.size()]];
        const Vec2 edge = b - a;
        const double length = edge.norm();
        if (!(cross2(edge, p - a) > slack * length)) return false;
    }
    return true;
}

// Area the counter-clockwise polygon `hull` gains when `p` joins it.
double areaGain(const std::vector<Vec2>& points, const std::vector<int>& hull, const Vec2& p) {
    if (hull.size() == 2)  // a segment: the triangle it makes with p
        return 0.5 * std::abs(cross2(points[hull[1]] - points[hull[0]], p - points[hull[0]]));
    double gain = 0;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const Vec2& a = points[hull[i]];
        const Vec2& b = points[hull[(i + 1) % hull.size()]];
        const double twiceArea = cross2(b - a, p - a);
        if (twiceArea < 0) gain -= 0.5 * twiceArea;
    }
    return gain;
}

// Adds points of `candidates` to `chosen` (the kept ones, in order of choice) until `budget`: each
// time the one adding the most area; ties and collinear sets (no area to add) go to the farthest
// from every kept point, then to the first.
void fillByArea(const std::vector<Vec2>& points, const std::vector<int>& candidates, int budget,
                std::vector<int>& chosen) {
    while (static_cast<int>(chosen.size()) < budget) {
        const std::vector<int> hull = hullOf(points, chosen);
        int best = -1;
        double bestGain = -1, bestDistance = -1;
        for (int i : candidates) {
            if (std::find(chosen.begin(), chosen.end(), i) != chosen.end()) continue;
            const double gain = hull.size() >= 2 ? areaGain(points, hull, points[i]) : 0.0;
            double distance = 1e300;
            for (int k : chosen) distance = std::min(distance, (points[i] - points[k]).squaredNorm());
            if (gain > bestGain || (gain == bestGain && distance > bestDistance))
                best = i, bestGain = gain, bestDistance = distance;
        }
        if (best < 0) return;
        chosen.push_back(best);
    }
}

void requireValid(const BodyPairContact& c, int index) {
    const bool finite = c.position.allFinite() && c.normal.allFinite() && std::isfinite(c.depth);
    if (!finite || std::abs(c.normal.norm() - 1.0) > 1e-6)
        throw InvalidInput("reduceBodyPairContacts: contact " + std::to_string(index) +
                           (finite ? " has a normal that is not unit length" : " has a non-finite position, normal or depth"));
}

}  // namespace

int reduceBodyPairContacts(const BodyPairContact* contacts, int count, const BodyPairFrame& frame,
                           const Settings& settings, std::vector<int>& kept) {
    kept.clear();
    if (count < 0) throw InvalidInput("reduceBodyPairContacts: negative contact count " + std::to_string(count));
    if (count > 0 && !contacts) throw InvalidInput("reduceBodyPairContacts: null contacts");
    for (int i = 0; i < count; ++i) requireValid(contacts[i], i);
    const int budget = settings.maxBodyPairContacts;
    if (budget <= 0) {
        for (int i = 0; i < count; ++i) kept.push_back(i);
        return count;
    }

    // 1. Clusters by normal, in the order of the contacts.
    const double cosTolerance = std::cos(settings.bodyPairNormalTolerance);
    std::vector<int> clusterOf(count), firstOfCluster;
    for (int i = 0; i < count; ++i) {
        int cluster = -1;
        for (std::size_t c = 0; c < firstOfCluster.size() && cluster < 0; ++c)
            if (contacts[i].normal.dot(contacts[firstOfCluster[c]].normal) >= cosTolerance) cluster = static_cast<int>(c);
        if (cluster < 0) {
            cluster = static_cast<int>(firstOfCluster.size());
            firstOfCluster.push_back(i);
        }
        clusterOf[i] = cluster;
    }

    const double gravityLength = frame.gravity.norm();
    const Vec3 up = gravityLength > 0 ? Vec3(-frame.gravity / gravityLength) : Vec3::Zero();
    std::vector<Vec2> planar(count);
    for (std::size_t cluster = 0; cluster < firstOfCluster.size(); ++cluster) {
        const BodyPairContact& first = contacts[firstOfCluster[cluster]];
        const Vec3 axis = canonicalSign(first.normal);
        Vec3 u, v;
        planeBasis(axis, u, v);
        std::vector<int> members;
        Vec2 low = Vec2::Constant(1e300), high = Vec2::Constant(-1e300);
        for (int i = 0; i < count; ++i) {
            if (clusterOf[i] != static_cast<int>(cluster)) continue;
            const Vec3 relative = contacts[i].position - first.position;
            planar[i] = Vec2(relative.dot(u), relative.dot(v));
            low = low.cwiseMin(planar[i]);
            high = high.cwiseMax(planar[i]);
            members.push_back(i);
        }
        const double extent = (high - low).norm();

        // 2. Near-duplicates: deepest first (ties: the first), each kept unless a kept one is within
        //    the merge distance.
        std::vector<int> byDepth = members;
        std::stable_sort(byDepth.begin(), byDepth.end(),
                         [&](int a, int b) { return contacts[a].depth > contacts[b].depth; });
        const double mergeSquared = std::pow(kBodyPairMergeFraction * extent, 2);
        std::vector<int> distinct;
        for (int i : byDepth) {
            bool duplicate = false;
            for (int k : distinct)
                if ((planar[i] - planar[k]).squaredNorm() <= mergeSquared) {
                    duplicate = true;
                    break;
                }
            if (!duplicate) distinct.push_back(i);
        }
        if (static_cast<int>(distinct.size()) <= budget) {
            kept.insert(kept.end(), distinct.begin(), distinct.end());
            continue;
        }

        // 3. The budget: the deepest (distinct[0]), the farthest from it, then by area.
        const int deepest = distinct[0];
        std::vector<int> chosen{deepest};
        if (budget >= 2) {
            int farthest = -1;
            double farthestDistance = -1;
            for (int i : distinct) {
                const double d = (planar[i] - planar[deepest]).squaredNorm();
                if (i != deepest && d > farthestDistance) farthest = i, farthestDistance = d;
            }
            chosen.push_back(farthest);
            fillByArea(planar, distinct, budget, chosen);
        }

        // The carried body's centre of mass over the kept polygon, where it was over the whole one.
        const double push = up.dot(first.normal);  // > 0: the normal (from B into A) lifts A
        const bool carriesA = push > 0 && frame.hasCentreA, carriesB = push < 0 && frame.hasCentreB;
        if (budget >= 3 && (carriesA || carriesB)) {
            const Vec3 relative = (carriesA ? frame.centreA : frame.centreB) - first.position;
            const Vec2 centre(relative.dot(u), relative.dot(v));
            const std::vector<int> whole = hullOf(planar, distinct);
            const double slack = 1e-9 * extent;
            if (strictlyInside(planar, whole, centre, slack) && !strictlyInside(planar, hullOf(planar, chosen), centre, slack)) {
                // The triangles of the deepest with the polygon's edges cover the polygon (the deepest
                // lies in it): one of them holds the centre.
                for (std::size_t e = 0; e < whole.size(); ++e) {
                    const int a = whole[e], b = whole[(e + 1) % whole.size()];
                    if (a == deepest || b == deepest) continue;
                    const std::vector<int> triangle{deepest, a, b};
                    // Closed triangles: a centre on the diagonal from the deepest counts for both sides.
                    if (!strictlyInside(planar, hullOf(planar, triangle), centre, -slack)) continue;
                    chosen = triangle;
                    fillByArea(planar, distinct, budget, chosen);
                    break;
                }
            }
        }
        kept.insert(kept.end(), chosen.begin(), chosen.end());
    }
    std::sort(kept.begin(), kept.end());
    return static_cast<int>(kept.size());
}

}  // namespace gdc
