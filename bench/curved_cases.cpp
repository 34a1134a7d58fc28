// The curved pairs of issue 33 in the per-pair benchmark (pair_cases.hpp): a cylinder, capsule or
// sphere resting on the canonical cube (as a dBox or as the cube's 8-vertex dConvex), on the ground
// plane, or on a standing cylinder. ODE's conventions: capsule and cylinder axes along local z,
// ODE's lengths (a capsule's straight part). Every case is built in the common frame and cycles
// kPosesPerCase poses jittered as the cube cases are (±1 mm, ±0.01 rad; for a pair of bodies a
// relative jitter of the upper one, then one more common jitter of both).
//
// Contenders: "ode" (ODE's own collider through dCollide without install(): a native one for
// cylinder–box, cylinder–plane and capsule–box, libccd's MPR for cylinder–convex, capsule–convex,
// sphere–convex, cylinder–cylinder and capsule–cylinder in Debian's build), "gdcontact_ode"
// (gdc::ode::collide called directly), "gdcontact" (the core's gdc::collide on ShapeRef).
// Both ODE contenders get a contact array of gdc::Settings{}.maxContacts (6) and that as flags.
#include "pair_cases.hpp"

#include "ode_shapes.hpp"

#include <gdcontact/collide.hpp>
#include <gdcontact/shapes.hpp>
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
#include <gdcontact/ode.hpp>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <memory>
#include <ostream>

