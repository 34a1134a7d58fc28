// Proof that a change to the ODE adapter's per-call path (gdc::ode::collide: reading the geoms,
// the core query, the filter, the depth order and the write of dContactGeoms) changed nothing the
// solver sees: every dContactGeom array gdc::ode::collide writes on a fixed stream of random poses,
// written to a file by one build and compared with another build's file.
//
//   contact_geom_dump dump FILE             (run by the build before the change and by the build after)
//   contact_geom_dump compare BEFORE AFTER  (largest difference in normal, depth and position per pair type)
//   contact_geom_dump compare-sets BEFORE AFTER  (the same, each contact against BEFORE's nearest:
//                                            a double- against a single-precision ODE, docs/install.md)
//
// Pair types: box–plane and plane–box (random box sizes, planes of any orientation through the
// box), convex–plane (gdc::ode::createConvex: a cube's hull and small random hulls), box–box and
// box–convex (random rotations, near touching). Per pose a random contact budget (flags), margin,
// contact order and spanning of the region. Written per contact: pos, normal (all four dReals),
// depth, side1, side2, and whether g1 and g2 are the geoms passed. compare exits 1 when a count or
// a flag differs or a value differs by more than 1e-9 of the pair's size, and prints how many
// arrays are identical to the bit.
#include <gdcontact/ode.hpp>

#include "geometry_oracles.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace gdc;
using testing::randomRotation;

namespace {

constexpr int kPosesPerType = 100000;

enum { BoxPlane, PlaneBox, ConvexPlane, BoxBox, BoxConvex, TypeCount };
const char* kTypeNames[TypeCount] = {"box-plane", "plane-box", "convex-plane", "box-box", "box-convex"};

struct Contact {
    double pos[4], normal[4], depth;
    int side1, side2, geomsPassed;
};

struct Record {
    int type = 0;
    double size = 0;
    int count = 0;
    Contact contacts[kMaxManifoldPoints];
};

void write(std::FILE* out, const Record& r) {
    std::fwrite(&r.type, sizeof r.type, 1, out);
    std::fwrite(&r.size, sizeof r.size, 1, out);
    std::fwrite(&r.count, sizeof r.count, 1, out);
    std::fwrite(r.contacts, sizeof(Contact), r.count, out);
}

bool read(std::FILE* in, Record& r) {
    if (std::fread(&r.type, sizeof r.type, 1, in) != 1) return false;
    if (std::fread(&r.size, sizeof r.size, 1, in) != 1 || std::fread(&r.count, sizeof r.count, 1, in) != 1 ||
        r.count < 0 || r.count > kMaxManifoldPoints)
        return false;
    return std::fread(r.contacts, sizeof(Contact), r.count, in) == static_cast<std::size_t>(r.count);
}

Settings randomSettings(std::mt19937& random, double size) {
    std::uniform_real_distribution<double> unit(0, 1);
    Settings settings;
    settings.maxContacts = 1 + static_cast<int>(unit(random) * 8) % 8;
    settings.margin = unit(random) < 0.5 ? 0.0 : unit(random) * 0.02 * size;
    settings.spanContactRegion = unit(random) < 0.3;
    settings.contactOrder = unit(random) < 0.5 ? ContactOrder::DeepestLast : ContactOrder::DeepestFirst;
    return settings;
}

void setPose(dGeomID geom, const Mat3& rotation, const Vec3& position) {
    dMatrix3 r;
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) r[4 * row + column] = rotation(row, column);
        r[4 * row + 3] = 0;
    }
    dGeomSetRotation(geom, r);
    dGeomSetPosition(geom, position.x(), position.y(), position.z());
}

// One call of gdc::ode::collide, recorded. The flags' budget is random too (at most the settings').
Record collideOnce(int type, double size, dGeomID o1, dGeomID o2, const Settings& settings, std::mt19937& random) {
    std::uniform_int_distribution<int> budget(1, 16);
    dContactGeom contacts[kMaxManifoldPoints];
    std::memset(contacts, 0x5a, sizeof contacts);  // what the adapter leaves unwritten shows
    Record r;
    r.type = type;
    r.size = size;
    r.count = ode::collide(o1, o2, budget(random), contacts, sizeof(dContactGeom), settings);
    for (int i = 0; i < r.count; ++i) {
        Contact& c = r.contacts[i];
        std::copy(contacts[i].pos, contacts[i].pos + 4, c.pos);
        std::copy(contacts[i].normal, contacts[i].normal + 4, c.normal);
        c.depth = contacts[i].depth;
        c.side1 = contacts[i].side1;
        c.side2 = contacts[i].side2;
        c.geomsPassed = (contacts[i].g1 == o1 ? 1 : 0) | (contacts[i].g2 == o2 ? 2 : 0);
    }
    return r;
}

