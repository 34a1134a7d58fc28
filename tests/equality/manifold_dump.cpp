// Proof that a restructuring of the pipeline changed no answer: every manifold collide() returns on
// a fixed stream of random poses of every pair type, written to a file by one build and compared
// with another build's file.
//
//   manifold_dump dump FILE             (run by the build before the change and by the build after)
//   manifold_dump compare BEFORE AFTER  (largest difference in normal, depth and points per pair type)
//
// The poses come from std::mt19937 with fixed seeds, so two builds with the same compiler and
// standard library make the same stream. Pair types: box–box of seven kinds (resting face, face
// near the angular tolerance, edge–edge, vertex–face, deep, nearly touching, separated/random),
// box–plane, hull–plane (small hulls and one above the vertex loop's limit), hull–hull (small hulls,
// a tessellated sphere whose faces come with caps, an elongated prism), box–hull, and the curved
// kinds on a plane (sphere, capsule, cylinder: a cap level with the plane, tilted within and beyond
// the angular tolerance, a side lying) and cylinder–cylinder (caps stacked, crossing, at random). Settings vary
// per pose (margin, contact budget, spanning the region, angular tolerance). compare exits 1 when a
// count or a feature differs, or when a value differs by more than 1e-9 of the pair's size.
#include <gdcontact/collide.hpp>

#include "box_poses.hpp"
#include "geometry_oracles.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace gdc;
using testing::randomHalfExtents;
using testing::randomRotation;
using testing::tilt;

namespace {

Settings randomSettings(std::mt19937& random, double size) {
    std::uniform_real_distribution<double> unit(0, 1);
    Settings settings;
    settings.maxContacts = 1 + static_cast<int>(unit(random) * 8) % 8;
    settings.margin = unit(random) < 0.5 ? 0.0 : unit(random) * 0.02 * size;
    settings.spanContactRegion = unit(random) < 0.5;
    if (unit(random) < 0.2) settings.angularTolerance = unit(random) * 0.8;  // beyond 0.7: the general path
    return settings;
}

// The box–box kinds, in box_poses.hpp's order (its Scattered, at 1.1 of the size, mostly separated).
enum Kind { RestingFace, FaceNearTolerance, EdgeEdge, VertexFace, Deep, NearlyTouching, Separated, KindCount };
const char* kKindNames[KindCount] = {"resting-face", "face-near-tolerance", "edge-edge", "vertex-face",
                                     "deep",         "nearly-touching",     "separated"};

// One answer as written to the file: the pair type, the pair's size, then the manifold.
struct Record {
    int type;
    double size;
    Manifold manifold;
};

void write(std::FILE* out, int type, double size, const Manifold& m) {
    std::fwrite(&type, sizeof type, 1, out);
    std::fwrite(&size, sizeof size, 1, out);
    std::fwrite(m.normal.data(), sizeof(double), 3, out);
    std::fwrite(&m.pointCount, sizeof m.pointCount, 1, out);
    const int features[4] = {int(m.featureA.type), m.featureA.index, int(m.featureB.type), m.featureB.index};
    std::fwrite(features, sizeof(int), 4, out);
    for (int i = 0; i < m.pointCount; ++i) {
        std::fwrite(m.points[i].position.data(), sizeof(double), 3, out);
        std::fwrite(&m.points[i].depth, sizeof(double), 1, out);
    }
}

bool read(std::FILE* in, Record& r) {
    if (std::fread(&r.type, sizeof r.type, 1, in) != 1) return false;
    std::fread(&r.size, sizeof r.size, 1, in);
    std::fread(r.manifold.normal.data(), sizeof(double), 3, in);
    std::fread(&r.manifold.pointCount, sizeof(int), 1, in);
    int features[4];
    std::fread(features, sizeof(int), 4, in);
    r.manifold.featureA = {FeatureType(features[0]), features[1]};
    r.manifold.featureB = {FeatureType(features[2]), features[3]};
    for (int i = 0; i < r.manifold.pointCount; ++i) {
        std::fread(r.manifold.points[i].position.data(), sizeof(double), 3, in);
        std::fread(&r.manifold.points[i].depth, sizeof(double), 1, in);
    }
    return true;
}

// Pair types in the file: box–box kinds 0..6, then these.
enum {
    BoxPlane = KindCount, HullPlane, HullHull, BoxHull, SpherePlane, CapsulePlane, CylinderPlane, CylinderCylinder,
    TypeCount
};
std::string typeName(int type) {
    if (type < KindCount) return std::string("box-box ") + kKindNames[type];
    const char* names[] = {"box-plane",     "hull-plane",     "hull-hull",        "box-hull",
                           "sphere-plane",  "capsule-plane",  "cylinder-plane",   "cylinder-cylinder"};
    return names[type - KindCount];
}

std::vector<Vec3> sphereHullPoints(std::mt19937& random, int count, const Vec3& scale) {
    std::normal_distribution<double> normal;
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i)
        points.push_back(Vec3(normal(random), normal(random), normal(random)).normalized().cwiseProduct(scale));
    return points;
}

