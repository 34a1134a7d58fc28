// Triangle meshes (include/gdcontact/triangle_mesh.hpp) against exact answers computed here,
// independently of src/: the mesh's topology (active edges by the dihedral angles and the winding,
// overlapping() against a brute-force box test), a flat triangulated floor against the plane it
// lies in (gdc::collide with a HalfSpace: the same normal, the same deepest depth, the same support),
// the contact contract on folded meshes (points in their shapes, depths within the exact overlap of
// the body with the triangle's prism, normals from the triangle's face or an active edge's cone),
// seams, the back side, and determinism under a repeated call and a permuted triangle order.
//
// Tolerances, relative to the body's size s (Polytope::radius(), about 0.3..1.3 here):
// - kInside = 1e-6·s for "this point is in this body": Polytope::fromPoints merges faces within
//   Settings::coplanarTolerance (1e-6 rad), so its face planes may lie ~1e-6·s off its vertices;
//   boxes and the flat floor are exact, but one tolerance keeps the checks uniform.
// - kDepth = 1e-9·s for depths that are exact (a flat floor: the lowest vertex's height, computed
//   from the same vertices by the plane and by the triangle; rounding is ~1e-15·s, and 1e-9·s is
//   the library's own decision scale, body_pair.hpp / the reduction's tolerance).
// - kNormal = 1e-12 for normals that are exact (a flat floor's face normal is (0, 0, ±c)/c).
// - kCone = 1e-6 (rad) for "this normal lies in this feature's normal cone": a growth-distance
//   normal is converged to 1e-10 of the pair's size (Settings::rayCastTolerance), far inside it.
#include <gdcontact/collide.hpp>
#include <gdcontact/triangle_mesh.hpp>

#include "geometry_oracles.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace gdc;
using gdc::testing::randomRotation;
using gdc::testing::rotationAbout;
using gdc::testing::signedDistance;

namespace {

using Rng = std::mt19937_64;
using Triangles = std::vector<std::array<int, 3>>;

constexpr double kInside = 1e-6;  // × s
constexpr double kDepth = 1e-9;   // × s
constexpr double kNormal = 1e-12;
constexpr double kCone = 1e-6;

double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
double logUniform(Rng& rng, double lo, double hi) { return std::exp(uniform(rng, std::log(lo), std::log(hi))); }
int integer(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

std::string show(const Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return s.str();
}
std::string show(const Mat3& m) {
    std::ostringstream s;
    s.precision(17);
    s << "[" << m.row(0) << "; " << m.row(1) << "; " << m.row(2) << "]";
    return s.str();
}

// ---------- meshes ----------

struct MeshData {
    std::vector<Vec3> vertices;
    Triangles triangles;
};

// A grid of nx × ny square cells of side `cell`, its lower corner at lattice point (i0, j0), each
// cell two triangles counter-clockwise seen from +z (the diagonal alternating with the cell's
// parity), heights from `height(x, y)`.
template <class Height>
MeshData gridMesh(int i0, int j0, int nx, int ny, double cell, Height height) {
    MeshData m;
    auto index = [&](int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const double x = (i0 + i) * cell, y = (j0 + j) * cell;
            m.vertices.emplace_back(x, y, height(x, y, i, j));
        }
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
            if (((i0 + i) + (j0 + j)) % 2 == 0) {
                m.triangles.push_back({a, b, c});
                m.triangles.push_back({a, c, d});
            } else {
                m.triangles.push_back({a, b, d});
                m.triangles.push_back({b, c, d});
            }
        }
    return m;
}

MeshData flatGrid(int i0, int j0, int nx, int ny, double cell) {
    return gridMesh(i0, j0, nx, ny, cell, [](double, double, int, int) { return 0.0; });
}

// Undirected edge key.
std::pair<int, int> edgeKey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

std::map<std::pair<int, int>, int> edgeUse(const Triangles& triangles) {
    std::map<std::pair<int, int>, int> use;
    for (const auto& t : triangles)
        for (int e = 0; e < 3; ++e) ++use[edgeKey(t[e], t[(e + 1) % 3])];
    return use;
}

// ---------- bodies ----------

struct Body {
    std::shared_ptr<Polytope> poly;
    double size = 1;
    bool box = false;
};

Body makeBody(Rng& rng, bool box) {
    Body b;
    b.box = box;
    if (box) {
        b.poly = std::make_shared<Polytope>(Polytope::box(Vec3(uniform(rng, 0.15, 0.7), uniform(rng, 0.15, 0.7), uniform(rng, 0.15, 0.7))));
    } else {
        // Points on a random ellipsoid (semi-axes 0.25..0.8), randomly turned: hulls of 8..20
        // vertices with faces of every orientation.
        const Vec3 axes(uniform(rng, 0.25, 0.8), uniform(rng, 0.25, 0.8), uniform(rng, 0.25, 0.8));
        const Mat3 turn = randomRotation(rng);
        std::normal_distribution<double> gauss;
        std::vector<Vec3> points;
        for (int i = 0, n = integer(rng, 8, 20); i < n; ++i) {
            Vec3 d(gauss(rng), gauss(rng), gauss(rng));
            points.push_back(turn * axes.cwiseProduct(d.normalized()));
        }
        b.poly = std::make_shared<Polytope>(Polytope::fromPoints(points));
    }
    b.size = b.poly->radius();
    return b;
}

std::vector<Vec3> worldVertices(const Polytope& p, const Pose& pose) {
    std::vector<Vec3> out;
    for (const Vec3& v : p.vertices()) out.push_back(pose.apply(v));
    return out;
}

// ---------- contacts ----------

std::vector<MeshContact> collideMesh(const Polytope& a, const Pose& pa, const TriangleMesh& mesh, const Pose& pm,
                                     const Settings& settings = {}) {
    std::vector<MeshContact> out{MeshContact{}};  // cleared first: a stale entry must go
    collide(a, pa, mesh, pm, settings, out);
    return out;
}

double maxDepth(const std::vector<MeshContact>& cs) {
    double d = -INFINITY;
    for (const auto& c : cs) d = std::max(d, c.depth);
    return d;
}


double hullArea(const std::vector<Vec2>& p) { return gdc::testing::convexHullArea(p); }

// Distance from p to the closed triangle (a, b, c), by projection and the three edges.
double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a);
    const double nn = n.squaredNorm();
    const Vec3 q = p - n * (n.dot(p - a) / nn);
    const double u = n.dot((b - q).cross(c - q)), v = n.dot((c - q).cross(a - q)), w = n.dot((a - q).cross(b - q));
    if (u >= 0 && v >= 0 && w >= 0) return (p - q).norm();
    auto segment = [&](const Vec3& x, const Vec3& y) {
        const double t = std::clamp((p - x).dot(y - x) / (y - x).squaredNorm(), 0.0, 1.0);
        return (p - (x + t * (y - x))).norm();
    };
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// Whether the projection of p along the triangle's normal lies inside it, at least `margin` from
// its edges.
bool projectsInside(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double margin) {
    const Vec3 n = (b - a).cross(c - a).normalized();
    const Vec3 w[3] = {a, b, c};
    for (int e = 0; e < 3; ++e) {
        const Vec3 out = (w[(e + 1) % 3] - w[e]).cross(n).normalized();  // outward in the plane
        if (out.dot(p - w[e]) > -margin) return false;
    }
    return true;
}