std::vector<Vec3> sphereHullPoints(std::mt19937& random, int count) {
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> scale(0.2, 1.2);
    const Vec3 axes(scale(random), scale(random), scale(random));
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i)
        points.push_back(Vec3(normal(random), normal(random), normal(random)).normalized().cwiseProduct(axes));
    return points;
}

dGeomID convexOf(const std::vector<Vec3>& points) {
    std::vector<dReal> flat;
    for (const Vec3& p : points) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
    return ode::createConvex(nullptr, flat.data(), static_cast<unsigned>(points.size()));
}

int dump(const char* path) {
    std::FILE* out = std::fopen(path, "wb");
    if (!out) return std::perror("dump"), 2;
    dInitODE2(0);
    ode::setPairCacheEnabled(false);  // the query itself, not a repeated answer
    std::mt19937 random(20261127);
    std::uniform_real_distribution<double> unit(0, 1), symmetric(-1, 1), extent(0.05, 2.0);

    // The convex geoms: a cube's hull and small random hulls (up to 24 points).
    std::vector<dGeomID> convexes;
    std::vector<double> convexSizes;
    {
        std::vector<Vec3> cube;
        for (int v = 0; v < 8; ++v) cube.push_back(Vec3(v & 1 ? 0.5 : -0.5, v & 2 ? 0.5 : -0.5, v & 4 ? 0.5 : -0.5));
        convexes.push_back(convexOf(cube));
        convexSizes.push_back(std::sqrt(0.75));
        for (int i = 0; i < 7; ++i) {
            convexes.push_back(convexOf(sphereHullPoints(random, 6 + static_cast<int>(unit(random) * 19))));
            convexSizes.push_back(1.2 * std::sqrt(3.0));
        }
    }
    dGeomID box = dCreateBox(nullptr, 1, 1, 1), box2 = dCreateBox(nullptr, 1, 1, 1);
    auto randomBox = [&](dGeomID geom) {
        Vec3 half(extent(random), extent(random), extent(random));
        if (unit(random) < 0.3) half.setConstant(half.x());
        dGeomBoxSetLengths(geom, 2 * half.x(), 2 * half.y(), 2 * half.z());
        return half;
    };
    // A plane of random orientation whose surface passes within the body's size of `centre`.
    auto planeNear = [&](const Vec3& centre, double size) {
        const Vec3 n = Vec3(symmetric(random), symmetric(random), symmetric(random) + 0.01).normalized();
        const double offset = n.dot(centre) + symmetric(random) * size;
        return dCreatePlane(nullptr, n.x(), n.y(), n.z(), offset);
    };
    auto randomPosition = [&] { return Vec3(symmetric(random), symmetric(random), symmetric(random)) * 10.0; };

    for (int trial = 0; trial < kPosesPerType; ++trial) {
        const Vec3 half = randomBox(box);
        const Vec3 at = randomPosition();
        setPose(box, randomRotation(random), at);
        dGeomID plane = planeNear(at, half.norm());
        const Settings settings = randomSettings(random, half.norm());
        write(out, collideOnce(BoxPlane, half.norm(), box, plane, settings, random));
        write(out, collideOnce(PlaneBox, half.norm(), plane, box, settings, random));
        dGeomDestroy(plane);
    }
    for (int trial = 0; trial < kPosesPerType; ++trial) {
        const int which = trial % static_cast<int>(convexes.size());
        const Vec3 at = randomPosition();
        setPose(convexes[which], randomRotation(random), at);
        dGeomID plane = planeNear(at, convexSizes[which]);
        const Settings settings = randomSettings(random, convexSizes[which]);
        write(out, collideOnce(ConvexPlane, convexSizes[which], convexes[which], plane, settings, random));
        dGeomDestroy(plane);
    }
    for (int trial = 0; trial < kPosesPerType; ++trial) {
        const double size = randomBox(box).norm() + randomBox(box2).norm();
        const Vec3 at = randomPosition();
        setPose(box, randomRotation(random), at);
        const Vec3 direction = Vec3(symmetric(random), symmetric(random), symmetric(random)).normalized();
        setPose(box2, randomRotation(random), at + direction * size * (0.3 + 0.6 * unit(random)));
        write(out, collideOnce(BoxBox, size, box, box2, randomSettings(random, size), random));
    }
    for (int trial = 0; trial < kPosesPerType; ++trial) {
        const int which = trial % static_cast<int>(convexes.size());
        const double size = randomBox(box).norm() + convexSizes[which];
        const Vec3 at = randomPosition();
        setPose(box, randomRotation(random), at);
        const Vec3 direction = Vec3(symmetric(random), symmetric(random), symmetric(random)).normalized();
        setPose(convexes[which], randomRotation(random), at + direction * size * (0.3 + 0.6 * unit(random)));
        write(out, collideOnce(BoxConvex, size, box, convexes[which], randomSettings(random, size), random));
    }
    for (dGeomID geom : convexes) dGeomDestroy(geom);
    dGeomDestroy(box);
    dGeomDestroy(box2);
    dCloseODE();
    std::fclose(out);
    return 0;
}

