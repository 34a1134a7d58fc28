// The drop-in programs, each run to its end in a child process (so that an abort — ODE's dError,
// an uncaught exception — fails the test instead of ending the suite), with every contact ODE got
// audited in the program's near callback. Each program prints one "dropin:" line on stderr.
#include "child_process.hpp"  // tests/ode
#include "demo_support.hpp"

#include <gdcontact/ode.hpp>

#include <catch2/catch.hpp>

#include <csignal>
#include <sstream>
#include <string>

int runBoxStack();
int runConvexPile();
int runTerrain();
int runInstallOnly();

namespace {

struct Outcome {
    int status = -2;
    std::string text;
    long objects = -1, contacts = -1, invalid = -1, fallen = -1, steps = -1;
};

Outcome run(int (*program)()) {
    Outcome outcome;
    std::tie(outcome.status, outcome.text) = gdc::ode::test::runInChild([program] {
        // As in a program's main: an exception nothing catches ends the process (std::terminate).
        std::signal(SIGABRT, SIG_DFL);  // not the test framework's handler: just end
        [program]() noexcept { std::_Exit(program()); }();
    });
    const auto at = outcome.text.find("dropin: ");
    if (at != std::string::npos) {
        std::istringstream line(outcome.text.substr(at + 8));
        std::string word;
        line >> word >> outcome.objects >> word >> outcome.contacts >> word >> outcome.invalid >> word >>
            outcome.fallen >> word >> outcome.steps;
    }
    return outcome;
}

void checkRanClean(const Outcome& outcome, long steps) {
    INFO(outcome.text);
    REQUIRE(outcome.status == 0);
    CHECK(outcome.steps == steps);  // ran to its end
    CHECK(outcome.contacts > 100);
    CHECK(outcome.invalid == 0);
    CHECK(outcome.fallen == 0);
    CHECK(outcome.text.find("ODE INTERNAL ERROR") == std::string::npos);
    CHECK(outcome.text.find("ODE Error") == std::string::npos);
}

}  // namespace

TEST_CASE("box stack with scripted keys dropping boxes and convexes (rounded, inward, shuffled data)",
          "[dropin]") {
    const Outcome outcome = run(&runBoxStack);
    checkRanClean(outcome, 2000);
    CHECK(outcome.objects == 28);
    // Each createConvex of inconsistent data says so once: 6 icosahedra ('v'), 5 prisms ('p').
    CHECK(dropin::count(outcome.text, "convex hull of the") == 11);
    CHECK(dropin::count(outcome.text, "(20 faces)") == 6);  // the icosahedra
    CHECK(dropin::count(outcome.text, "plain dCreateConvex") == 0);
}

TEST_CASE("a convex pile from rounded data stands inside its walls", "[dropin]") {
    const Outcome outcome = run(&runConvexPile);
    checkRanClean(outcome, 600);
    CHECK(dropin::count(outcome.text, "convex hull of the") == 15);  // 8 inward icosahedra, 7 prisms
}

// Whether the ODE linked collides a convex with a trimesh: ODE 0.16.x does it with libccd only
// (ODE_WITH_LIBCCD; Debian's is), and that pair is ODE's, not gdcontact's.
bool odeCollidesConvexWithTrimesh() {
    dInitODE2(0);
    // float, as BuildSingle reads them, whatever dReal is (a dReal array read as floats is garbage
    // in a double-precision ODE, and the probe then answered "no contacts" for the wrong reason).
    static const float vertices[] = {-5, -5, 0, 5, -5, 0, 5, 5, 0, -5, 5, 0};
    static const dTriIndex indices[] = {0, 1, 2, 0, 2, 3};
    dTriMeshDataID data = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildSingle(data, vertices, 3 * sizeof(float), 4, indices, 6, 3 * sizeof(dTriIndex));
    dGeomTriMeshDataPreprocess2(data, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);  // as terrain.cpp
    dGeomID mesh = dCreateTriMesh(0, data, nullptr, nullptr, nullptr);
    const dReal corners[] = {-0.5, -0.5, -0.5, 0.5, -0.5, -0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5,
                             -0.5, -0.5, 0.5,  0.5, -0.5, 0.5,  -0.5, 0.5, 0.5,  0.5, 0.5, 0.5};
    dGeomID cube = gdc::ode::createConvex(0, corners, 8);
    dGeomSetPosition(cube, 0.1, 0.2, 0.3);  // 0.2 into the mesh
    dContactGeom contacts[4];
    const int count = dCollide(cube, mesh, 4, contacts, sizeof(dContactGeom));
    dGeomDestroy(cube);
    dGeomDestroy(mesh);
    dGeomTriMeshDataDestroy(data);
    dCloseODE();
    return count > 0;
}

TEST_CASE("convexes and boxes on a trimesh and a heightfield", "[dropin]") {
    const Outcome outcome = run(&runTerrain);
    if (odeCollidesConvexWithTrimesh()) {
        checkRanClean(outcome, 600);
        return;
    }
    // An ODE without libccd gives convex–trimesh no contacts: the convexes on the trimesh fall
    // through it (ODE's pair, as without gdcontact); everything else as always.
    INFO(outcome.text);
    REQUIRE(outcome.status == 0);
    CHECK(outcome.steps == 600);
    CHECK(outcome.contacts > 100);
    CHECK(outcome.invalid == 0);
    CHECK(outcome.text.find("ODE INTERNAL ERROR") == std::string::npos);
}

TEST_CASE("a program that only adds install(): plain dCreateConvex geoms work, with one message", "[dropin]") {
    const Outcome outcome = run(&runInstallOnly);
    CHECK(dropin::count(outcome.text, "made with plain dCreateConvex") == 1);
    // An ODE that does not export its own convex colliders (a static libode) cannot give the plain
    // convexes' pairs ODE's contacts after install(): the documented degradation (docs/ode.md) is
    // no contacts for them and one message — never an abort or an invalid contact; the convexes
    // then sink through the ground, so only "fallen" is not checked.
    if (dropin::count(outcome.text, "does not export its own convex colliders") == 1) {
        INFO(outcome.text);
        REQUIRE(outcome.status == 0);
        CHECK(outcome.steps == 500);
        CHECK(outcome.contacts > 100);  // the boxes' pairs still have gdcontact's
        CHECK(outcome.invalid == 0);
        CHECK(outcome.text.find("ODE INTERNAL ERROR") == std::string::npos);
        return;
    }
    checkRanClean(outcome, 500);
}
