// gdc::validate: every Settings field against the bounds settings.hpp states for it.
#include <gdcontact/settings.hpp>
#include <gdcontact/manifold.hpp>
#include <gdcontact/types.hpp>

#include <sstream>
#include <string>

namespace gdc {
namespace {

template <class T>
void requireWithin(const char* field, T value, T lower, T upper, const char* unit) {
    if (value >= lower && value <= upper) return;  // false for NaN
    std::ostringstream message;
    message << "Settings::" << field << " is " << value << "; it must be in [" << lower << ", " << upper << "]"
            << unit << " (see its comment in gdcontact/settings.hpp)";
    throw InvalidInput(message.str());
}

}  // namespace

void validate(const Settings& settings) {
    requireWithin("rayCastTolerance", settings.rayCastTolerance, 1e-15, 1e-3, " (relative to the pair's size)");
    requireWithin("maxRayCastIterations", settings.maxRayCastIterations, 1, 10000, " iterations");
    requireWithin("angularTolerance", settings.angularTolerance, 0.0, 0.5, " rad");
    requireWithin("margin", settings.margin, 0.0, 1.0, " scene length units");
    requireWithin("maxContacts", settings.maxContacts, 1, static_cast<int>(kMaxManifoldPoints), " contacts");
    requireWithin("rimPointsPerTurn", settings.rimPointsPerTurn, 4, 64, " points");
    requireWithin("bruteForceSupportLimit", settings.bruteForceSupportLimit, 0, 65536, " vertices");
    requireWithin("coplanarTolerance", settings.coplanarTolerance, 0.0, 0.1, " rad");
    const int method = static_cast<int>(settings.normalMethod);
    requireWithin("normalMethod", method, static_cast<int>(NormalMethod::GrowthDistance),
                  static_cast<int>(NormalMethod::SeparatingAxis), " (a NormalMethod value)");
    requireWithin("manifoldReuseDistance", settings.manifoldReuseDistance, 0.0, 1.0, " scene length units");
    const int order = static_cast<int>(settings.contactOrder);
    requireWithin("contactOrder", order, static_cast<int>(ContactOrder::DeepestLast),
                  static_cast<int>(ContactOrder::DeepestFirstWhenLoaded), " (a ContactOrder value)");
    requireWithin("loadedDepthFraction", settings.loadedDepthFraction, 0.0, 1.0, " (relative to the pair's size)");
    requireWithin("reductionHysteresis", settings.reductionHysteresis, 0.0, 0.1, " (relative)");
    // Per-body-pair contact budget
    requireWithin("maxBodyPairContacts", settings.maxBodyPairContacts, 0, static_cast<int>(kMaxManifoldPoints),
                  " contacts (0: off)");
    requireWithin("bodyPairNormalTolerance", settings.bodyPairNormalTolerance, 0.0, 0.5, " rad");
}

// Every field: a field added to Settings must be added here (tests/pair_cache_test.cpp changes
// each field in turn and expects a difference).
bool operator==(const Settings& a, const Settings& b) {
    return a.rayCastTolerance == b.rayCastTolerance && a.maxRayCastIterations == b.maxRayCastIterations &&
           a.angularTolerance == b.angularTolerance && a.margin == b.margin &&
           a.spanContactRegion == b.spanContactRegion && a.maxContacts == b.maxContacts && a.rimPointsPerTurn == b.rimPointsPerTurn &&
           a.bruteForceSupportLimit == b.bruteForceSupportLimit && a.coplanarTolerance == b.coplanarTolerance &&
           a.normalMethod == b.normalMethod && a.manifoldReuseDistance == b.manifoldReuseDistance &&
           a.contactOrder == b.contactOrder && a.loadedDepthFraction == b.loadedDepthFraction &&
           a.reductionHysteresis == b.reductionHysteresis &&
           // Per-body-pair contact budget
           a.maxBodyPairContacts == b.maxBodyPairContacts &&
           a.bodyPairNormalTolerance == b.bodyPairNormalTolerance;
}

}  // namespace gdc