// An exact upper bound of the overlap along unit n (from the body towards the mesh) of the posed
// body A with the triangle's prism extruded infinitely behind it (every thinner prism is inside it,
// so the bound holds for the library's prism whatever its thickness): T(n) = sup{t : t·n ∈ A − P}
// ≤ (h_A(m) + h_P(−m)) / (m·n) for every m with m·n > 0 — the Minkowski difference's face normals
// are among the candidates below (A's faces, P's faces, edge × edge), and any other m only gives a
// valid, looser plane. Axes with m·N > 0 see P's infinite extrusion (h_P(−m) = ∞) and bound nothing.
double prismOverlapBound(const Polytope& a, const Pose& pose, const Vec3 (&w)[3], const Vec3& n) {
    const std::vector<Vec3> av = worldVertices(a, pose);
    const Vec3 N = (w[1] - w[0]).cross(w[2] - w[0]).normalized();
    std::vector<Vec3> axes;
    for (const auto& f : a.faces()) axes.push_back(pose.rotation * f.normal);
    std::vector<Vec3> aEdges, pEdges;
    for (const auto& e : a.edges()) aEdges.push_back(pose.rotation * (a.vertices()[e.head] - a.vertices()[e.tail]));
    for (int e = 0; e < 3; ++e) {
        pEdges.push_back(w[(e + 1) % 3] - w[e]);
        axes.push_back(pEdges.back().cross(N));
    }
    pEdges.push_back(N);
    axes.push_back(N);
    for (const Vec3& x : aEdges)
        for (const Vec3& y : pEdges) axes.push_back(x.cross(y));
    double bound = INFINITY;
    for (Vec3 m : axes) {
        if (!(m.norm() > 1e-12)) continue;
        m.normalize();
        for (const Vec3& mm : {m, Vec3(-m)}) {
            const double dn = mm.dot(n);
            if (dn <= 1e-9 || mm.dot(N) > 1e-12) continue;
            double hA = -INFINITY, hP = -INFINITY;
            for (const Vec3& v : av) hA = std::max(hA, mm.dot(v));
            for (const Vec3& v : w) hP = std::max(hP, -mm.dot(v));
            bound = std::min(bound, (hA + hP) / dn);
        }
    }
    return bound;
}

// Whether −n (unit, out of the mesh's front) lies in the normal cone of a feature of triangle t
// of the thin prism that may give a contact its normal: the face (within kNormal), an active edge,
// or a vertex with an active edge (each within kCone). Returns "face", "edge", "vertex" or "".
std::string normalFeature(const TriangleMesh& mesh, const Pose& pm, int t, const Vec3& n) {
    const auto& tri = mesh.triangle(t);
    Vec3 w[3];
    for (int k = 0; k < 3; ++k) w[k] = pm.apply(mesh.vertices()[tri[k]]);
    const Vec3 N = pm.rotation * mesh.triangleNormal(t);
    const Vec3 m = -n;
    if ((m - N).norm() <= kNormal * 1e3) return "face";  // 1e-9: the face normal, rounded through a pose
    if (m.dot(N) < -kCone) return "";
    for (int e = 0; e < 3; ++e) {
        if (!mesh.edgeActive(t, e)) continue;
        const Vec3 d = (w[(e + 1) % 3] - w[e]).normalized();
        const Vec3 out = d.cross(N);
        if (std::abs(m.dot(d)) <= kCone && m.dot(out) >= -kCone) return "edge";
    }
    for (int k = 0; k < 3; ++k) {
        const int eOut = k, eIn = (k + 2) % 3;  // edges k→k+1 and k−1→k
        if (!mesh.edgeActive(t, eOut) && !mesh.edgeActive(t, eIn)) continue;
        const double scale = std::max((w[(k + 1) % 3] - w[k]).norm(), (w[(k + 2) % 3] - w[k]).norm());
        if (m.dot(w[(k + 1) % 3] - w[k]) <= kCone * scale && m.dot(w[(k + 2) % 3] - w[k]) <= kCone * scale) return "vertex";
    }
    return "";
}

// The contract of every mesh contact, whatever the mesh: finite fields, a unit normal into the
// triangle's back half-space, a normal from the face or an active feature, the position in the body
// and (with the point on the mesh) on the triangle or beyond an edge into a valley, below the
// neighbour, the depth within the exact overlap bound (the plane's beyond a valley edge), at most
// maxBodyPairContacts contacts per normal. Returns a description of the first violation ("" if none).
std::string contractViolation(const Polytope& a, const Pose& pa, double size, const TriangleMesh& mesh, const Pose& pm,
                              const std::vector<MeshContact>& cs, const Settings& settings = {}) {
    std::ostringstream why;
    why.precision(17);
    for (std::size_t i = 0; i < cs.size(); ++i) {
        const MeshContact& c = cs[i];
        why.str("");
        why << "contact " << i << " pos " << show(c.position) << " n " << show(c.normal) << " depth " << c.depth
            << " triangle " << c.triangle << ": ";
        if (!c.position.allFinite() || !c.normal.allFinite() || !std::isfinite(c.depth)) return why.str() + "not finite";
        if (std::abs(c.normal.norm() - 1) > 1e-12) return why.str() + "normal not unit";
        if (c.triangle < 0 || c.triangle >= mesh.triangleCount()) return why.str() + "triangle out of range";
        if (mesh.triangleNormal(c.triangle).norm() == 0) return why.str() + "from a skipped triangle";
        if (c.depth < -settings.margin - kDepth * size) return why.str() + "depth below -margin";
        const auto& tri = mesh.triangle(c.triangle);
        Vec3 w[3];
        for (int k = 0; k < 3; ++k) w[k] = pm.apply(mesh.vertices()[tri[k]]);
        const Vec3 N = pm.rotation * mesh.triangleNormal(c.triangle);
        if (!(c.normal.dot(N) < 0)) return why.str() + "normal out of the triangle's back (n·N = " + std::to_string(c.normal.dot(N)) + ")";
        const std::string feature = normalFeature(mesh, pm, c.triangle, c.normal);
        if (feature.empty()) return why.str() + "normal in no active feature's cone of its triangle";
        // The point on A is in A; the position, depth/2 from it along the normal, is in the body
        // only up to that distance: above a tilted face's corner (a face taken within the angular
        // tolerance) the vertical leaves the body through the tilted side by depth/2·sin(tilt) —
        // the plane's answer does the same — and above a vertex feature it may leave sooner.
        const Vec3 onA = c.position + 0.5 * c.depth * c.normal, onB = c.position - 0.5 * c.depth * c.normal;
        if (signedDistance(a, pa, onA) > kInside * size) return why.str() + "point on A outside the body by " + std::to_string(signedDistance(a, pa, onA) / size) + "·s";
        if (signedDistance(a, pa, c.position) > kInside * size + 0.5 * std::max(c.depth, 0.0))
            return why.str() + "position outside the body by " + std::to_string(signedDistance(a, pa, c.position) / size) + "·s";
        // The point on the mesh is on the prism's feature along −n: on the triangle (its face, an
        // edge or a vertex of its top) unless −n is within the angular tolerance of a side face's
        // normal (−n·N ≤ sin 0.05, with a margin), where it may lie on that side, below the top.
        // A face's contact may lie beyond an edge into a valley (inactive, not a seam: below the
        // valley the solid is the union of what lies below each side's plane), in the face's plane
        // and below the neighbour's.
        bool beyondValley = false;
        if (-c.normal.dot(N) > std::sin(settings.angularTolerance) + 0.01) {
            const double d = pointTriangleDistance(onB, w[0], w[1], w[2]);
            if (d > kInside * size) {
                if (feature != "face" || std::abs(N.dot(onB - w[0])) > kInside * size)
                    return why.str() + "point on the mesh " + std::to_string(d / size) + "·s off its triangle";
                for (int e = 0; e < 3; ++e) {
                    if ((w[(e + 1) % 3] - w[e]).cross(N).normalized().dot(onB - w[e]) <= kInside * size) continue;
                    const int u = mesh.neighbour(c.triangle, e);
                    const bool valley = u >= 0 && !mesh.edgeActive(c.triangle, e) &&
                                        mesh.triangleNormal(c.triangle).dot(mesh.triangleNormal(u)) < 1 - 1e-12;
                    const Vec3 Nu = pm.rotation * mesh.triangleNormal(u >= 0 ? u : c.triangle);
                    const Vec3 wu = pm.apply(mesh.vertices()[mesh.triangle(u >= 0 ? u : c.triangle)[0]]);
                    if (!valley || Nu.dot(onB - wu) > kInside * size)
                        return why.str() + "point on the mesh " + std::to_string(d / size) + "·s off its triangle beyond edge " +
                               std::to_string(e) + (valley ? " into a valley, above the neighbour by " + std::to_string(Nu.dot(onB - wu) / size) + "·s"
                                                           : ", not into a valley");
                }
                beyondValley = true;
            }
        } else {
            double outside = N.dot(onB - w[0]);
            for (int e = 0; e < 3; ++e) outside = std::max(outside, (w[(e + 1) % 3] - w[e]).cross(N).normalized().dot(onB - w[e]));
            if (outside > kInside * size) return why.str() + "point on the mesh " + std::to_string(outside / size) + "·s outside its prism";
        }
        const double bound = beyondValley ? INFINITY : prismOverlapBound(a, pa, w, c.normal);
        if (c.depth > bound + 4 * kInside * size)
            return why.str() + "depth above the exact overlap bound " + std::to_string(bound);
        if (feature == "face") {
            // The brief's plane form of the same bound: max over body vertices of (offset − N·v).
            double plane = -INFINITY;
            for (const Vec3& v : worldVertices(a, pa)) plane = std::max(plane, N.dot(w[0]) - N.dot(v));
            if (c.depth > plane + kDepth * size) return why.str() + "depth above the plane penetration " + std::to_string(plane);
        }
    }
    // Identical normals fall in one cluster of the reduction (each joins the first cluster whose
    // first normal is near its own — the same for both): at most the budget of them.
    if (settings.maxBodyPairContacts > 0)
        for (const auto& c : cs) {
            int same = 0;
            for (const auto& d : cs) same += (c.normal - d.normal).norm() <= 1e-12;
            if (same > settings.maxBodyPairContacts) return "more than maxBodyPairContacts contacts with one normal";
        }
    return "";
}

