// The general pipeline's features in the common frame (A's) and the depth certificate read off
// them (feature_geometry.cpp), for GeneralPairHooks (collide.cpp).
#pragma once

#include "contact/feature_intersection.hpp"
#include "contact/gauss_map.hpp"
#include "geometry/minkowski.hpp"
#include "geometry/small_vector.hpp"

#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>

namespace gdc::detail {

/// A face's or an edge's geometry: its vertices placed in the common frame by `toCommon`, unless
/// `common` has them there already (A's own vertices where toCommon is the identity, and then its
/// planes too; B's as the hull enumeration placed them, hull_gauge.hpp).
FeatureGeometry faceGeometry(const Polytope& polytope, int index, const Pose& toCommon, const Vec3* common);
FeatureGeometry edgeGeometry(const Polytope& polytope, int index, const Pose& toCommon, const Vec3* common);

/// The pieces of a selected feature: the faces of a face's cap or the edges of an edge's chain
/// (gauss_map.hpp), the selected one among them; nothing for a vertex. `direction` is the contact
/// normal in the polytope's own frame, pointing away from the body (n for A, −n for B).
void featurePieces(const Polytope& polytope, const Feature& feature, const Vec3& direction,
                   const AngularTolerance& angularTolerance, SmallVector<int, 8>& pieces);

/// The feature in the common frame; with more than one piece (featurePieces) each is a feature of
/// its own in `capFaces`, intersected one by one.
FeatureGeometry featureGeometry(const Polytope& polytope, const Feature& feature, const SmallVector<int, 8>& pieces,
                                const Pose& toCommon, const Vec3* common = nullptr);

/// Whether the deepest lifted point provably carries the whole penetration along `normal`, within
/// `slack`, from the facets of A − B its provenance names (feature_geometry.cpp says why): then the
/// depth confirmation's ray cast could not add a point.
bool penetrationCertified(const LiftedPoint& deepest, const FeatureGeometry& featureA, const FeatureGeometry& featureB,
                          const Vec3& normal, const MinkowskiDifference& pair, double slack, double tolerance);

}  // namespace gdc::detail
