// Terrain (issue 34): bodies at rest on a triangle-mesh ground (dCreateTriMesh, 24 × 24 cells of
// 0.25 m, 1152 triangles, built here with dGeomTriMeshDataBuildDouble from a height grid). Its west
// half is a flat plateau at z = 0 with two smooth bumps, its east half a 4° slope rising along +x
// from the fold at x = 0 (below the friction angle atan 0.6 = 31°: what rests there must stay).
// On the plateau: two boxes, three rocks (one at a bump's foot), a standing barrel (dCylinder), a
// lying barrel and a lying capsule (dCapsule); on the slope: two boxes, a rock and a wheel on its
// tread (a narrow dCylinder, axis along the fall line, so rolling would take it across the slope,
// which is level). Every body starts a centimetre above the surface, along its normal. The bumps
// also raise the vertices of the cells their rims cross, so those cells are not level: every
// plateau body but the rock at the bump's foot lies on cells that are exactly flat (a lying barrel
// whose end touched such a cell, tilted 1.8°, was pushed off it and rolled on at 0.017 m/s, with
// every method: that is the geometry, not a collider's error).
//
// The methods on the mesh: gdcontact takes box-, convex-, capsule- and cylinder-trimesh
// (gdc::ode::handles); ODE's own trimesh colliders take them under --method ode. Contact
// tracking (libccd's MPR) needs two convex shapes and a mesh is none, so under --method tracking
// every body–terrain pair is left to ODE's trimesh colliders, as under --method ode (its bodies
// touch nothing else here): the tracking run is ODE's, up to that.
//
// The geometric penetration measure is TerrainGround::penetration (the deepest body vertex below
// the triangle under it, or terrain vertex inside a body); round parts are measured as their
// tessellations (up to its sagitta, under 1 % of the radius), as in the barrels scene.
#include "resting_scene.hpp"
#include "scene_registry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace gdc::scenes {
namespace {

constexpr double kGap = 0.01;                          // m: each body starts this far above the surface
constexpr int kCells = 24;                             // per side
constexpr double kCell = 0.25;                         // m
constexpr double kHalfSize = 0.5 * kCells * kCell;     // the grid spans [−3, 3]² m
const double kSlope = std::tan(4.0 * kPi / 180.0);     // east half: z = kSlope · x

struct Bump {
    double x, y, radius, height;
};
constexpr std::array<Bump, 2> kBumps{{{-2.0, 1.75, 0.9, 0.15}, {-0.5, 2.4, 0.5, 0.1}}};

/// The ground's height: the plateau and its bumps (height·(1 − (r/R)²)², smooth where it meets
/// the flat: no crease at its rim), or the slope.
double height(double x, double y) {
    if (x > 0.0) return kSlope * x;
    double z = 0.0;
    for (const Bump& bump : kBumps) {
        const double s = std::hypot(x - bump.x, y - bump.y) / bump.radius;
        if (s < 1.0) z += bump.height * (1.0 - s * s) * (1.0 - s * s);
    }
    return z;
}

/// The surface's unit normal where bodies are placed (the plateau away from the bumps, the slope).
Vec3 normalAt(double x) { return x > 0.0 ? Vec3(-kSlope, 0.0, 1.0).normalized() : Vec3::UnitZ(); }

/// The lowest point along `n` of the part turned by `rotation` (its origin at 0): a box's or a
/// hull's lowest vertex, a capsule's or a cylinder's exact support.
double lowest(const PlacedPart& part, const Mat3& rotation, const Vec3& n) {
    const Vec3 axis = rotation * Vec3::UnitZ();
    const double along = std::abs(n.dot(axis)), half = 0.5 * part.roundLength;
    if (part.round == RoundKind::Capsule) return -along * half - part.roundRadius;
    if (part.round == RoundKind::Cylinder)
        return -along * half - part.roundRadius * std::sqrt(std::max(0.0, 1.0 - along * along));
    double low = 0.0;
    for (const Vec3& v : part.shape->vertices()) low = std::min(low, n.dot(rotation * v));
    return low;
}

class Terrain final : public RestingScene {
public:
    explicit Terrain(const SceneOptions& options) : RestingScene("terrain", options) {}

private:
    void build() override {
        addGround();
        addBoxes();
        addRocks();
        addRoundBodies();
    }