std::string describe(const std::vector<MeshContact>& cs) {
    std::ostringstream s;
    s.precision(17);
    for (const auto& c : cs) s << "\n  pos " << show(c.position) << " n " << show(c.normal) << " depth " << c.depth << " tri " << c.triangle;
    return s.str();
}

std::string describePose(const char* what, const Pose& p) {
    return std::string(what) + " rotation " + show(p.rotation) + " position " + show(p.position);
}

// Same contact set within `tol` (positions, normals, depths), each matched once.
bool sameContactSet(const std::vector<MeshContact>& x, const std::vector<MeshContact>& y, double tol) {
    if (x.size() != y.size()) return false;
    std::vector<char> used(y.size(), 0);
    for (const auto& c : x) {
        bool found = false;
        for (std::size_t j = 0; j < y.size() && !found; ++j)
            if (!used[j] && (c.position - y[j].position).norm() <= tol && (c.normal - y[j].normal).norm() <= tol &&
                std::abs(c.depth - y[j].depth) <= tol)
                used[j] = 1, found = true;
        if (!found) return false;
    }
    return true;
}

}  // namespace

// =====================================================================================================
// 1. Construction
// =====================================================================================================

TEST_CASE("mesh: a flat grid has inactive interior edges and active boundary edges") {
    const MeshData m = flatGrid(-2, -1, 5, 3, 0.7);
    const TriangleMesh mesh(m.vertices, m.triangles);
    REQUIRE(mesh.triangleCount() == 30);
    REQUIRE(mesh.skippedTriangleCount() == 0);
    const auto use = edgeUse(m.triangles);
    int interior = 0, boundary = 0;
    for (int t = 0; t < mesh.triangleCount(); ++t) {
        CHECK(mesh.triangle(t) == m.triangles[t]);
        CHECK((mesh.triangleNormal(t) - Vec3::UnitZ()).norm() <= kNormal);  // counter-clockwise from +z
        for (int e = 0; e < 3; ++e) {
            const bool onBoundary = use.at(edgeKey(m.triangles[t][e], m.triangles[t][(e + 1) % 3])) == 1;
            (onBoundary ? boundary : interior)++;
            INFO("triangle " << t << " edge " << e);
            CHECK(mesh.edgeActive(t, e) == onBoundary);
        }
    }
    CHECK(boundary == 2 * (5 + 3));
    CHECK(interior > 0);
}

namespace {
// Two triangles sharing the edge A = (0, −1, 0) → B = (0, 1, 0) (edge 1 of both), the left one's far
// vertex at (−1, 0, zL), the right one's at (1, 0, zR); counter-clockwise from above. zL = zR < 0:
// a convex ridge, > 0 a concave valley; the normals are (2zL, 0, 2) and (−2zR, 0, 2) normalised.
MeshData fold(double zL, double zR) {
    MeshData m;
    m.vertices = {Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(-1, 0, zL), Vec3(1, 0, zR)};
    m.triangles = {{2, 0, 1}, {3, 1, 0}};
    return m;
}
double foldAngle(double z) { return 2 * std::atan(std::abs(z)); }  // between the two normals
}  // namespace

TEST_CASE("mesh: a fold's edge is active for a convex ridge beyond the angular tolerance only") {
    const Settings defaults;
    struct Case {
        double z;       // both far vertices' height
        double angle;   // the fold between the normals
        bool active;
        const char* what;
    };
    const double big = std::tan(0.2 / 2), small = std::tan(0.02 / 2), huge = std::tan(1.2 / 2);
    const Case cases[] = {
        {-big, 0.2, true, "ridge 0.2 rad (> 0.05)"},
        {-huge, 1.2, true, "ridge 1.2 rad"},
        {big, 0.2, false, "valley 0.2 rad (concave)"},
        {huge, 1.2, false, "valley 1.2 rad (concave)"},
        {-small, 0.02, false, "ridge 0.02 rad (< angularTolerance 0.05)"},
        {small, 0.02, false, "valley 0.02 rad"},
        {0.0, 0.0, false, "coplanar"},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        REQUIRE(std::abs(foldAngle(c.z) - c.angle) < 1e-12);
        const MeshData m = fold(c.z, c.z);
        const TriangleMesh mesh(m.vertices, m.triangles);
        CHECK(mesh.edgeActive(0, 1) == c.active);
        CHECK(mesh.edgeActive(1, 1) == c.active);
        for (int t = 0; t < 2; ++t)
            for (int e : {0, 2}) CHECK(mesh.edgeActive(t, e));  // boundary
        // The normals: unit, front by the winding.
        const Vec3 nL = Vec3(2 * c.z, 0, 2).normalized(), nR = Vec3(-2 * c.z, 0, 2).normalized();
        CHECK((mesh.triangleNormal(0) - nL).norm() <= kNormal);
        CHECK((mesh.triangleNormal(1) - nR).norm() <= kNormal);
        CHECK(std::abs(mesh.triangleNormal(0).norm() - 1) <= kNormal);
    }
    // The tolerance is Settings::angularTolerance: a 0.02 rad ridge is active under a 0.01 rad one.
    Settings tight;
    tight.angularTolerance = 0.01;
    const MeshData m = fold(-small, -small);
    CHECK(TriangleMesh(m.vertices, m.triangles, tight).edgeActive(0, 1));
    CHECK_FALSE(TriangleMesh(m.vertices, m.triangles, defaults).edgeActive(0, 1));
    // An asymmetric fold: one side flat, the other bent down by 0.1 rad: a ridge of 0.1 rad.
    const MeshData lopsided = fold(0.0, -std::tan(0.1));
    CHECK(TriangleMesh(lopsided.vertices, lopsided.triangles).edgeActive(0, 1));
    const MeshData lopsidedValley = fold(0.0, std::tan(0.1));
    CHECK_FALSE(TriangleMesh(lopsidedValley.vertices, lopsidedValley.triangles).edgeActive(0, 1));
}

TEST_CASE("mesh: an edge shared by three triangles is active") {
    // A fan of three coplanar-or-not triangles on the edge (0,−1,0)–(0,1,0).
    const std::vector<Vec3> v = {Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, 0.8)};
    const Triangles t = {{2, 0, 1}, {3, 1, 0}, {4, 1, 0}};
    const TriangleMesh mesh(v, t);
    for (int k = 0; k < 3; ++k) CHECK(mesh.edgeActive(k, 1));
}