namespace gdcbench {
namespace {

/// Overlap of every curved case's canonical pose. Not the 1 mm a resting body typically shows
/// under ODE: the ±1 mm, ±0.01 rad jitter of the cycled poses would then leave some poses
/// separated and tilt most resting caps and lying sides off their region (a 1 m lying cylinder
/// tilted by 0.01 rad lifts one end by 5 mm). With kRestingOverlap (1 cm, as the cube cases) every
/// pose keeps the whole resting region in contact.
constexpr double kCurvedOverlap = kRestingOverlap;

constexpr double kCylinderRadius = 0.3, kCylinderLength = 1.0;
constexpr double kCapsuleRadius = 0.1, kCapsuleLength = 0.6;
constexpr double kBallRadius = 0.2;

/// One side of a curved case.
struct Side {
    enum Kind { Box, Convex, Plane, Sphere, Capsule, Cylinder } kind;
    double radius = 0, length = 0;
};
const Side kBox{Side::Box}, kConvex{Side::Convex}, kPlane{Side::Plane};
const Side kCylinder{Side::Cylinder, kCylinderRadius, kCylinderLength};
const Side kCapsule{Side::Capsule, kCapsuleRadius, kCapsuleLength};
const Side kBall{Side::Sphere, kBallRadius};

struct CurvedCase {
    std::string family, caseName;
    Side a, b;      // A rests on B
    Pose poseA, poseB;  // canonical, in the common frame (B unused for the plane)
};

std::vector<CurvedCase> curvedCases() {
    const double h = kCubeHalfExtent, d = kCurvedOverlap;
    const double cylHalf = kCylinderLength / 2;
    const Pose frame = commonFrame();
    const Mat3 standing = rotation(Vec3::UnitZ(), 0.4);
    // The axis horizontal, at 0.3 rad to the cube's edges (a 1 m cylinder stays within the 1 m face).
    const Mat3 lying = rotation(Vec3::UnitZ(), 0.3) * rotation(Vec3::UnitY(), M_PI / 2);
    const Pose origin{Mat3::Identity(), Vec3::Zero()};
    std::vector<CurvedCase> cases;
    auto add = [&](std::string family, std::string name, Side a, Side b, const Pose& poseA, const Pose& poseB) {
        cases.push_back({std::move(family), std::move(name), a, b, compose(frame, poseA), compose(frame, poseB)});
    };
    // On the cube (B at the origin, its top face at z = h).
    add("cylinder_box", "standing", kCylinder, kBox, {standing, {0.1, 0.05, h + cylHalf - d}}, origin);
    add("cylinder_box", "lying", kCylinder, kBox, {lying, {0, 0, h + kCylinderRadius - d}}, origin);
    // On the ground plane z = 0.
    add("cylinder_plane", "standing", kCylinder, kPlane, {standing, {0.1, 0.05, cylHalf - d}}, origin);
    add("cylinder_plane", "lying", kCylinder, kPlane, {lying, {0, 0, kCylinderRadius - d}}, origin);
    // The cube as an 8-vertex dConvex.
    add("cylinder_convex", "standing", kCylinder, kConvex, {standing, {0.1, 0.05, h + cylHalf - d}}, origin);
    add("capsule_box", "lying", kCapsule, kBox, {lying, {0.1, 0.05, h + kCapsuleRadius - d}}, origin);
    add("capsule_convex", "lying", kCapsule, kConvex, {lying, {0.1, 0.05, h + kCapsuleRadius - d}}, origin);
    add("sphere_convex", "resting", kBall, kConvex, {Mat3::Identity(), {0.1, 0.05, h + kBallRadius - d}}, origin);
    // On a standing cylinder (B at the origin, its top cap at z = cylHalf): coaxial but 5 cm off.
    add("cylinder_cylinder", "stacked", kCylinder, kCylinder, {standing, {0.05, 0, 2 * cylHalf - d}}, origin);
    // The capsule across the top cap, one end of its segment beyond the rim (the chord ends there).
    add("capsule_cylinder", "lying", kCapsule, kCylinder, {lying, {0.05, 0.02, cylHalf + kCapsuleRadius - d}}, origin);
    return cases;
}

/// A seed per case name (FNV-1a), as pair_cases.cpp's.
std::uint64_t seedOf(const std::string& name) {
    std::uint64_t h = 14695981039346656037ull;
    for (unsigned char ch : name) h = (h ^ ch) * 1099511628211ull;
    return 20100701ull ^ h;
}

/// The cycled poses: A jittered about its canonical pose; for a pair of bodies both then moved by
/// one more common jitter (as pair_cases.cpp's cubePairPoses); the plane stays where it is.
void cyclePoses(const CurvedCase& c, std::vector<Pose>& a, std::vector<Pose>& b) {
    const std::uint64_t seed = seedOf(c.family + "/" + c.caseName);
    const std::vector<Pose> relative = jitteredPoses(c.poseA, kPosesPerCase, seed);
    if (c.b.kind == Side::Plane) {
        a = relative;
        b.assign(kPosesPerCase, c.poseB);
        return;
    }
    const std::vector<Pose> common = jitteredPoses({Mat3::Identity(), Vec3::Zero()}, kPosesPerCase, seed ^ 0x5bd1e995u);
    a.clear(), b.clear();
    for (int i = 0; i < kPosesPerCase; ++i) {
        a.push_back(compose(common[i], relative[i]));
        b.push_back(compose(common[i], c.poseB));
    }
}

std::shared_ptr<gdc::Polytope> cubeBox() {
    return std::make_shared<gdc::Polytope>(gdc::Polytope::box(Vec3::Constant(kCubeHalfExtent)));
}
std::shared_ptr<gdc::Polytope> cubeHull() {
    return std::make_shared<gdc::Polytope>(gdc::Polytope::fromPoints(boxVertices(Vec3::Constant(kCubeHalfExtent))));
}

/// The geoms of one side of one ODE contender: one per pose (posed outside the timed loop), a
/// single one for the plane. `adapter`: a dConvex made by gdc::ode::createConvex (gdcontact knows
/// its hull) instead of plain dCreateConvex (ODE's own data, as a user of ODE would make it).
struct SideGeoms {
    std::vector<dGeomID> geoms, owned;
    std::vector<std::unique_ptr<OdeConvex>> convexStorage;
    dGeomID at(int poseIndex) const { return geoms[poseIndex % geoms.size()]; }
    SideGeoms() = default;
    SideGeoms(const SideGeoms&) = delete;
    SideGeoms& operator=(const SideGeoms&) = delete;
    ~SideGeoms() {
        for (dGeomID g : owned) dGeomDestroy(g);
    }
};

std::shared_ptr<SideGeoms> odeGeoms(const Side& side, const std::vector<Pose>& poses, bool adapter) {
    auto out = std::make_shared<SideGeoms>();
    if (side.kind == Side::Plane) {
        out->geoms.push_back(createOdePlane(nullptr, groundPlane()));
        out->owned.push_back(out->geoms.back());
        return out;
    }
    const std::vector<Vec3> corners = boxVertices(Vec3::Constant(kCubeHalfExtent));
    std::vector<dReal> flat;
    for (const Vec3& p : corners) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
    std::shared_ptr<gdc::Polytope> hull = side.kind == Side::Convex && !adapter ? cubeHull() : nullptr;
    for (const Pose& pose : poses) {
        dGeomID g = nullptr;
        switch (side.kind) {
            case Side::Box: g = createOdeBox(nullptr, Vec3::Constant(kCubeHalfExtent)); break;
            case Side::Sphere: g = dCreateSphere(nullptr, side.radius); break;
            case Side::Capsule: g = dCreateCapsule(nullptr, side.radius, side.length); break;
            case Side::Cylinder: g = dCreateCylinder(nullptr, side.radius, side.length); break;
            case Side::Convex:
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
                if (adapter) {
                    g = gdc::ode::createConvex(nullptr, flat.data(), static_cast<unsigned>(corners.size()));
                    break;
                }
#endif
                out->convexStorage.push_back(std::make_unique<OdeConvex>(nullptr, *hull));
                g = out->convexStorage.back()->geom();  // destroyed by its OdeConvex
                break;
            case Side::Plane: break;
        }
        if (side.kind != Side::Convex || adapter) out->owned.push_back(g);
        setGeomPose(g, pose);
        out->geoms.push_back(g);
    }
    return out;
}

/// The core's shape for a side; `keep` holds the polytope a ShapeRef borrows.
gdc::ShapeRef coreShape(const Side& side, std::shared_ptr<gdc::Polytope>& keep) {
    switch (side.kind) {
        case Side::Box: keep = cubeBox(); return *keep;
        case Side::Convex: keep = cubeHull(); return *keep;
        case Side::Plane: return groundPlane();
        case Side::Sphere: return gdc::Sphere{side.radius};
        case Side::Capsule: return gdc::Capsule{side.radius, side.length};
        case Side::Cylinder: return gdc::Cylinder{side.radius, side.length};
    }
    return groundPlane();
}

using OdeCollider = int (*)(dGeomID, dGeomID, int, dContactGeom*, int);
int nativeCollide(dGeomID a, dGeomID b, int flags, dContactGeom* contacts, int skip) {
    return dCollide(a, b, flags, contacts, skip);
}
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
int adapterCollide(dGeomID a, dGeomID b, int flags, dContactGeom* contacts, int skip) {
    return gdc::ode::collide(a, b, flags, contacts, skip);
}
#endif

constexpr int kMaxContacts = 6;  // gdc::Settings{}.maxContacts, checked below

std::function<int(int)> odePair(std::shared_ptr<SideGeoms> a, std::shared_ptr<SideGeoms> b, OdeCollider collider) {
    return [a, b, collider](int i) {
        std::array<dContactGeom, kMaxContacts> contacts;
        return collider(a->at(i), b->at(i), kMaxContacts, contacts.data(), sizeof(dContactGeom));
    };
}

std::vector<PairContender> curvedContenders(const CurvedCase& c, const ContenderFilter& want) {
    std::vector<Pose> posesA, posesB;
    cyclePoses(c, posesA, posesB);
    std::vector<PairContender> out;
    auto add = [&](std::string name, auto make) {
        if (!want || want(name)) out.push_back({std::move(name), make()});
    };
    add("ode", [&] { return odePair(odeGeoms(c.a, posesA, false), odeGeoms(c.b, posesB, false), nativeCollide); });
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
    add("gdcontact_ode",
        [&] { return odePair(odeGeoms(c.a, posesA, true), odeGeoms(c.b, posesB, true), adapterCollide); });
#endif
    add("gdcontact", [&] {
        std::shared_ptr<gdc::Polytope> keepA, keepB;  // the polytopes the ShapeRefs borrow
        const gdc::ShapeRef a = coreShape(c.a, keepA), b = coreShape(c.b, keepB);
        const gdc::Settings settings{};
        return std::function<int(int)>([a, b, keepA, keepB, posesA, posesB, settings](int i) {
            return gdc::collide(a, posesA[i], b, posesB[i], settings).pointCount;
        });
    });
    return out;
}

/// The support function h(d) = max over the side's points x of d·x, for the side at `pose`.
double supportValue(const Side& side, const Pose& pose, const Vec3& d) {
    const Vec3 local = pose.rotation.transpose() * d;
    const double base = d.dot(pose.position);
    switch (side.kind) {
        case Side::Box:
        case Side::Convex: return base + kCubeHalfExtent * local.cwiseAbs().sum();
        case Side::Sphere: return base + side.radius * local.norm();
        case Side::Capsule: return base + side.radius * local.norm() + 0.5 * side.length * std::abs(local.z());
        case Side::Cylinder:
            return base + side.radius * std::hypot(local.x(), local.y()) + 0.5 * side.length * std::abs(local.z());
        case Side::Plane: break;
    }
    return INFINITY;
}

/// The exact overlap of the pair along a unit normal n from B into A (how far A must move along n
/// to separate): h_B(n) + h_A(−n); against the plane only along its own normal (else NaN).
double exactOverlap(const CurvedCase& c, const Pose& a, const Pose& b, const Vec3& n) {
    if (c.b.kind == Side::Plane) {
        const gdc::HalfSpace plane = groundPlane();
        const Vec3 up = plane.normal.normalized();
        return (n - up).norm() < 1e-9 ? plane.offset / plane.normal.norm() + supportValue(c.a, a, -up) : NAN;
    }
    return supportValue(c.b, b, n) + supportValue(c.a, a, -n);
}

/// The angle (degrees) between a contact normal from B into A and the common frame's up.
double tiltDegrees(const Vec3& normal) {
    const Vec3 up = commonFrame().rotation * Vec3::UnitZ();
    return std::acos(std::max(-1.0, std::min(1.0, normal.normalized().dot(up)))) * 180 / M_PI;
}

void printOdeContacts(std::ostream& out, const char* who, dGeomID a, dGeomID b, OdeCollider collider,
                      const CurvedCase& c, const Pose& poseA, const Pose& poseB) {
    std::array<dContactGeom, kMaxContacts> contacts;
    const int n = collider(a, b, kMaxContacts, contacts.data(), sizeof(dContactGeom));
    out << "  " << std::setw(14) << std::left << who << std::right << n << " contacts";
    if (n > 0) {
        double worst = 0;
        for (int i = 0; i < n; ++i)
            worst = std::max(worst, tiltDegrees(Vec3(contacts[i].normal[0], contacts[i].normal[1], contacts[i].normal[2])));
        const Vec3 first(contacts[0].normal[0], contacts[0].normal[1], contacts[0].normal[2]);
        out << ", normals within " << worst << " deg of up, exact overlap along the first "
            << 1e3 * exactOverlap(c, poseA, poseB, first.normalized()) << " mm";
    }
    out << ", depths [mm]:";
    for (int i = 0; i < n; ++i) out << ' ' << 1e3 * contacts[i].depth;
    out << '\n';
}

}  // namespace

std::vector<PairCaseSet> curvedCaseSets() {
    static_assert(kMaxContacts <= 16);
    std::vector<PairCaseSet> sets;
    if (gdc::Settings{}.maxContacts != kMaxContacts) return sets;  // the contact arrays assume the default
    for (const CurvedCase& c : curvedCases())
        sets.push_back({c.family, c.caseName, kPosesPerCase,
                        [c](const ContenderFilter& f) { return curvedContenders(c, f); }});
    return sets;
}

void printCurvedContacts(std::ostream& out, int poseIndex) {
    out << std::setprecision(4);
    for (const CurvedCase& c : curvedCases()) {
        std::vector<Pose> posesA, posesB;
        cyclePoses(c, posesA, posesB);
        const int i = poseIndex % kPosesPerCase;
        out << c.family << '/' << c.caseName << " (pose " << i << ", canonical overlap " << 1e3 * kCurvedOverlap
            << " mm; normals from B into A)\n";
        auto nativeA = odeGeoms(c.a, {posesA[i]}, false), nativeB = odeGeoms(c.b, {posesB[i]}, false);
        printOdeContacts(out, "ode", nativeA->at(0), nativeB->at(0), nativeCollide, c, posesA[i], posesB[i]);
#ifdef GDCONTACT_BENCH_ODE_ADAPTER
        auto adapterA = odeGeoms(c.a, {posesA[i]}, true), adapterB = odeGeoms(c.b, {posesB[i]}, true);
        printOdeContacts(out, "gdcontact_ode", adapterA->at(0), adapterB->at(0), adapterCollide, c, posesA[i], posesB[i]);
#endif
        std::shared_ptr<gdc::Polytope> keepA, keepB;
        const gdc::Manifold m = gdc::collide(coreShape(c.a, keepA), posesA[i], coreShape(c.b, keepB), posesB[i]);
        out << "  " << std::setw(14) << std::left << "gdcontact" << std::right << m.pointCount << " contacts";
        if (m.pointCount > 0)  // the core's normal points from A into B: negated to ODE's convention
            out << ", normals within " << tiltDegrees(-m.normal) << " deg of up, exact overlap along it "
                << 1e3 * exactOverlap(c, posesA[i], posesB[i], -m.normal) << " mm";
        out << ", depths [mm]:";
        for (int k = 0; k < m.pointCount; ++k) out << ' ' << 1e3 * m.points[k].depth;
        out << '\n';
    }
}

}  // namespace gdcbench