// The hulls of the hull pairs: small random hulls, a cube's hull, a tessellated sphere (caps at
// larger tolerances), a long thin prism.
std::vector<Polytope> makeHulls(std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<Polytope> hulls;
    std::vector<Vec3> cube;
    for (int v = 0; v < 8; ++v) cube.push_back(Vec3(v & 1 ? 0.5 : -0.5, v & 2 ? 0.5 : -0.5, v & 4 ? 0.5 : -0.5));
    hulls.push_back(Polytope::fromPoints(cube));
    for (int i = 0; i < 12; ++i) {
        const int count = 6 + static_cast<int>(unit(random) * 27);
        hulls.push_back(Polytope::fromPoints(
            sphereHullPoints(random, count, Vec3(0.2 + unit(random), 0.2 + unit(random), 0.2 + unit(random)))));
    }
    // A tessellated sphere: near-coplanar neighbouring faces (caps), and above the vertex loop's limit.
    std::vector<Vec3> sphere;
    const int rings = 10, segments = 16;
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double theta = M_PI * r / rings, phi = 2 * M_PI * s / segments;
            sphere.push_back(0.6 * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
        }
    sphere.push_back(Vec3(0, 0, 0.6)), sphere.push_back(Vec3(0, 0, -0.6));
    hulls.push_back(Polytope::fromPoints(sphere));
    std::vector<Vec3> prism;
    for (int s = 0; s < 6; ++s)
        for (double z : {-1.5, 1.5})
            prism.push_back(Vec3(0.15 * std::cos(M_PI * s / 3), 0.15 * std::sin(M_PI * s / 3), z));
    hulls.push_back(Polytope::fromPoints(prism));
    return hulls;
}

Pose hullPose(const Polytope& a, const Polytope& b, std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0, 1), symmetric(-1, 1);
    const double size = a.radius() + b.radius();
    const double pick = unit(random);
    const Mat3 rotation = pick < 0.3 ? tilt(random, 0.05) : randomRotation(random);
    if (pick < 0.85) {
        // B's lowest point near A's highest along a random direction (from 0.2 % apart to 1 % sunk).
        const Vec3 up = pick < 0.3 ? Vec3(Vec3::UnitZ()) : Vec3(randomRotation(random) * Vec3::UnitZ());
        const Vec3 highestA = a.vertices()[a.supportVertex(up)];
        const Vec3 lowestB = rotation * b.vertices()[b.supportVertex(rotation.transpose() * -up)];
        const Vec3 sideways = Vec3(symmetric(random), symmetric(random), symmetric(random)) * (0.05 * size);
        const Vec3 slide = sideways - sideways.dot(up) * up;
        return Pose{rotation, highestA - lowestB + slide - up * (size * (0.004 + 0.006 * symmetric(random)))};
    }
    return Pose{rotation, Vec3(symmetric(random), symmetric(random), symmetric(random)) * (0.7 * size)};
}

