// Misuse caught where it happens, with a message naming the fix; settings bounds; no exception
// into C.
#include "child_process.hpp"  // tests/ode
#include "demo_support.hpp"

#include <gdcontact/ode.h>
#include <gdcontact/ode.hpp>

#include <catch2/catch.hpp>

#include <dlfcn.h>

#include <cmath>
#include <csignal>
#include <limits>
#include <string>
#include <vector>

using gdc::ode::test::runInChild;

namespace {

// Contacts of a 1 m box resting 1 cm into another's top face (4 corners with ODE's dBoxBox).
int boxOnBoxContacts() {
    dGeomID lower = dCreateBox(0, 1, 1, 1), upper = dCreateBox(0, 1, 1, 1);
    dGeomSetPosition(upper, 0, 0, 0.99);
    dContactGeom contacts[8];
    const int n = dCollide(upper, lower, 8, contacts, sizeof(dContactGeom));
    dGeomDestroy(lower);
    dGeomDestroy(upper);
    return n;
}

gdc::Settings withMaxContacts(int n) {
    gdc::Settings settings;
    settings.maxContacts = n;
    return settings;
}

// Whether gdcontact can tell an uninitialised ODE: ODE 0.16.x has no public query; a shared libode
// exports the flag its initialisation sets, a static one does not, and then install() cannot check
// the call order (docs/ode.md, "install() before dInitODE2()").
bool initialisationVisible() {
    return dlsym(RTLD_DEFAULT, "_ZN5odeou28CAssertionCheckCustomization24g_fnAssertFailureHandlerE") != nullptr;
}

}  // namespace

TEST_CASE("install() before dInitODE2() says to call dInitODE2 first", "[dropin][misuse]") {
    if (!initialisationVisible()) {
        WARN("this ODE (a static libode) does not let gdcontact tell whether it is initialised: not checked");
        return;
    }
    CHECK_THROWS_WITH(gdc::ode::install(), Catch::Contains("dInitODE2") && Catch::Contains("not initialised"));
    // A program that does not catch it ends with that message, not inside ODE.
    const auto [status, text] = runInChild([] {
        std::signal(SIGABRT, SIG_DFL);  // not the test framework's handler: just end
        []() noexcept { gdc::ode::install(); }();
    });
    CHECK(status != 0);
    CHECK_THAT(text, Catch::Contains("call dInitODE2(0) first"));
    CHECK(gdcInstall(nullptr) == GDC_ERROR_ODE_NOT_INITIALIZED);
    CHECK_THAT(gdcLastError(), Catch::Contains("dInitODE2"));
}

TEST_CASE("install() twice replaces the settings, after dCloseODE it must follow a new dInitODE2", "[dropin][misuse]") {
    dInitODE2(0);
    CHECK(boxOnBoxContacts() == 4);  // ODE's dBoxBox
    gdc::ode::install(withMaxContacts(2));
    CHECK(boxOnBoxContacts() == 2);
    gdc::ode::install(withMaxContacts(3));  // twice: the later settings win
    CHECK(boxOnBoxContacts() == 3);
    dCloseODE();
    if (initialisationVisible())  // else not seen (a static libode): docs/ode.md
        CHECK_THROWS_WITH(gdc::ode::install(), Catch::Contains("dInitODE2"));  // closed: refused, not an ODE abort
    dInitODE2(0);
    CHECK(boxOnBoxContacts() == 4);  // dCloseODE forgot the override: ODE's dBoxBox again
    gdc::ode::install(withMaxContacts(3));
    CHECK(boxOnBoxContacts() == 3);
    dCloseODE();
}

