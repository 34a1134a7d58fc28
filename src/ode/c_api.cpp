// The C API (<gdcontact/ode.h>): gdc::ode::install / collide / createConvex behind C functions.
// Nothing thrown inside gdcontact leaves these functions: each failure becomes an error code or a
// 0 geom, with its message kept per thread for gdcLastError().
#include <gdcontact/ode.h>
#include <gdcontact/ode.hpp>

#include "ode_internals.hpp"

#include <exception>
#include <new>
#include <stdexcept>
#include <string>

namespace {

static_assert(GDC_NORMAL_GROWTH_DISTANCE == static_cast<int>(gdc::NormalMethod::GrowthDistance) &&
                  GDC_NORMAL_SEPARATING_AXIS == static_cast<int>(gdc::NormalMethod::SeparatingAxis),
              "GDC_NORMAL_* must match gdc::NormalMethod");

// This thread's last error. The text lives in a string; `lastError` points at it (or at a static
// message when even storing the text failed), so gdcLastError never allocates and never fails.
thread_local std::string lastErrorText;
thread_local const char* lastError = "";

void clearError() noexcept { lastError = ""; }

void setError(const char* prefix, const char* message) noexcept {
    try {
        lastErrorText.assign(prefix);
        lastErrorText.append(message);
        lastError = lastErrorText.c_str();
    } catch (...) {
        lastError = "gdcontact: out of memory (while recording an error)";
    }
}

// Runs `body`, turning every exception into an error code and this thread's message.
template <class Body>
int guarded(Body&& body) noexcept {
    try {
        body();
        clearError();
        return GDC_OK;
    } catch (const gdc::InvalidInput& error) {  // its message already starts with "gdcontact: "
        setError("", error.what());
        return GDC_ERROR_INVALID_ARGUMENT;
    } catch (const std::bad_alloc&) {
        setError("", "gdcontact: out of memory");
        return GDC_ERROR_OUT_OF_MEMORY;
    } catch (const std::exception& error) {
        setError("gdcontact: internal error: ", error.what());
        return GDC_ERROR_INTERNAL;
    } catch (...) {
        setError("", "gdcontact: internal error: unknown exception");
        return GDC_ERROR_INTERNAL;
    }
}

gdc::Settings toSettings(const gdcSettings& in, const char* caller = "gdcInstall") {
    if (in.normalMethod != GDC_NORMAL_GROWTH_DISTANCE && in.normalMethod != GDC_NORMAL_SEPARATING_AXIS)
        throw gdc::InvalidInput(std::string(caller) + ": gdcSettings::normalMethod must be GDC_NORMAL_GROWTH_DISTANCE (0) "
                                "or GDC_NORMAL_SEPARATING_AXIS (1), not " + std::to_string(in.normalMethod));
    gdc::Settings out;
    out.rayCastTolerance = in.rayCastTolerance;
    out.maxRayCastIterations = in.maxRayCastIterations;
    out.angularTolerance = in.angularTolerance;
    out.margin = in.margin;
    out.spanContactRegion = in.spanContactRegion != 0;
    out.maxContacts = in.maxContacts;
    out.bruteForceSupportLimit = in.bruteForceSupportLimit;
    out.coplanarTolerance = in.coplanarTolerance;
    out.normalMethod = static_cast<gdc::NormalMethod>(in.normalMethod);
    out.manifoldReuseDistance = in.manifoldReuseDistance;
    out.contactOrder = static_cast<gdc::ContactOrder>(in.contactOrder);  // checked by gdc::validate
    out.reductionHysteresis = in.reductionHysteresis;
    // Per-body-pair contact budget
    out.maxBodyPairContacts = in.maxBodyPairContacts;
    out.bodyPairNormalTolerance = in.bodyPairNormalTolerance;
    out.loadedDepthFraction = in.loadedDepthFraction;
    out.rimPointsPerTurn = in.rimPointsPerTurn;
    return out;  // the ranges are checked by gdc::validate (in gdc::ode::install), which names the field
}

}  // namespace