TEST_CASE("mesh: triangle normals follow the winding") {
    Rng rng(7);
    for (int k = 0; k < 200; ++k) {
        std::vector<Vec3> v;
        for (int i = 0; i < 3; ++i) v.emplace_back(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5));
        const TriangleMesh mesh(v, Triangles{{0, 1, 2}, {0, 2, 1}});
        const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
        CHECK((mesh.triangleNormal(0) - n).norm() <= 1e-12);
        CHECK((mesh.triangleNormal(1) + n).norm() <= 1e-12);
        CHECK(std::abs(mesh.triangleNormal(0).norm() - 1) <= 1e-12);
    }
}

TEST_CASE("mesh: bad input throws and degenerate triangles are skipped") {
    const std::vector<Vec3> v = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)};
    std::vector<Vec3> nan = v;
    nan[2].y() = NAN;
    CHECK_THROWS_AS(TriangleMesh(nan, Triangles{{0, 1, 2}}), InvalidInput);
    std::vector<Vec3> inf = v;
    inf[1].x() = INFINITY;
    CHECK_THROWS_AS(TriangleMesh(inf, Triangles{{0, 1, 2}}), InvalidInput);
    // A NaN vertex no triangle uses is still bad input.
    CHECK_THROWS_AS(TriangleMesh(nan, Triangles{{0, 1, 3}}), InvalidInput);
    CHECK_THROWS_AS(TriangleMesh(v, Triangles{{0, 1, 4}}), InvalidInput);
    CHECK_THROWS_AS(TriangleMesh(v, Triangles{{0, -1, 2}}), InvalidInput);

    // A repeated index and a zero-area (collinear) triangle among good ones.
    const std::vector<Vec3> w = {Vec3(-2, -2, 0), Vec3(2, -2, 0), Vec3(2, 2, 0), Vec3(-2, 2, 0), Vec3(0, -2, 0)};
    const Triangles t = {{0, 1, 2}, {0, 0, 2}, {0, 4, 1}, {0, 2, 3}};
    const TriangleMesh mesh(w, t);
    CHECK(mesh.triangleCount() == 4);
    CHECK(mesh.skippedTriangleCount() == 2);
    CHECK(mesh.triangleNormal(1) == Vec3::Zero());
    CHECK(mesh.triangleNormal(2) == Vec3::Zero());
    std::vector<int> found;
    mesh.overlapping(Aabb{Vec3::Constant(-10), Vec3::Constant(10)}, found);
    CHECK(found == std::vector<int>{0, 3});
    // A box resting on them touches only the good ones.
    const Polytope box = Polytope::box(Vec3(1.5, 1.5, 0.5));
    const auto cs = collideMesh(box, Pose{Mat3::Identity(), Vec3(0, 0, 0.49)}, mesh, Pose{});
    CHECK_FALSE(cs.empty());
    for (const auto& c : cs) CHECK((c.triangle == 0 || c.triangle == 3));
    CHECK(contractViolation(box, Pose{Mat3::Identity(), Vec3(0, 0, 0.49)}, box.radius(), mesh, Pose{}, cs).empty());
}

TEST_CASE("mesh: overlapping() equals a brute-force box test") {
    Rng rng(11);
    MeshData m;
    for (int k = 0; k < 400; ++k) {
        const Vec3 centre(uniform(rng, 0, 10), uniform(rng, 0, 10), uniform(rng, 0, 10));
        const double r = logUniform(rng, 0.01, 1.5);
        const int base = static_cast<int>(m.vertices.size());
        for (int i = 0; i < 3; ++i) m.vertices.push_back(centre + r * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)));
        if (k % 37 == 5) m.triangles.push_back({base, base, base + 1});  // skipped
        else if (k % 37 == 9) {  // collinear: skipped
            m.vertices[base + 2] = 0.3 * m.vertices[base] + 0.7 * m.vertices[base + 1];
            m.triangles.push_back({base, base + 1, base + 2});
        } else
            m.triangles.push_back({base, base + 1, base + 2});
        // Some triangles reuse earlier vertices (a connected part).
        if (k > 10 && k % 5 == 0) m.triangles.push_back({base, base - 4, base - 8});
    }
    const TriangleMesh mesh(m.vertices, m.triangles);
    std::vector<Aabb> bounds;
    for (const auto& t : m.triangles) {
        Aabb b{m.vertices[t[0]], m.vertices[t[0]]};
        for (int i : t) b.lower = b.lower.cwiseMin(m.vertices[i]), b.upper = b.upper.cwiseMax(m.vertices[i]);
        bounds.push_back(b);
    }
    int nonEmpty = 0;
    for (int k = 0; k < 600; ++k) {
        Aabb box;
        if (k % 4 == 3) {  // exactly touching a triangle's bounds at a corner (closed boxes overlap)
            const Aabb& b = bounds[static_cast<std::size_t>(integer(rng, 0, static_cast<int>(bounds.size()) - 1))];
            box.lower = b.upper;
            box.upper = b.upper + Vec3::Constant(logUniform(rng, 1e-3, 1));
        } else {
            const Vec3 c(uniform(rng, -1, 11), uniform(rng, -1, 11), uniform(rng, -1, 11));
            const Vec3 h(logUniform(rng, 0.01, 3), logUniform(rng, 0.01, 3), logUniform(rng, 0.01, 3));
            box = {c - h, c + h};
        }
        std::vector<int> expected;
        for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t)
            if (mesh.triangleNormal(t).norm() > 0 && bounds[static_cast<std::size_t>(t)].overlaps(box)) expected.push_back(t);
        std::vector<int> got{-7};  // appended to
        mesh.overlapping(box, got);
        REQUIRE(!got.empty());
        CHECK(got.front() == -7);
        got.erase(got.begin());
        INFO("box " << show(box.lower) << " – " << show(box.upper));
        CHECK(got == expected);
        nonEmpty += !expected.empty();
    }
    CHECK(mesh.skippedTriangleCount() > 0);
    CHECK(nonEmpty > 100);
}

// =====================================================================================================
// 2. A flat triangulated floor against its plane
// =====================================================================================================

