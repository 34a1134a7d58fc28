// The per-body-pair contact budget inside the adapter: reduceBodyPair's work without its checks,
// for spaceCollide, which groups its pairs by body pair itself.
#pragma once

#include <gdcontact/body_pair.hpp>
#include <gdcontact/settings.hpp>

#include <ode/ode.h>

#include <vector>

namespace gdc::ode::detail {

/// Which of `contacts` (count of them, at stride `skip`, each between a geom of b1 and one of b2 in
/// either order) the body-pair budget keeps: their indices, ascending, in `kept`; returns how many.
/// `points` is scratch. Checks nothing (reduceBodyPair does, for users).
/// Whether two bodies of one geom each (neither the static world, 0) — which touch through one
/// pair of geoms at most, so the body-pair budget never applies to them: the grouping skips them.
bool bothHaveOneGeom(dBodyID b1, dBodyID b2);

int chooseBodyPairContacts(dBodyID b1, dBodyID b2, const dContactGeom* contacts, int count, int skip,
                           const Settings& settings, std::vector<BodyPairContact>& points, std::vector<int>& kept);

}  // namespace gdc::ode::detail