extern "C" {

void gdcDefaultSettings(gdcSettings* settings) noexcept {
    if (!settings) return;
    const gdc::Settings defaults = gdc::ode::defaultSettings();
    settings->rayCastTolerance = defaults.rayCastTolerance;
    settings->maxRayCastIterations = defaults.maxRayCastIterations;
    settings->angularTolerance = defaults.angularTolerance;
    settings->margin = defaults.margin;
    settings->spanContactRegion = defaults.spanContactRegion ? 1 : 0;
    settings->maxContacts = defaults.maxContacts;
    settings->bruteForceSupportLimit = defaults.bruteForceSupportLimit;
    settings->coplanarTolerance = defaults.coplanarTolerance;
    settings->normalMethod = static_cast<int>(defaults.normalMethod);
    settings->manifoldReuseDistance = defaults.manifoldReuseDistance;
    settings->contactOrder = static_cast<int>(defaults.contactOrder);
    settings->reductionHysteresis = defaults.reductionHysteresis;
    // Per-body-pair contact budget
    settings->maxBodyPairContacts = defaults.maxBodyPairContacts;
    settings->bodyPairNormalTolerance = defaults.bodyPairNormalTolerance;
    settings->loadedDepthFraction = defaults.loadedDepthFraction;
    settings->rimPointsPerTurn = defaults.rimPointsPerTurn;
}

int gdcInstall(const gdcSettings* settings) noexcept {
    try {
        if (!gdc::ode::detail::odeIsInitialized()) {
            setError("", "gdcontact: gdcInstall was called while ODE is not initialised: call dInitODE2(0) first "
                         "(and again after dCloseODE()), then gdcInstall");
            return GDC_ERROR_ODE_NOT_INITIALIZED;
        }
    } catch (...) {  // cannot happen (a dlsym and a load); never let anything out
    }
    return guarded([&] {
        if (!settings) {
            gdc::ode::install();
        } else {
            gdc::ode::install(toSettings(*settings));
        }
    });
}

int gdcCollide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) noexcept {
    try {
        return gdc::ode::collide(o1, o2, flags, contact, skip);  // reports its own failures (dMessage)
    } catch (...) {  // it promises not to throw; should it, the pair gets no contacts
        return 0;
    }
}

dGeomID gdcCreateConvex(dSpaceID space, const dReal* planes, unsigned planeCount, const dReal* points,
                        unsigned pointCount, const unsigned* polygons) noexcept {
    dGeomID geom = nullptr;
    const int code = guarded([&] {
        if (!planes) throw gdc::InvalidInput("gdcCreateConvex: planes is NULL");
        if (!points) throw gdc::InvalidInput("gdcCreateConvex: points is NULL");
        if (!polygons) throw gdc::InvalidInput("gdcCreateConvex: polygons is NULL");
        geom = gdc::ode::createConvex(space, planes, planeCount, points, pointCount, polygons);
        if (!geom) throw std::runtime_error("gdcCreateConvex: no geom was created");
    });
    return code == GDC_OK ? geom : nullptr;
}

dGeomID gdcCreateConvexFromPoints(dSpaceID space, const dReal* points, unsigned pointCount) noexcept {
    dGeomID geom = nullptr;
    const int code = guarded([&] {
        if (!points) throw gdc::InvalidInput("gdcCreateConvexFromPoints: points is NULL");
        geom = gdc::ode::createConvex(space, points, pointCount);
        if (!geom) throw std::runtime_error("gdcCreateConvexFromPoints: no geom was created");
    });
    return code == GDC_OK ? geom : nullptr;
}

dGeomID gdcCreateConvexStrict(dSpaceID space, const dReal* planes, unsigned planeCount, const dReal* points,
                              unsigned pointCount, const unsigned* polygons) noexcept {
    dGeomID geom = nullptr;
    const int code = guarded([&] {
        if (!planes) throw gdc::InvalidInput("gdcCreateConvexStrict: planes is NULL");
        if (!points) throw gdc::InvalidInput("gdcCreateConvexStrict: points is NULL");
        if (!polygons) throw gdc::InvalidInput("gdcCreateConvexStrict: polygons is NULL");
        geom = gdc::ode::createConvexStrict(space, planes, planeCount, points, pointCount, polygons);
        if (!geom) throw std::runtime_error("gdcCreateConvexStrict: no geom was created");
    });
    return code == GDC_OK ? geom : nullptr;
}

int gdcSpaceCollide(dSpaceID space, int maxContactsPerPair, void* data, gdcContactHandler handler) noexcept {
    return guarded([&] { gdc::ode::spaceCollide(space, maxContactsPerPair, data, handler); });
}

int gdcSetThreadCount(int threads) noexcept {
    return guarded([&] { gdc::ode::setThreadCount(threads); });
}

void gdcSetPairCacheEnabled(int enabled) noexcept { gdc::ode::setPairCacheEnabled(enabled != 0); }

void gdcClearPairCache(void) noexcept {
    try {
        gdc::ode::clearPairCache();
    } catch (...) {  // an allocation inside the table's clean-up: nothing to report, nothing left half done
    }
}

int gdcReduceBodyPair(dBodyID b1, dBodyID b2, dContactGeom* contacts, int count, int skip,
                      const gdcSettings* settings) noexcept {
    int kept = 0;
    const int code = guarded([&] {
        // gdc::ode::reduceBodyPair validates the settings and every contact before it moves any.
        kept = gdc::ode::reduceBodyPair(b1, b2, contacts, count, skip,
                                        settings ? toSettings(*settings, "gdcReduceBodyPair") : gdc::ode::defaultSettings());
    });
    return code == GDC_OK ? kept : -code;
}

const char* gdcLastError(void) noexcept { return lastError; }

}  // extern "C"