int dump(const char* path) {
    std::FILE* out = std::fopen(path, "wb");
    if (!out) return std::perror(path), 2;
    std::uniform_real_distribution<double> unit(0, 1), symmetric(-1, 1);
    // Box–box: 20 000 poses of each kind.
    {
        std::mt19937 random(20261126);
        for (int trial = 0; trial < 20000 * KindCount; ++trial) {
            const Vec3 halfA = randomHalfExtents(random), halfB = randomHalfExtents(random);
            const Polytope a = Polytope::box(halfA), b = Polytope::box(halfB);
            const Settings settings = randomSettings(random, halfA.norm() + halfB.norm());
            const Kind kind = Kind(trial % KindCount);
            const Pose relative = testing::boxPoseOfKind(testing::BoxPoseKind(kind), halfA, halfB, settings.angularTolerance, 1.1, random);
            const Pose world{randomRotation(random), Vec3(unit(random), unit(random), unit(random)) * 10};
            const Pose poseB{world.rotation * relative.rotation, world.apply(relative.position)};
            write(out, kind, a.radius() + b.radius(), collide(a, world, b, poseB, settings));
        }
    }
    std::mt19937 random(20261127);
    const std::vector<Polytope> hulls = makeHulls(random);
    auto planeNear = [&](const Polytope& a, const Pose& pose) {
        // A plane through a point near A's lowest along a random (often nearly vertical) normal.
        const Vec3 normal = (unit(random) < 0.5 ? tilt(random, 0.02) : randomRotation(random)) * Vec3::UnitZ();
        const Vec3 lowest = pose.apply(a.vertices()[a.supportVertex(pose.rotation.transpose() * -normal)]);
        const double offset = normal.dot(lowest) + a.radius() * 0.02 * symmetric(random);
        return HalfSpace{normal * (unit(random) < 0.5 ? 1.0 : 3.0), offset * (unit(random) < 0.5 ? 1.0 : 3.0)};
    };
    auto randomPose = [&] {
        return Pose{unit(random) < 0.3 ? tilt(random, 0.02) : randomRotation(random),
                    Vec3(symmetric(random), symmetric(random), symmetric(random)) * 5};
    };
    // Box–plane and hull–plane: 100 000 each. A HalfSpace{n, o} scaled by 3 is the same plane.
    for (int trial = 0; trial < 100000; ++trial) {
        const Polytope a = Polytope::box(randomHalfExtents(random));
        const Settings settings = randomSettings(random, a.radius());
        const Pose pose = randomPose();
        const HalfSpace plane = planeNear(a, pose);
        write(out, BoxPlane, a.radius(), collide(a, pose, plane, settings));
    }
    for (int trial = 0; trial < 100000; ++trial) {
        const Polytope& a = hulls[trial % hulls.size()];
        const Settings settings = randomSettings(random, a.radius());
        const Pose pose = randomPose();
        const HalfSpace plane = planeNear(a, pose);
        write(out, HullPlane, a.radius(), collide(a, pose, plane, settings));
    }
    // Hull–hull and box–hull: 100 000 each.
    for (int trial = 0; trial < 100000; ++trial) {
        const Polytope& a = hulls[trial % hulls.size()];
        const Polytope& b = hulls[(trial / hulls.size()) % hulls.size()];
        const Settings settings = randomSettings(random, a.radius() + b.radius());
        const Pose relative = hullPose(a, b, random);
        const Pose world = randomPose();
        const Pose poseB{world.rotation * relative.rotation, world.apply(relative.position)};
        write(out, HullHull, a.radius() + b.radius(), collide(a, world, b, poseB, settings));
    }
    for (int trial = 0; trial < 100000; ++trial) {
        const Polytope a = Polytope::box(randomHalfExtents(random));
        const Polytope& b = hulls[trial % hulls.size()];
        const Settings settings = randomSettings(random, a.radius() + b.radius());
        const Pose relative = hullPose(a, b, random);
        const Pose world = randomPose();
        const Pose poseB{world.rotation * relative.rotation, world.apply(relative.position)};
        write(out, BoxHull, a.radius() + b.radius(), collide(a, world, b, poseB, settings));
    }
    // The curved kinds on a plane: 50 000 each. The plane's normal along the shape's axis (a cap or
    // an end level with it), tilted a little (within and beyond the angular tolerance), across the
    // axis (a side lying) or at random; its offset from the shape's lowest point up to 2 % of its
    // size either way.
    for (int kind = 0; kind < 3; ++kind)
        for (int trial = 0; trial < 50000; ++trial) {
            const double radius = 0.05 + unit(random), length = 0.05 + 2 * unit(random);
            const ShapeRef shape = kind == 0   ? ShapeRef(Sphere{radius})
                                   : kind == 1 ? ShapeRef(Capsule{radius, length})
                                               : ShapeRef(Cylinder{radius, length});
            const double size = kind == 0 ? radius : kind == 1 ? radius + 0.5 * length : std::hypot(radius, 0.5 * length);
            const Settings settings = randomSettings(random, size);
            const Pose pose = randomPose();
            const double pick = unit(random);
            const Vec3 axis = pose.rotation.col(2), across = pose.rotation.col(0);
            const Vec3 normal = pick < 0.3   ? Vec3(axis)
                                : pick < 0.6 ? Vec3(tilt(random, 0.1) * axis)
                                : pick < 0.8 ? Vec3(tilt(random, 0.02) * across)
                                             : Vec3(randomRotation(random) * Vec3::UnitZ());
            // The shape's lowest point along the plane's normal (the solid is on its −normal side):
            // the shape's support along −normal.
            const Vec3 local = pose.rotation.transpose() * -normal;
            const double radial = std::hypot(local.x(), local.y());
            const Vec3 axial(0, 0, kind == 0 ? 0.0 : (local.z() >= 0 ? 0.5 * length : -0.5 * length));
            const Vec3 reach = kind == 2 ? Vec3(radial > 0 ? Vec3(radius * local.x() / radial, radius * local.y() / radial, 0)
                                                           : Vec3(radius, 0, 0)) + axial
                                         : Vec3(axial + radius * local);
            const double offset = normal.dot(pose.apply(reach)) + size * 0.02 * symmetric(random);
            write(out, SpherePlane + kind, size, collide(shape, pose, HalfSpace{normal, offset}, Pose{}, settings));
        }
    // Cylinder–cylinder: 50 000. B's cap on A's (coaxial within 0.05 rad, offset up to a radius), B
    // lying across A's cap, or at random; touching along the axis or a random direction, then pushed
    // in by up to 2 % of the size.
    auto cylinderSupport = [](const Cylinder& c, const Pose& pose, const Vec3& d) {
        const Vec3 local = pose.rotation.transpose() * d;
        const double radial = std::hypot(local.x(), local.y());
        const Vec3 side = radial > 0 ? Vec3(c.radius * local.x() / radial, c.radius * local.y() / radial, 0)
                                     : Vec3(c.radius, 0, 0);
        return pose.apply(side + Vec3(0, 0, local.z() >= 0 ? 0.5 * c.length : -0.5 * c.length));
    };
    for (int trial = 0; trial < 50000; ++trial) {
        const Cylinder a{0.05 + unit(random), 0.05 + 2 * unit(random)}, b{0.05 + unit(random), 0.05 + 2 * unit(random)};
        const double size = std::hypot(a.radius, 0.5 * a.length) + std::hypot(b.radius, 0.5 * b.length);
        const Settings settings = randomSettings(random, size);
        const Pose poseA = randomPose();
        const double pick = unit(random);
        const Mat3 rotationB = pick < 0.4   ? Mat3(poseA.rotation * tilt(random, 0.05))
                               : pick < 0.7 ? Mat3(poseA.rotation * Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()) * tilt(random, 0.05))
                                            : randomRotation(random);
        const Vec3 up = pick < 0.7 ? Vec3(poseA.rotation.col(2)) : Vec3(randomRotation(random) * Vec3::UnitZ());
        Pose poseB{rotationB, Vec3::Zero()};
        const Vec3 sideways = a.radius * Vec3(symmetric(random), symmetric(random), symmetric(random));
        poseB.position = cylinderSupport(a, poseA, up) - cylinderSupport(b, poseB, -up) + (sideways - sideways.dot(up) * up) -
                         up * (size * 0.01 * (1 + symmetric(random)));
        write(out, CylinderCylinder, size, collide(ShapeRef(a), poseA, ShapeRef(b), poseB, settings));
    }
    std::fclose(out);
    return 0;
}