namespace {

enum class PoseKind { Tumbled, FaceDownTilted, FaceDownFlat };
enum class Snap { None, GridVertex, Seam, Diagonal };

struct FloorPose {
    Pose pose;
    double depth = 0;
};

// A pose of `body` resting on z = 0, overlapping it by `depth`, its lowest vertex at the
// horizontal point chosen by `snap` on the lattice of `cell`.
FloorPose floorPose(Rng& rng, const Body& body, PoseKind kind, Snap snap, double cell) {
    const Polytope& p = *body.poly;
    Mat3 r;
    if (kind == PoseKind::Tumbled) {
        r = randomRotation(rng);
    } else {
        const auto& f = p.faces()[static_cast<std::size_t>(integer(rng, 0, static_cast<int>(p.faces().size()) - 1))];
        const Mat3 down = Eigen::Quaterniond::FromTwoVectors(f.normal, -Vec3::UnitZ()).toRotationMatrix();
        const Mat3 spin = rotationAbout(Vec3::UnitZ(), uniform(rng, 0, 2 * M_PI));
        const double a = uniform(rng, 0, 2 * M_PI);
        // Tilted by less than half the angular tolerance (0.05 rad): the face stays the feature.
        const Mat3 tilt = kind == PoseKind::FaceDownTilted ? rotationAbout(Vec3(std::cos(a), std::sin(a), 0), uniform(rng, 0, 0.02))
                                                           : Mat3::Identity();
        r = tilt * spin * down;
    }
    int lowest = 0;
    for (int i = 0; i < static_cast<int>(p.vertices().size()); ++i)
        if ((r * p.vertices()[i]).z() < (r * p.vertices()[lowest]).z()) lowest = i;
    const Vec3 low = r * p.vertices()[lowest];
    FloorPose out;
    out.depth = body.size * uniform(rng, 1e-4, 0.03);
    Vec2 target(uniform(rng, -cell, cell), uniform(rng, -cell, cell));
    switch (snap) {
        case Snap::None: break;
        case Snap::GridVertex: target = Vec2(integer(rng, -1, 1) * cell, integer(rng, -1, 1) * cell); break;
        case Snap::Seam: target.x() = integer(rng, -1, 1) * cell; break;
        case Snap::Diagonal: {  // the diagonal of cell (0, 0) (even parity: from its corner (0,0) to (1,1))
            const double u = uniform(rng, 0, 1) * cell;
            target = Vec2(u, u);
            break;
        }
    }
    out.pose.rotation = r;
    out.pose.position = Vec3(target.x() - low.x(), target.y() - low.y(), -low.z() - out.depth);
    return out;
}

// The floor: a flat grid of `cell` covering the square of half side `reach` about the origin, its
// grid lines on the multiples of `cell`.
MeshData floorFor(double cell, double reach) {
    const int k = static_cast<int>(std::ceil(reach / cell)) + 1;
    return flatGrid(-k, -k, 2 * k, 2 * k, cell);
}

// Area of the body's cross-section region projected on the floor: the hull of its vertices below
// z = 0 and its edges' crossings of z = 0 (the contacts, all in the body and below the floor, lie
// in it).
double regionBelowArea(const Polytope& p, const Pose& pose) {
    const auto v = worldVertices(p, pose);
    std::vector<Vec2> pts;
    for (const Vec3& x : v)
        if (x.z() <= 0) pts.push_back(x.head<2>());
    for (const auto& e : p.edges()) {
        const Vec3 &a = v[static_cast<std::size_t>(e.tail)], &b = v[static_cast<std::size_t>(e.head)];
        if ((a.z() < 0) != (b.z() < 0)) {
            const double t = a.z() / (a.z() - b.z());
            pts.push_back((a + t * (b - a)).head<2>());
        }
    }
    return hullArea(pts);
}

std::vector<Vec2> planar(const std::vector<MeshContact>& cs) {
    std::vector<Vec2> p;
    for (const auto& c : cs) p.push_back(c.position.head<2>());
    return p;
}
std::vector<Vec2> planar(const Manifold& m) {
    std::vector<Vec2> p;
    for (int i = 0; i < m.pointCount; ++i) p.push_back(m.points[i].position.head<2>());
    return p;
}

// Whether the plane's answer is the whole contact region's support: its feature A is a vertex or
// an edge (points on one segment: any area is 0), or a face all of whose vertices are below the
// floor (then the region's polygon is that face, the plane's points are its vertices).
bool planeAnswerComplete(const Polytope& p, const Pose& pose, const Manifold& m) {
    if (m.featureA.type != FeatureType::Face) return true;
    const auto& f = p.faces()[static_cast<std::size_t>(m.featureA.index)];
    for (int k = 0; k < f.count; ++k)
        if (pose.apply(p.vertices()[static_cast<std::size_t>(p.faceVertices()[static_cast<std::size_t>(f.first + k)])]).z() >= 0) return false;
    return m.pointCount == f.count;
}

}  // namespace

TEST_CASE("mesh: a flat triangulated floor answers as its plane") {
    const Settings settings;
    const HalfSpace floorPlane{Vec3::UnitZ(), 0.0};
    const double cells[] = {0.17, 0.5, 1.3, 3.1};
    const double reach = 2 * 3.1 + 2 * 1.4;  // |lattice target| ≤ cell, body radius ≤ 1.4
    Rng rng(2024);
    int checked = 0, equalArea = 0, boundedArea = 0, translated = 0, rotatedSame = 0, rotatedDiffer = 0;
    int problems = 0;
    for (double cell : cells) {
        const MeshData m = floorFor(cell, std::max(reach, 3 * cell));
        const TriangleMesh mesh(m.vertices, m.triangles);
        for (int k = 0; k < 240; ++k) {
            const Body body = makeBody(rng, k % 2 == 0);
            const PoseKind kind = static_cast<PoseKind>(k / 2 % 3);
            const Snap snap = static_cast<Snap>(k / 6 % 4);
            const FloorPose fp = floorPose(rng, body, kind, snap, cell);
            const Polytope& p = *body.poly;
            const double s = body.size;
            const Manifold plane = collide(p, fp.pose, floorPlane, settings);
            const auto cs = collideMesh(p, fp.pose, mesh, Pose{}, settings);
            std::ostringstream where;
            where.precision(17);
            where << "cell " << cell << " pose #" << k << (body.box ? " box " + show(p.boxHalfExtents()) : " hull of " + std::to_string(p.vertices().size()) + " vertices")
                  << "\n" << describePose("body", fp.pose) << "\nplane: " << plane.pointCount << " points, depth " << plane.maxDepth()
                  << "\nmesh:" << describe(cs);
            INFO(where.str());
            REQUIRE(plane.pointCount > 0);
            REQUIRE(std::abs(plane.maxDepth() - fp.depth) <= kDepth * s);  // the plane itself is exact
            ++checked;
            bool ok = !cs.empty();
            CHECK(!cs.empty());
            if (cs.empty()) continue;
            const std::string violation = contractViolation(p, fp.pose, s, mesh, Pose{}, cs, settings);
            CHECK(violation == "");
            ok = ok && violation.empty();
            for (const auto& c : cs) {
                // The floor's face normal, exactly: −z. (The plane's own answer rounds its normal
                // through the body's frame: clang's build is off by more than 1e-12 there.)
                CHECK((c.normal - Vec3(0, 0, -1)).norm() <= kNormal);
                CHECK(c.position.z() <= kInside * s);                 // on/below the floor
                CHECK(std::abs((c.position - 0.5 * c.depth * c.normal).z()) <= kDepth * s);  // its mesh point on the floor
                ok = ok && (c.normal - Vec3(0, 0, -1)).norm() <= kNormal;
            }
            CHECK(std::abs(maxDepth(cs) - plane.maxDepth()) <= kDepth * s);
            ok = ok && std::abs(maxDepth(cs) - plane.maxDepth()) <= kDepth * s;
            // The support: the contacts' polygon against the plane's.
            const double meshArea = hullArea(planar(cs)), planeArea = hullArea(planar(plane));
            const double region = regionBelowArea(p, fp.pose);
            const double areaTol = 1e-9 * s * s;
            INFO("areas: mesh " << meshArea << " plane " << planeArea << " region below " << region);
            CHECK(meshArea <= region * (1 + 1e-6) + areaTol);
            if (plane.pointCount <= settings.maxBodyPairContacts && planeAnswerComplete(p, fp.pose, plane)) {
                // The mesh's candidates span the same polygon (the feature's vertices, all below the
                // floor, each inside some triangle; the rest on its edges or inside); at most
                // maxBodyPairContacts hull vertices are all kept, up to the reduction's hysteresis (a
                // point within 1 % of the best gain may stand in for a corner, at each of the
                // farthest / third / fourth picks) and near-duplicate merging (1e-3 of the extent):
                // 5 % of the area covers them.
                CHECK(std::abs(meshArea - planeArea) <= 0.05 * planeArea + areaTol);
                ok = ok && std::abs(meshArea - planeArea) <= 0.05 * planeArea + areaTol;
                ++equalArea;
            } else {
                // Sound bound of the greedy reduction (deepest p1, farthest p2 within 1 − h of the
                // farthest distance L, then the largest triangle and the largest added area, each within
                // 1 − h): every candidate lies within L of p1 and within the band of the two farthest
                // distances D+, D− on either side of p1p2, so the candidates' hull has area at most
                // 2L(D+ + D−), the kept one at least (1 − h)³·L(D+ + D−)/2: a quarter of it, times
                // (1 − h)³. The candidates' hull holds the plane's points (each below the floor, in a
                // triangle), so it bounds the plane's polygon too.
                const double h = settings.reductionHysteresis;
                CHECK(meshArea >= std::pow(1 - h, 3) / 4 * planeArea - 2e-3 * planeArea - areaTol);
                ++boundedArea;
            }

            // The same relative pose, the whole scene moved: translated only (exactly the same
            // answer, moved), and turned too (normals and deepest depth the same; the point set the
            // same unless the reduction's ties, broken along a fixed world direction, chose others).
            const Vec3 shift(uniform(rng, -10, 10), uniform(rng, -10, 10), uniform(rng, -10, 10));
            for (int turned = 0; turned < 2; ++turned) {
                const Mat3 g = turned ? randomRotation(rng) : Mat3::Identity();
                const Pose meshPose{g, shift};
                const Pose bodyPose{g * fp.pose.rotation, g * fp.pose.position + shift};
                const auto moved = collideMesh(p, bodyPose, mesh, meshPose, settings);
                std::vector<MeshContact> expected = cs;
                for (auto& c : expected) c.position = g * c.position + shift, c.normal = g * c.normal;
                const double tol = 1e-9 * (s + shift.norm());
                INFO((turned ? "turned" : "translated") << " by " << show(g) << " + " << show(shift) << "\nmoved:" << describe(moved));
                CHECK(moved.size() == cs.size());
                CHECK(std::abs(maxDepth(moved) - maxDepth(cs)) <= tol);
                for (const auto& c : moved) CHECK((c.normal - g * Vec3(0, 0, -1)).norm() <= 1e-12);
                const bool same = sameContactSet(moved, expected, tol);
                if (!turned) {
                    CHECK(same);
                    ++translated;
                } else {
                    same ? ++rotatedSame : ++rotatedDiffer;
                    // Whatever the choice, a valid one of the same support.
                    CHECK(contractViolation(p, bodyPose, s, mesh, meshPose, moved, settings) == "");
                }
            }
            if (!ok && ++problems <= 3) WARN("flat floor problem:\n" << where.str());
        }
    }
    WARN("flat floor: " << checked << " poses, " << equalArea << " with the plane's area, " << boundedArea
                        << " by the bound; turned scenes: " << rotatedSame << " the same set, " << rotatedDiffer
                        << " another (reduction ties along the world's identity direction)");
    CHECK(translated == checked);
}