    void addGround() {
        std::vector<Vec3> vertices;
        for (int j = 0; j <= kCells; ++j)
            for (int i = 0; i <= kCells; ++i) {
                const double x = -kHalfSize + kCell * i, y = -kHalfSize + kCell * j;
                vertices.emplace_back(x, y, height(x, y));
            }
        std::vector<std::array<int, 3>> triangles;
        auto at = [](int i, int j) { return j * (kCells + 1) + i; };
        for (int j = 0; j < kCells; ++j)
            for (int i = 0; i < kCells; ++i) {
                // Counter-clockwise seen from above: +x, then +y.
                triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        addTerrain(std::move(vertices), std::move(triangles));
    }

    /// A body of one part resting at (x, y) on the plateau or the slope, turned by `heading` about
    /// the surface's normal after `local` (the part's own rotation), kGap above the surface.
    Body& place(const std::string& name, const PlacedPart& part, double density, double x, double y, const Mat3& local,
                double heading, std::array<float, 3> colour) {
        const Vec3 n = normalAt(x);
        const Mat3 tilt = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), n).toRotationMatrix();
        Pose pose;
        pose.rotation = tilt * Eigen::AngleAxisd(heading, Vec3::UnitZ()).toRotationMatrix() * local;
        pose.position = Vec3(x, y, height(x, y)) + (kGap - lowest(part, pose.rotation, n)) * n;
        return addBody(name, {part}, density, pose, colour);
    }

    void addBoxes() {
        const std::array<float, 3> crate{0.6f, 0.45f, 0.3f};
        struct Spot {
            Vec3 half;
            double x, y, heading;
        };
        const std::array<Spot, 4> spots{{{{0.3, 0.2, 0.15}, -2.0, -1.5, 0.0},
                                         {{0.15, 0.15, 0.15}, -0.9, -2.2, 0.4},
                                         {{0.2, 0.2, 0.1}, 1.0, -1.5, 0.0},
                                         {{0.3, 0.15, 0.12}, 2.2, -0.4, 0.5}}};
        for (const Spot& spot : spots)
            place("box", PlacedPart{makeBox(spot.half), Pose{}, true, spot.half}, 600.0, spot.x, spot.y,
                  Mat3::Identity(), spot.heading, crate);
    }

    void addRocks() {
        // Lumpy spheres: 20 random points each at 0.09–0.14 m from the centre, seeded, as hulls
        // about their centroids (ODE's convex colliders measure from a dConvex's origin).
        const std::array<float, 3> stone{0.5f, 0.5f, 0.47f};
        Random random(34);
        const std::array<Vec3, 4> spots{{{-2.3, -0.3, 0.3}, {-1.3, -0.7, 1.9}, {-1.15, 1.75, 0.8}, {1.5, 0.8, 2.6}}};
        for (const Vec3& spot : spots) {
            std::vector<Vec3> points;
            for (int i = 0; i < 20; ++i) {
                const double z = random.uniform(-1.0, 1.0), phi = random.uniform(0.0, 2 * kPi);
                const double r = std::sqrt(1.0 - z * z), radius = random.uniform(0.09, 0.14);
                points.push_back(radius * Vec3(r * std::cos(phi), r * std::sin(phi), z));
            }
            const auto hull = centredOnCentroid(Polytope::fromPoints(points)).first;
            place("rock", PlacedPart{hull, Pose{}}, 2500.0, spot.x(), spot.y(), Mat3::Identity(), spot.z(), stone);
        }
    }

    void addRoundBodies() {
        const Mat3 alongX = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitX()).toRotationMatrix();
        const Mat3 alongY = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitY()).toRotationMatrix();
        place("barrel", makeCylinderPart(0.15, 0.4), 700.0, -0.6, -0.3, Mat3::Identity(), 0.0, {0.75f, 0.35f, 0.2f});
        place("lying barrel", makeCylinderPart(0.15, 0.4), 700.0, -1.7, 0.3, alongY, 0.0, {0.8f, 0.55f, 0.2f});
        place("capsule", makeCapsulePart(0.07, 0.45), 1000.0, -2.5, 0.3, alongY, 0.0, {0.35f, 0.6f, 0.85f});
        place("wheel", makeCylinderPart(0.22, 0.1), 900.0, 1.8, 2.0, alongX, 0.0, {0.25f, 0.25f, 0.28f});
    }
};

}  // namespace

std::unique_ptr<Scene> makeTerrain(const SceneOptions& options) { return std::make_unique<Terrain>(options); }

}  // namespace gdc::scenes