int compare(const char* beforePath, const char* afterPath) {
    std::FILE* before = std::fopen(beforePath, "rb");
    std::FILE* after = std::fopen(afterPath, "rb");
    if (!before || !after) return std::perror("compare"), 2;
    struct Largest {
        long poses = 0, inContact = 0, points = 0, identical = 0, mismatches = 0;
        double normal = 0, depth = 0, position = 0;  // relative to the pair's size (normal: |Δn|)
    };
    std::map<int, Largest> types;
    Record x, y;
    bool ok = true;
    while (read(before, x)) {
        if (!read(after, y) || y.type != x.type) {
            std::printf("the files differ in length or order\n");
            return 1;
        }
        Largest& l = types[x.type];
        ++l.poses;
        const Manifold &m = x.manifold, &n = y.manifold;
        const bool sameShape = m.pointCount == n.pointCount && m.featureA.type == n.featureA.type &&
                               m.featureA.index == n.featureA.index && m.featureB.type == n.featureB.type &&
                               m.featureB.index == n.featureB.index;
        if (!sameShape) {
            ++l.mismatches;
            continue;
        }
        bool bits = true;
        if (m.pointCount > 0) {
            ++l.inContact;
            l.points += m.pointCount;
            l.normal = std::max(l.normal, (m.normal - n.normal).norm());
            bits = bits && std::memcmp(m.normal.data(), n.normal.data(), 3 * sizeof(double)) == 0;
            for (int i = 0; i < m.pointCount; ++i) {
                l.position = std::max(l.position, (m.points[i].position - n.points[i].position).norm() / x.size);
                l.depth = std::max(l.depth, std::abs(m.points[i].depth - n.points[i].depth) / x.size);
                bits = bits && std::memcmp(m.points[i].position.data(), n.points[i].position.data(), 3 * sizeof(double)) == 0 &&
                       std::memcmp(&m.points[i].depth, &n.points[i].depth, sizeof(double)) == 0;
            }
        }
        l.identical += bits;
    }
    std::printf("%-30s %8s %8s %8s %9s %10s %10s %10s %10s\n", "pair type", "poses", "contact", "points", "identical",
                "mismatch", "|dn|", "ddepth/s", "dpoint/s");
    for (const auto& [type, l] : types) {
        std::printf("%-30s %8ld %8ld %8ld %9ld %10ld %10.3g %10.3g %10.3g\n", typeName(type).c_str(), l.poses,
                    l.inContact, l.points, l.identical, l.mismatches, l.normal, l.depth, l.position);
        ok = ok && l.mismatches == 0 && l.normal <= 1e-9 && l.depth <= 1e-9 && l.position <= 1e-9;
    }
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 3 && std::string(argv[1]) == "dump") return dump(argv[2]);
    if (argc == 4 && std::string(argv[1]) == "compare") return compare(argv[2], argv[3]);
    std::fprintf(stderr, "usage: manifold_dump dump FILE | manifold_dump compare BEFORE AFTER\n");
    return 2;
}