// =====================================================================================================
// 3. Folded meshes: the contact contract
// =====================================================================================================

namespace {

// A V (valley, slope > 0) or a ridge (slope < 0) along the y axis: a grid of n × n cells of `cell`
// about the origin with z = slope·|x| (the fold on a grid line).
MeshData vFold(double slope, int n, double cell) {
    return gridMesh(-n / 2, -n / 2, n, n, cell, [&](double x, double, int, int) { return slope * std::abs(x); });
}

MeshData randomHeights(Rng& rng, int n, double cell, double amplitude) {
    std::vector<double> h(static_cast<std::size_t>((n + 1) * (n + 1)));
    for (double& x : h) x = uniform(rng, -amplitude, amplitude);
    return gridMesh(-n / 2, -n / 2, n, n, cell, [&](double, double, int i, int j) { return h[static_cast<std::size_t>(j * (n + 1) + i)]; });
}

}  // namespace

TEST_CASE("mesh: folded meshes keep the contact contract") {
    const Settings settings;
    Rng rng(99);
    struct Scene {
        std::string name;
        MeshData data;
        int kind;  // 0 valley, 1 ridge, 2 heights
        double slope = 0;
    };
    std::vector<Scene> scenes;
    for (double angle : {0.1, 0.4, 1.0}) {
        scenes.push_back({"valley " + std::to_string(angle), vFold(std::tan(angle / 2), 8, 1.0), 0, std::tan(angle / 2)});
        scenes.push_back({"ridge " + std::to_string(angle), vFold(-std::tan(angle / 2), 8, 1.0), 1, -std::tan(angle / 2)});
    }
    for (int k = 0; k < 3; ++k) scenes.push_back({"heights " + std::to_string(k), randomHeights(rng, 6, 0.8, 0.25), 2});
    int checked = 0, faces = 0, edges = 0, vertices = 0, problems = 0;
    for (const Scene& scene : scenes) {
        const TriangleMesh mesh(scene.data.vertices, scene.data.triangles);
        const double half = scene.kind == 2 ? 0.8 * 3 : 4.0;  // the mesh's half width
        std::vector<int> middle;  // triangles whose centroid is within half − 1.2 of the centre
        for (int t = 0; t < mesh.triangleCount(); ++t) {
            Vec3 c = Vec3::Zero();
            for (int i : mesh.triangle(t)) c += mesh.vertices()[i] / 3;
            if (c.head<2>().cwiseAbs().maxCoeff() <= half - 1.2) middle.push_back(t);
        }
        REQUIRE(middle.size() >= 4);
        for (int k = 0; k < 150; ++k) {
            const Body body = makeBody(rng, k % 2 == 0);
            const Polytope& p = *body.poly;
            const double s = body.size;
            // A triangle near the middle, a point q in it, the body's lowest vertex along −N placed
            // δ behind q.
            const int t = middle[static_cast<std::size_t>(integer(rng, 0, static_cast<int>(middle.size()) - 1))];
            Vec3 w[3];
            for (int i = 0; i < 3; ++i) w[i] = mesh.vertices()[mesh.triangle(t)[i]];
            double u = uniform(rng, 0, 1), v = uniform(rng, 0, 1);
            if (u + v > 1) u = 1 - u, v = 1 - v;
            if (k % 5 == 1) v = 0;  // on an edge (a seam or the fold)
            if (k % 5 == 2) u = v = 0;  // on a vertex
            const Vec3 q = w[0] + u * (w[1] - w[0]) + v * (w[2] - w[0]);
            const Vec3 N = mesh.triangleNormal(t);
            Mat3 r = randomRotation(rng);
            if (k % 3 == 0) {  // a face down on the triangle, tilted a little
                const auto& f = p.faces()[static_cast<std::size_t>(integer(rng, 0, static_cast<int>(p.faces().size()) - 1))];
                r = rotationAbout(N.unitOrthogonal(), uniform(rng, 0, 0.02)) *
                    Eigen::Quaterniond::FromTwoVectors(f.normal, -N).toRotationMatrix();
            }
            int lowest = 0;
            for (int i = 0; i < static_cast<int>(p.vertices().size()); ++i)
                if (N.dot(r * p.vertices()[i]) < N.dot(r * p.vertices()[lowest])) lowest = i;
            const double delta = s * uniform(rng, 1e-4, 0.05);
            const Pose pose{r, q - delta * N - r * p.vertices()[lowest]};
            const auto cs = collideMesh(p, pose, mesh, Pose{}, settings);
            std::ostringstream where;
            where.precision(17);
            where << scene.name << " pose #" << k << (body.box ? " box " + show(p.boxHalfExtents()) : " hull") << " on triangle " << t
                  << " δ " << delta << "\n" << describePose("body", pose) << "\nmesh:" << describe(cs);
            INFO(where.str());
            ++checked;
            // The body's lowest vertex is δ behind the triangle at q (inside it or on its boundary),
            // the body in front of it: there is a contact.
            CHECK(!cs.empty());
            const std::string violation = contractViolation(p, pose, s, mesh, Pose{}, cs, settings);
            CHECK(violation == "");
            bool ok = !cs.empty() && violation.empty();
            // Where the body stays off the mesh's boundary, the features are known: a valley has no
            // active edge there (every normal a face's), a ridge only the fold (every normal between
            // the two sides' normals).
            double reachXY = 0;
            for (const Vec3& x : worldVertices(p, pose)) reachXY = std::max(reachXY, x.head<2>().cwiseAbs().maxCoeff());
            const bool inside = reachXY < half - 1e-3;
            for (const auto& c : cs) {
                const std::string feature = normalFeature(mesh, Pose{}, c.triangle, c.normal);
                faces += feature == "face", edges += feature == "edge", vertices += feature == "vertex";
                if (!inside) continue;
                if (scene.kind == 0) {
                    CHECK(feature == "face");
                    ok = ok && feature == "face";
                }
                if (scene.kind == 1) {
                    // The sides' normals are (±slope, 0, 1) normalised: −n = a·left + b·right with
                    // a, b ≥ 0 has no y part and |x/z| ≤ |slope|. A face of the body resting on
                    // the fold keeps its own normal where that is within the angular tolerance of
                    // the fold's arc (the method's normal for a face on an edge): a y part up to the
                    // tolerance's sine, but never beyond either side's normal.
                    const Vec3 m = -c.normal;
                    const bool between = std::abs(m.y()) <= std::sin(settings.angularTolerance) + kCone && m.z() > 0 &&
                                         std::abs(m.x() / m.z()) <= std::abs(scene.slope) + kCone;
                    CHECK(between);
                    ok = ok && between;
                }
            }
            if (!ok && ++problems <= 3) WARN("folded mesh problem:\n" << where.str());
        }
    }
    WARN("folded meshes: " << checked << " poses; normals from faces " << faces << ", active edges " << edges << ", vertices " << vertices);
}