TEST_CASE("every Settings field is bounded on both sides, and the message names the field and its bounds",
          "[dropin][misuse][settings]") {
    struct Field {
        const char* name;
        void (*set)(gdc::Settings&, double);
        double lower, upper, below, above;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Field fields[] = {
        {"rayCastTolerance", [](gdc::Settings& s, double v) { s.rayCastTolerance = v; }, 1e-15, 1e-3, 1e-16, 2e-3},
        {"maxRayCastIterations", [](gdc::Settings& s, double v) { s.maxRayCastIterations = int(v); }, 1, 10000, 0, 10001},
        {"angularTolerance", [](gdc::Settings& s, double v) { s.angularTolerance = v; }, 0, 0.5, -1e-9, 2.0},
        {"margin", [](gdc::Settings& s, double v) { s.margin = v; }, 0, 1, -1e-9, 10.0},
        {"maxContacts", [](gdc::Settings& s, double v) { s.maxContacts = int(v); }, 1, 16, 0, 17},
        {"bruteForceSupportLimit", [](gdc::Settings& s, double v) { s.bruteForceSupportLimit = int(v); }, 0, 65536, -1, 65537},
        {"coplanarTolerance", [](gdc::Settings& s, double v) { s.coplanarTolerance = v; }, 0, 0.1, -1e-9, 0.2},
        {"normalMethod", [](gdc::Settings& s, double v) { s.normalMethod = static_cast<gdc::NormalMethod>(int(v)); }, 0, 1, -1, 2},
        {"manifoldReuseDistance", [](gdc::Settings& s, double v) { s.manifoldReuseDistance = v; }, 0, 1, -1e-9, 2.0},
        {"contactOrder", [](gdc::Settings& s, double v) { s.contactOrder = static_cast<gdc::ContactOrder>(int(v)); }, 0, 2, -1, 3},
        {"loadedDepthFraction", [](gdc::Settings& s, double v) { s.loadedDepthFraction = v; }, 0, 1, -1e-9, 1.5},
        {"reductionHysteresis", [](gdc::Settings& s, double v) { s.reductionHysteresis = v; }, 0, 0.1, -1e-9, 0.2},
        // Per-body-pair contact budget
        {"maxBodyPairContacts", [](gdc::Settings& s, double v) { s.maxBodyPairContacts = int(v); }, 0, 16, -1, 17},
        {"bodyPairNormalTolerance", [](gdc::Settings& s, double v) { s.bodyPairNormalTolerance = v; }, 0, 0.5, -1e-9, 0.6},
    };
    for (const Field& field : fields) {
        INFO(field.name);
        for (double good : {field.lower, field.upper}) {
            gdc::Settings settings;
            field.set(settings, good);
            CHECK_NOTHROW(gdc::validate(settings));
        }
        for (double bad : {field.below, field.above}) {
            gdc::Settings settings;
            field.set(settings, bad);
            CHECK_THROWS_WITH(gdc::validate(settings), Catch::Contains(std::string("Settings::") + field.name) &&
                                                           Catch::Contains("must be in ["));
        }
    }
    for (double gdc::Settings::*member : {&gdc::Settings::rayCastTolerance, &gdc::Settings::angularTolerance,
                                          &gdc::Settings::margin, &gdc::Settings::coplanarTolerance,
                                          &gdc::Settings::reductionHysteresis}) {
        gdc::Settings settings;
        settings.*member = nan;
        CHECK_THROWS_AS(gdc::validate(settings), gdc::InvalidInput);
    }
    // install() and gdcInstall use it, and refuse without changing anything.
    dInitODE2(0);
    gdc::Settings wide;
    wide.angularTolerance = 2.0;
    CHECK_THROWS_WITH(gdc::ode::install(wide), Catch::Contains("angularTolerance"));
    gdcSettings c;
    gdcDefaultSettings(&c);
    c.margin = 10.0;
    CHECK(gdcInstall(&c) == GDC_ERROR_INVALID_ARGUMENT);
    CHECK_THAT(gdcLastError(), Catch::Contains("margin") && Catch::Contains("[0, 1]"));
    CHECK(boxOnBoxContacts() == 4);  // nothing was installed
    dCloseODE();
}

TEST_CASE("the C API takes what dCreateConvex takes and reports unusable data by a 0 geom, never an exception",
          "[dropin][misuse][c]") {
    dInitODE2(0);
    REQUIRE(gdcInstall(nullptr) == GDC_OK);
    dMessageFunction* previous = dGetMessageHandler();
    dropin::messages().clear();
    dSetMessageHandler(&dropin::captureMessage);
    const dropin::ConvexData inwards = dropin::roundedIcosahedron(0.3, true);
    dGeomID geom = gdcCreateConvex(nullptr, inwards.planes.data(), inwards.planeCount(), inwards.points.data(),
                                   inwards.pointCount(), inwards.polygons.data());
    CHECK(geom != nullptr);
    CHECK(dropin::count(dropin::messages(), "convex hull of the 12 points (20 faces)") == 1);
    CHECK(gdcCreateConvexStrict(nullptr, inwards.planes.data(), inwards.planeCount(), inwards.points.data(),
                                inwards.pointCount(), inwards.polygons.data()) == nullptr);
    CHECK_THAT(gdcLastError(), Catch::Contains("plane 0"));
    dropin::ConvexData broken = dropin::demoCube();
    broken.polygons[3] = 99;  // ODE would read out of bounds
    CHECK(gdcCreateConvex(nullptr, broken.planes.data(), broken.planeCount(), broken.points.data(),
                          broken.pointCount(), broken.polygons.data()) == nullptr);
    CHECK_THAT(gdcLastError(), Catch::Contains("point 99"));
    const dropin::ConvexData cube = dropin::demoCube();
    dGeomID strictCube = gdcCreateConvexStrict(nullptr, cube.planes.data(), cube.planeCount(), cube.points.data(),
                                               cube.pointCount(), cube.polygons.data());
    CHECK(strictCube != nullptr);
    CHECK(std::string(gdcLastError()).empty());
    dSetMessageHandler(previous);
    dGeomDestroy(geom);
    dGeomDestroy(strictCube);
    dCloseODE();
}
