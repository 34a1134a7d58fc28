// The C API from C++: what a C program cannot check — the defaults are gdc::Settings', the error
// message is kept per thread, the header is usable from C++ (extern "C", noexcept).
#include <gdcontact/ode.h>
#include <gdcontact/ode.hpp>

#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

TEST_CASE("gdcDefaultSettings gives gdc::ode::defaultSettings(), field by field") {
    gdcSettings c;
    gdcDefaultSettings(&c);
    const gdc::Settings cpp = gdc::ode::defaultSettings();
    CHECK(c.rayCastTolerance == cpp.rayCastTolerance);
    CHECK(c.maxRayCastIterations == cpp.maxRayCastIterations);
    CHECK(c.angularTolerance == cpp.angularTolerance);
    CHECK(c.margin == cpp.margin);
    CHECK((c.spanContactRegion != 0) == cpp.spanContactRegion);
    CHECK(c.maxContacts == cpp.maxContacts);
    CHECK(c.bruteForceSupportLimit == cpp.bruteForceSupportLimit);
    CHECK(c.coplanarTolerance == cpp.coplanarTolerance);
    CHECK(c.normalMethod == static_cast<int>(cpp.normalMethod));
    CHECK(c.manifoldReuseDistance == cpp.manifoldReuseDistance);
    CHECK(c.contactOrder == static_cast<int>(cpp.contactOrder));
    CHECK(c.reductionHysteresis == cpp.reductionHysteresis);
    CHECK(c.maxBodyPairContacts == cpp.maxBodyPairContacts);
    CHECK(c.bodyPairNormalTolerance == cpp.bodyPairNormalTolerance);
    CHECK(c.loadedDepthFraction == cpp.loadedDepthFraction);
    CHECK(c.rimPointsPerTurn == cpp.rimPointsPerTurn);
}

TEST_CASE("gdcSettings' contact order values are gdc::ContactOrder's") {
    CHECK(GDC_ORDER_DEEPEST_LAST == static_cast<int>(gdc::ContactOrder::DeepestLast));
    CHECK(GDC_ORDER_DEEPEST_FIRST == static_cast<int>(gdc::ContactOrder::DeepestFirst));
    CHECK(GDC_ORDER_DEEPEST_FIRST_WHEN_LOADED == static_cast<int>(gdc::ContactOrder::DeepestFirstWhenLoaded));
}

TEST_CASE("The C functions are noexcept in C++ and have C linkage types") {
    STATIC_REQUIRE(noexcept(gdcInstall(nullptr)));
    STATIC_REQUIRE(noexcept(gdcCreateConvexFromPoints(nullptr, nullptr, 0)));
    STATIC_REQUIRE(noexcept(gdcLastError()));
    STATIC_REQUIRE(std::is_same_v<decltype(&gdcCollide), int (*)(dGeomID, dGeomID, int, dContactGeom*, int) noexcept>);
}

TEST_CASE("The error codes are distinct and 0 is success") {
    CHECK(GDC_OK == 0);
    CHECK(GDC_ERROR_INVALID_ARGUMENT != GDC_OK);
    CHECK(GDC_ERROR_OUT_OF_MEMORY != GDC_ERROR_INVALID_ARGUMENT);
    CHECK(GDC_ERROR_INTERNAL != GDC_ERROR_OUT_OF_MEMORY);
    CHECK(GDC_ERROR_INTERNAL != GDC_ERROR_INVALID_ARGUMENT);
    for (int code : {GDC_OK, GDC_ERROR_INVALID_ARGUMENT, GDC_ERROR_OUT_OF_MEMORY, GDC_ERROR_INTERNAL})
        CHECK(GDC_ERROR_ODE_NOT_INITIALIZED != code);
}