// =====================================================================================================
// 4. Seams
// =====================================================================================================

TEST_CASE("mesh: a box sliding across seams keeps the face normal and the plane's depth") {
    const Settings settings;
    const HalfSpace floorPlane{Vec3::UnitZ(), 0.0};
    const Polytope box = Polytope::box(Vec3(0.5, 0.3, 0.2));
    const double s = box.radius();
    int samples = 0;
    for (double cell : {1.0, 0.37}) {
        const MeshData m = floorFor(cell, 4);
        const TriangleMesh mesh(m.vertices, m.triangles);
        struct Orientation {
            const char* name;
            Mat3 r;
        };
        Rng rng(5);
        const Orientation orientations[] = {
            {"flat", Mat3::Identity()},
            {"flat, turned 0.3 rad", rotationAbout(Vec3::UnitZ(), 0.3)},
            {"tilted 0.01 rad about x", rotationAbout(Vec3::UnitX(), 0.01)},
            {"tilted 0.03 rad about (1, 1, 0), turned 1 rad", rotationAbout(Vec3(1, 1, 0), 0.03) * rotationAbout(Vec3::UnitZ(), 1.0)},
            {"on a vertex", randomRotation(rng)},
            {"on an edge", rotationAbout(Vec3::UnitX(), 0.7) * rotationAbout(Vec3::UnitZ(), 0.2)},
        };
        for (const auto& o : orientations) {
            double low = INFINITY;
            for (const Vec3& v : box.vertices()) low = std::min(low, (o.r * v).z());
            const double depth = 0.01;
            for (int dir = 0; dir < 3; ++dir)  // across x seams, y seams, and diagonally
                for (int i = 0; i <= 160; ++i) {
                    const double d = -0.8 * cell + i * 0.01 * cell;
                    const Vec3 offset = dir == 0 ? Vec3(d, 0.123 * cell, 0) : dir == 1 ? Vec3(0.271 * cell, d, 0) : Vec3(d, d, 0);
                    const Pose pose{o.r, offset + Vec3(0, 0, -low - depth)};
                    const Manifold plane = collide(box, pose, floorPlane, settings);
                    const auto cs = collideMesh(box, pose, mesh, Pose{}, settings);
                    INFO("cell " << cell << " " << o.name << " " << describePose("box", pose) << "\nmesh:" << describe(cs));
                    REQUIRE(!plane.empty());
                    REQUIRE(!cs.empty());
                    for (const auto& c : cs) REQUIRE((c.normal + Vec3::UnitZ()).norm() <= kNormal);
                    REQUIRE(std::abs(maxDepth(cs) - plane.maxDepth()) <= kDepth * s);
                    REQUIRE(std::abs(maxDepth(cs) - depth) <= kDepth * s);
                    REQUIRE(contractViolation(box, pose, s, mesh, Pose{}, cs, settings) == "");
                    ++samples;
                }
        }
    }
    CHECK(samples == 2 * 6 * 3 * 161);
}

// =====================================================================================================
// 5. The back side
// =====================================================================================================

TEST_CASE("mesh: a body behind the mesh gets no contacts") {
    const Settings settings;
    Rng rng(17);
    const MeshData m = floorFor(0.5, 4);
    const TriangleMesh mesh(m.vertices, m.triangles);
    for (int k = 0; k < 300; ++k) {
        const Body body = makeBody(rng, k % 2 == 0);
        const Polytope& p = *body.poly;
        const Mat3 r = randomRotation(rng);
        double high = -INFINITY;
        for (const Vec3& v : p.vertices()) high = std::max(high, (r * v).z());
        // Entirely below the floor: a gap of 0..2 sizes, or 1e-9..1e-2 of its size (touching it
        // from behind).
        const double top = k % 2 ? -body.size * uniform(rng, 0, 2) : -body.size * logUniform(rng, 1e-9, 1e-2);
        const Pose pose{r, Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), top - high)};
        const auto cs = collideMesh(p, pose, mesh, Pose{}, settings);
        INFO(describePose("body", pose) << " top " << top << "\nmesh:" << describe(cs));
        CHECK(cs.empty());
    }
}

// A body sunk through a flat floor, its centroid well behind and its top still in front by
// 1e-4..3e-2 of its size: what a body that went through a terrain in one step looks like. The mesh
// cannot tell it from one that came from behind, and pushes it back out to the front, as the plane
// would: the floor's normal, the plane's depth (its lowest vertex below the floor). A shape wholly
// behind gets nothing (the test above).
TEST_CASE("mesh: a body sunk through a floor with its top still in front is pushed back out to the front") {
    const Settings settings;
    Rng rng(18);
    const MeshData m = floorFor(0.5, 4);
    const TriangleMesh mesh(m.vertices, m.triangles);
    int compared = 0;
    for (int k = 0; k < 200; ++k) {
        const Body body = makeBody(rng, k % 2 == 0);
        const Polytope& p = *body.poly;
        const Mat3 r = randomRotation(rng);
        double high = -INFINITY, low = INFINITY;
        for (const Vec3& v : p.vertices()) high = std::max(high, (r * v).z()), low = std::min(low, (r * v).z());
        const double top = body.size * uniform(rng, 1e-4, 0.03);
        const Pose pose{r, Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), top - high)};
        if (pose.apply(p.centroid()).z() > -0.2 * body.size) continue;  // its centroid well behind
        const auto cs = collideMesh(p, pose, mesh, Pose{}, settings);
        INFO(describePose("body", pose) << " top " << top << " size " << body.size << "\nmesh:" << describe(cs));
        REQUIRE(!cs.empty());
        for (const auto& c : cs) CHECK((c.normal - Vec3(0, 0, -1)).norm() < 1e-12);
        CHECK(std::abs(maxDepth(cs) - (high - low - top)) < kDepth * body.size);
        ++compared;
    }
    CHECK(compared > 50);
}