// `sets`: each contact of AFTER held against the nearest contact of BEFORE (by position) instead of
// the one at its index — for builds whose contacts may come in another order (equal depths that
// a single-precision ODE's rounding makes unequal), where the question is how far the points moved.
int compare(const char* beforePath, const char* afterPath, bool sets = false) {
    std::FILE* before = std::fopen(beforePath, "rb");
    std::FILE* after = std::fopen(afterPath, "rb");
    if (!before || !after) return std::perror("compare"), 2;
    struct Largest {
        long calls = 0, withContacts = 0, contacts = 0, identical = 0, mismatches = 0;
        double normal = 0, depth = 0, position = 0;  // relative to the pair's size (normal: |Δn|)
        // sets: contacts farther than 1e-5 of the size from every contact of BEFORE (another choice
        // among nearly equally deep points), and the largest differences among the others
        long moved = 0;
        double nearDepth = 0, nearPosition = 0;
    };
    std::map<int, Largest> types;
    Record x, y;
    while (read(before, x)) {
        if (!read(after, y) || y.type != x.type) {
            std::printf("the files differ in length or order\n");
            return 1;
        }
        Largest& l = types[x.type];
        ++l.calls;
        bool same = x.count == y.count;
        for (int i = 0; same && i < x.count; ++i)
            same = x.contacts[i].side1 == y.contacts[i].side1 && x.contacts[i].side2 == y.contacts[i].side2 &&
                   x.contacts[i].geomsPassed == y.contacts[i].geomsPassed;
        if (!same) {
            ++l.mismatches;
            continue;
        }
        if (x.count > 0) ++l.withContacts;
        l.contacts += x.count;
        for (int i = 0; i < x.count; ++i) {
            const Contact& b = y.contacts[i];
            int nearest = i;
            for (int j = 0; sets && j < x.count; ++j) {
                auto distance = [&](int k) {
                    double d = 0;
                    for (int axis = 0; axis < 3; ++axis) d = std::max(d, std::abs(x.contacts[k].pos[axis] - b.pos[axis]));
                    return d;
                };
                if (distance(j) < distance(nearest)) nearest = j;
            }
            const Contact& a = x.contacts[nearest];
            double dn = 0, dp = 0;
            for (int k = 0; k < 4; ++k) {
                dn = std::max(dn, std::abs(a.normal[k] - b.normal[k]));
                dp = std::max(dp, std::abs(a.pos[k] - b.pos[k]));
            }
            l.normal = std::max(l.normal, dn);
            l.position = std::max(l.position, dp / x.size);
            l.depth = std::max(l.depth, std::abs(a.depth - b.depth) / x.size);
            if (dp / x.size > 1e-5) {
                ++l.moved;
            } else {
                l.nearPosition = std::max(l.nearPosition, dp / x.size);
                l.nearDepth = std::max(l.nearDepth, std::abs(a.depth - b.depth) / x.size);
            }
        }
        l.identical += std::memcmp(x.contacts, y.contacts, sizeof(Contact) * x.count) == 0;
    }
    bool ok = !read(after, y);
    if (!ok) std::printf("the files differ in length\n");
    std::printf("%-14s %8s %8s %9s %9s %9s %10s %10s %10s\n", "pair type", "calls", "touching", "contacts",
                "identical", "mismatch", "|dn|", "ddepth/s", "dpos/s");
    for (const auto& [type, l] : types) {
        std::printf("%-14s %8ld %8ld %9ld %9ld %9ld %10.3g %10.3g %10.3g\n", kTypeNames[type], l.calls, l.withContacts,
                    l.contacts, l.identical, l.mismatches, l.normal, l.depth, l.position);
        ok = ok && l.mismatches == 0 && l.normal <= 1e-9 && l.depth <= 1e-9 && l.position <= 1e-9;
    }
    if (sets) {
        std::printf("\n%-14s %9s %9s %12s %12s\n", "pair type", "contacts", "moved", "ddepth/s", "dpos/s");
        for (const auto& [type, l] : types)
            std::printf("%-14s %9ld %9ld %12.3g %12.3g\n", kTypeNames[type], l.contacts, l.moved, l.nearDepth,
                        l.nearPosition);
        std::printf("(moved: farther than 1e-5 of the size from every contact of BEFORE; the differences are "
                    "those of the others)\n");
    }
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 3 && std::string(argv[1]) == "dump") return dump(argv[2]);
    if (argc == 4 && std::string(argv[1]) == "compare") return compare(argv[2], argv[3]);
    if (argc == 4 && std::string(argv[1]) == "compare-sets") return compare(argv[2], argv[3], true);
    std::fprintf(stderr, "usage: contact_geom_dump dump FILE | contact_geom_dump compare[-sets] BEFORE AFTER\n");
    return 2;
}