TEST_CASE("gdcLastError is per thread") {
    dInitODE2(0);
    const dReal threePoints[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    REQUIRE(gdcCreateConvexFromPoints(nullptr, threePoints, 3) == nullptr);
    const std::string mine = gdcLastError();
    CHECK_FALSE(mine.empty());

    std::string otherBefore, otherAfter;
    std::thread other([&] {
        otherBefore = gdcLastError();
        gdcSettings bad;
        gdcDefaultSettings(&bad);
        bad.maxContacts = 0;
        gdcInstall(&bad);
        otherAfter = gdcLastError();
    });
    other.join();
    CHECK(otherBefore.empty());  // a new thread starts without this thread's error
    CHECK(otherAfter.find("maxContacts") != std::string::npos);
    CHECK(std::string(gdcLastError()) == mine);  // and its error did not replace this one
    dCloseODE();
}

TEST_CASE("A failed install leaves the installed settings as they were") {
    dInitODE2(0);
    gdcSettings two;
    gdcDefaultSettings(&two);
    two.maxContacts = 2;
    REQUIRE(gdcInstall(&two) == GDC_OK);
    gdcSettings bad = two;
    bad.margin = -1;
    REQUIRE(gdcInstall(&bad) == GDC_ERROR_INVALID_ARGUMENT);

    dGeomID a = dCreateBox(nullptr, 1, 1, 1);
    dGeomID b = dCreateBox(nullptr, 1, 1, 1);
    dGeomSetPosition(b, 0, 0, 0.99);
    dContactGeom contacts[8];
    CHECK(dCollide(a, b, 8, contacts, sizeof(dContactGeom)) == 2);
    dGeomDestroy(a);
    dGeomDestroy(b);
    dCloseODE();
}

TEST_CASE("gdcReduceBodyPair keeps what gdc::ode::reduceBodyPair keeps, over random composites") {
    // Two bodies of 2–4 boxes each, the upper resting on the lower at a random yaw, offset and
    // tilt (several geom pairs, coplanar and tilted contacts), and a composite on the static world:
    // the C function and the C++ one must return the same count and the same array, for several
    // settings, in both body orders.
    dInitODE2(0);
    REQUIRE(gdcInstall(nullptr) == GDC_OK);
    dWorldID world = dWorldCreate();
    dWorldSetGravity(world, 0, 0, -9.81);
    std::mt19937 random(22);
    std::uniform_real_distribution<double> unit(-1, 1), size(0.1, 0.4);
    int compared = 0, reduced = 0;
    for (int trial = 0; trial < 200; ++trial) {
        dBodyID upper = dBodyCreate(world);
        dBodyID lower = trial % 4 == 0 ? nullptr : dBodyCreate(world);  // a quarter on the static world
        std::vector<dGeomID> upperParts, lowerParts;
        auto addParts = [&](dBodyID body, double top, std::vector<dGeomID>& parts) {
            const int count = 2 + static_cast<int>(random() % 3);
            for (int k = 0; k < count; ++k) {
                const double lx = size(random), ly = size(random), lz = 0.1;
                dGeomID g = dCreateBox(nullptr, lx, ly, lz);
                const double x = 0.2 * unit(random), y = 0.2 * unit(random), z = top > 0 ? lz / 2 : -lz / 2;
                if (body) {
                    dGeomSetBody(g, body);
                    dGeomSetOffsetPosition(g, x, y, z);
                } else {
                    dGeomSetPosition(g, x, y, z);
                }
                parts.push_back(g);
            }
        };
        addParts(upper, 1, upperParts);
        addParts(lower, -1, lowerParts);
        if (lower) dBodySetPosition(lower, 0, 0, 0);
        dBodySetPosition(upper, 0.1 * unit(random), 0.1 * unit(random), -1e-3);
        dMatrix3 rotation;
        dRFromAxisAndAngle(rotation, unit(random), unit(random), 10, trial % 2 ? 3.14159 * unit(random) : 0.0);
        dBodySetRotation(upper, rotation);
        std::vector<dContactGeom> contacts;
        for (dGeomID a : upperParts)
            for (dGeomID b : lowerParts) {
                dContactGeom buffer[8];
                const int n = random() % 2 ? dCollide(a, b, 8, buffer, sizeof(dContactGeom))
                                           : dCollide(b, a, 8, buffer, sizeof(dContactGeom));
                contacts.insert(contacts.end(), buffer, buffer + n);
            }
        for (int budget : {3, 4, 6}) {
            gdcSettings c;
            gdcDefaultSettings(&c);
            c.maxBodyPairContacts = budget;
            gdc::Settings cpp;
            cpp.maxBodyPairContacts = budget;
            for (int swapped = 0; swapped < 2; ++swapped) {
                dBodyID b1 = swapped ? lower : upper, b2 = swapped ? upper : lower;
                std::vector<dContactGeom> viaC = contacts, viaCpp = contacts;
                const int n = static_cast<int>(contacts.size());
                const int keptC = gdcReduceBodyPair(b1, b2, viaC.data(), n, sizeof(dContactGeom), &c);
                const int keptCpp = gdc::ode::reduceBodyPair(b1, b2, viaCpp.data(), n, sizeof(dContactGeom), cpp);
                INFO("trial " << trial << " budget " << budget << " swapped " << swapped);
                REQUIRE(keptC == keptCpp);
                // An empty vector's data() may be null, which memcmp must not get (UBSan)
                if (keptC > 0)
                    CHECK(std::memcmp(viaC.data(), viaCpp.data(), sizeof(dContactGeom) * static_cast<std::size_t>(keptC)) == 0);
                CHECK(std::string(gdcLastError()).empty());
                ++compared;
                reduced += keptC < n;
            }
        }
        for (dGeomID g : upperParts) dGeomDestroy(g);
        for (dGeomID g : lowerParts) dGeomDestroy(g);
        dBodyDestroy(upper);
        if (lower) dBodyDestroy(lower);
    }
    CHECK(compared == 1200);
    CHECK(reduced > 300);  // the budget dropped contacts in many of them
    STATIC_REQUIRE(noexcept(gdcReduceBodyPair(nullptr, nullptr, nullptr, 0, 0, nullptr)));
    dWorldDestroy(world);
    dCloseODE();
}