// A rock lowered into rugged terrain (random heights; a smooth wave whose folds stay within the
// angular tolerance) a centimetre at a time, as a falling body meets it: every pose in which it
// penetrates — a vertex of it below a triangle, within the triangle's shadow, or a terrain vertex
// inside it (the exact test for a height field) — gets contacts, each a real overlap (depth > 0, a
// unit normal; "folded meshes keep the contact contract" checks the normals). Deep in a surface that curves within the tolerance, A's feature along
// each triangle's normal can lie over another triangle; before the sunk-vertex fallback such poses
// got nothing (40 of 23 000 here), and a rock could fall through.
TEST_CASE("mesh: a rock lowered into rugged terrain gets contacts in every pose it penetrates") {
    const Settings settings;
    Rng rng(35);
    const MeshData terrains[2] = {
        randomHeights(rng, 16, 0.25, 0.12),
        gridMesh(-8, -8, 16, 16, 0.25, [](double x, double y, int, int) { return 0.3 * std::sin(1.7 * x) * std::cos(1.3 * y); })};
    int penetrating = 0;
    for (const MeshData& m : terrains) {
        const TriangleMesh mesh(m.vertices, m.triangles);
        // The depth of p below the triangle straight above or below it (a height field has one), along
        // that triangle's normal; ≤ 0: above the surface.
        auto below = [&](const Vec3& p) {
            auto left = [](const Vec3& a, const Vec3& b, const Vec3& q) {
                return (b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x());
            };
            double deepest = -INFINITY;
            for (int t = 0; t < mesh.triangleCount(); ++t) {
                Vec3 w[3];
                for (int i = 0; i < 3; ++i) w[i] = mesh.vertices()[mesh.triangle(t)[i]];
                if (left(w[0], w[1], p) >= 0 && left(w[1], w[2], p) >= 0 && left(w[2], w[0], p) >= 0)
                    deepest = std::max(deepest, mesh.triangleNormal(t).dot(w[0] - p));
            }
            return deepest;
        };
        for (int rock = 0; rock < 40; ++rock) {
            const Body body = makeBody(rng, false);
            const Polytope& p = *body.poly;
            const Mat3 r = randomRotation(rng);
            const Vec3 at(uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0), 0);
            for (double z = 1.0; z > -1.0; z -= 0.01) {
                const Pose pose{r, at + Vec3(0, 0, z)};
                double depth = 0;
                for (const Vec3& v : worldVertices(p, pose)) depth = std::max(depth, below(v));
                for (const Vec3& x : mesh.vertices()) {
                    const Vec3 local = pose.applyInverse(x);
                    double inside = INFINITY;
                    for (const Polytope::Face& face : p.faces()) inside = std::min(inside, face.offset - face.normal.dot(local));
                    depth = std::max(depth, inside);
                }
                if (!(depth > 1e-6)) continue;
                if (depth > 0.5 * body.size) break;
                ++penetrating;
                const auto cs = collideMesh(p, pose, mesh, Pose{}, settings);
                INFO(describePose("rock", pose) << " penetrating " << depth << " size " << body.size << "\nmesh:" << describe(cs));
                REQUIRE(!cs.empty());
                for (const auto& c : cs) {
                    CHECK(c.depth > 0);
                    CHECK(c.position.allFinite());
                    CHECK(std::abs(c.normal.norm() - 1) < 1e-12);
                }
            }
        }
    }
    CHECK(penetrating > 1000);
}

// =====================================================================================================
// 6. Determinism
// =====================================================================================================

TEST_CASE("mesh: the same input gives the same output and a permuted triangle order the same set") {
    const Settings settings;
    Rng rng(31);
    struct Scene {
        const char* name;
        MeshData data;
    };
    std::vector<Scene> scenes = {{"flat 0.3", floorFor(0.3, 3)}, {"flat 1.1", floorFor(1.1, 4)},
                                 {"valley", vFold(std::tan(0.2), 8, 1.0)}, {"ridge", vFold(-std::tan(0.2), 8, 1.0)},
                                 {"heights", randomHeights(rng, 6, 0.8, 0.25)}};
    int differ = 0, total = 0, labelsDiffer = 0;
    for (const Scene& scene : scenes) {
        const TriangleMesh mesh(scene.data.vertices, scene.data.triangles);
        std::vector<int> order(scene.data.triangles.size());
        std::iota(order.begin(), order.end(), 0);
        std::shuffle(order.begin(), order.end(), rng);
        Triangles permuted;
        for (int i : order) permuted.push_back(scene.data.triangles[static_cast<std::size_t>(i)]);
        const TriangleMesh shuffled(scene.data.vertices, permuted);
        for (int k = 0; k < 120; ++k) {
            const Body body = makeBody(rng, k % 2 == 0);
            const Polytope& p = *body.poly;
            const Mat3 r = randomRotation(rng);
            double low = INFINITY;
            const Vec2 xy(uniform(rng, -1, 1), uniform(rng, -1, 1));
            // Lowered onto the surface below its centre: its lowest vertex a little under the
            // highest mesh point there (found by the mesh's own vertices: a coarse but sufficient
            // height for overlapping most of the time).
            double ground = -INFINITY;
            for (const Vec3& v : scene.data.vertices)
                if ((v.head<2>() - xy).norm() < 1.0) ground = std::max(ground, v.z());
            for (const Vec3& v : p.vertices()) low = std::min(low, (r * v).z());
            const Pose pose{r, Vec3(xy.x(), xy.y(), ground - low - body.size * uniform(rng, 0, 0.05))};
            const auto first = collideMesh(p, pose, mesh, Pose{}, settings);
            const auto second = collideMesh(p, pose, mesh, Pose{}, settings);
            INFO(scene.name << " " << describePose("body", pose) << "\nfirst:" << describe(first));
            REQUIRE(first.size() == second.size());
            for (std::size_t i = 0; i < first.size(); ++i) {
                CHECK(first[i].position == second[i].position);
                CHECK(first[i].normal == second[i].normal);
                CHECK(first[i].depth == second[i].depth);
                CHECK(first[i].triangle == second[i].triangle);
            }
            const auto other = collideMesh(p, pose, shuffled, Pose{}, settings);
            ++total;
            const bool same = sameContactSet(first, other, 1e-12);
            if (!same) {
                ++differ;
                if (differ <= 5)
                    WARN("permuted triangle order gives another set: " << scene.name << " " << describePose("body", pose)
                                                                      << "\noriginal:" << describe(first) << "\npermuted:" << describe(other));
            } else {
                // The same points: from the same triangles (mapped), unless two triangles gave
                // the same point (a seam: either is right).
                for (const auto& c : other) {
                    const int original = order[static_cast<std::size_t>(c.triangle)];
                    bool labelled = false;
                    for (const auto& d : first) labelled = labelled || ((d.position - c.position).norm() <= 1e-12 && d.triangle == original);
                    labelsDiffer += !labelled;
                }
            }
            CHECK(same);
        }
    }
    WARN("permutation: " << differ << " of " << total << " contact sets differ; " << labelsDiffer
                         << " contacts labelled with another triangle (the same point from two triangles)");
}

// =====================================================================================================
// 7. The triangle filter (ODE's dTriCallback)
// =====================================================================================================

// A refused triangle is not collided, and it does not change which edges of the others are active:
// no contact comes from it, and where no triangle under the body is refused the answer is the
// unfiltered one (to rounding: a flat region's plane is lifted once, from its first triangle's
// offset, and which triangle comes first depends on the filter). Where some are refused, the rest
// still answer with the floor's normal.
TEST_CASE("mesh: a triangle filter leaves out the triangles it refuses before the reduction") {
    const Settings settings;
    Rng rng(44);
    const MeshData floor = floorFor(0.3, 2.0);
    const TriangleMesh mesh(floor.vertices, floor.triangles);
    struct Refusing {
        int modulus;
        static bool accepts(void* context, int t) { return t % static_cast<Refusing*>(context)->modulus != 0; }
    };
    int compared = 0, refusedSome = 0;
    for (int k = 0; k < 200; ++k) {
        const Body body = makeBody(rng, k % 2 == 0);
        const Polytope& p = *body.poly;
        const Mat3 r = randomRotation(rng);
        double low = INFINITY;
        for (const Vec3& v : p.vertices()) low = std::min(low, (r * v).z());
        const Pose pose{r, Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), -low - body.size * uniform(rng, 1e-3, 0.05))};
        Refusing refusing{2 + k % 3};
        std::vector<MeshContact> filtered, all;
        collide(p, pose, mesh, Pose{}, settings, filtered, TriangleFilter{&Refusing::accepts, &refusing});
        collide(p, pose, mesh, Pose{}, settings, all);
        bool anyRefusedUnder = false;
        for (const auto& c : all) anyRefusedUnder = anyRefusedUnder || !Refusing::accepts(&refusing, c.triangle);
        for (const auto& c : filtered) CHECK(Refusing::accepts(&refusing, c.triangle));
        if (!anyRefusedUnder) {
            REQUIRE(filtered.size() == all.size());
            for (std::size_t i = 0; i < all.size(); ++i) {
                CHECK((filtered[i].position - all[i].position).norm() <= 1e-12 * body.size);
                CHECK(std::abs(filtered[i].depth - all[i].depth) <= 1e-12 * body.size);
            }
        } else {
            ++refusedSome;
            for (const auto& c : filtered) CHECK((c.normal - Vec3(0, 0, -1)).norm() < 1e-12);
        }
        ++compared;
    }
    CHECK(compared == 200);
    CHECK(refusedSome > 50);
}
