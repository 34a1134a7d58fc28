// The curved kinds' Gauss-map features (round_shape.hpp). Every point a feature carries lies on the
// shape's surface: a capsule's segment and a sphere's point are moved out by the radius along d, the
// surface there; a cylinder's side segment and rim point are on its side already.
#include "shapes/round_shape.hpp"

namespace gdc::detail {
namespace {

AnyFeature pointFeature(const Vec3& point, const Pose& toCommon, int index) {
    AnyFeature feature;
    feature.geometry.type = FeatureType::Vertex;
    feature.geometry.points.push_back(toCommon.apply(point));
    feature.id = {FeatureType::Vertex, index};
    return feature;
}

AnyFeature segmentFeature(const Vec3& from, const Vec3& to, const Pose& toCommon) {
    AnyFeature feature;
    feature.geometry.type = FeatureType::Edge;
    feature.geometry.points.push_back(toCommon.apply(from));
    feature.geometry.points.push_back(toCommon.apply(to));
    feature.id = {FeatureType::Edge, 0};
    return feature;
}

// The end a feature is at: index 0 for the top (+z), 1 for the bottom.
int endIndex(const Vec3& d) { return d.z() >= 0 ? 0 : 1; }

}  // namespace

AnyFeature sphereFeature(const RoundShape& s, const Vec3& d, const Pose& toCommon) {
    return pointFeature(s.radius * d, toCommon, 0);
}

AnyFeature capsuleFeature(const RoundShape& s, const Vec3& d, const Pose& toCommon, const AngularTolerance& tolerance) {
    const Vec3 out = s.radius * d;
    // Within the tolerance of the equator the whole segment is the feature: a lying capsule rests on
    // a line, not on the end that rounding happens to favour.
    if (std::abs(d.z()) <= tolerance.sine && s.halfLength > 0)
        return segmentFeature(Vec3(0, 0, -s.halfLength) + out, Vec3(0, 0, s.halfLength) + out, toCommon);
    return pointFeature(Vec3(0, 0, endToward(d, s.halfLength)) + out, toCommon, endIndex(d));
}

AnyFeature cylinderFeature(const RoundShape& s, const Vec3& d, const Pose& toCommon, const AngularTolerance& tolerance) {
    const double end = endToward(d, s.halfLength);
    if (std::abs(d.z()) >= tolerance.cosine) {
        AnyFeature feature;
        feature.geometry.type = FeatureType::Face;
        feature.isDisc = true;
        feature.disc.centre = toCommon.apply(Vec3(0, 0, end));
        feature.disc.axis = toCommon.rotation * Vec3(0, 0, end >= 0 ? 1 : -1);
        feature.disc.radius = s.radius;
        feature.disc.reference = toCommon.rotation * Vec3::UnitX();
        feature.id = {FeatureType::Face, endIndex(d)};
        return feature;
    }
    const Vec3 side = s.radius * radialUnit(d);
    if (std::abs(d.z()) <= tolerance.sine)
        return segmentFeature(side - Vec3(0, 0, s.halfLength), side + Vec3(0, 0, s.halfLength), toCommon);
    return pointFeature(side + Vec3(0, 0, end), toCommon, endIndex(d));
}

}  // namespace gdc::detail
