// The C API from C++: what a C program cannot check — the defaults are gdc::Settings', the error
// message is kept per thread, the header is usable from C++ (extern "C", noexcept).
#include <gdcontact/ode.h>
#include <gdcontact/ode.hpp>

#include <catch2/catch.hpp>

#include <string>
#include <thread>
#include <type_traits>

TEST_CASE("gdcDefaultSettings gives gdc::Settings' defaults, field by field") {
    gdcSettings c;
    gdcDefaultSettings(&c);
    const gdc::Settings cpp;
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
}

TEST_CASE("gdcSettings' contact order values are gdc::ContactOrder's") {
    CHECK(GDC_ORDER_DEEPEST_LAST == static_cast<int>(gdc::ContactOrder::DeepestLast));
    CHECK(GDC_ORDER_DEEPEST_FIRST == static_cast<int>(gdc::ContactOrder::DeepestFirst));
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
