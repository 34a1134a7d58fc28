// The box's shape hooks (box_shape.hpp).
#include "box_shape.hpp"

namespace gdc::detail {
namespace {

// An AngularTolerance's comparisons, as selectFeature makes them.
struct ExactAngularTolerance {
    const AngularTolerance& tolerance;
    bool withinCosine(double c) const { return c >= tolerance.cosine; }
    bool withinSine(double s) const { return s <= tolerance.sine; }
};

}  // namespace

Feature selectBoxFeature(const Vec3& direction, const AngularTolerance& tolerance) {
    ExactAngularTolerance exact{tolerance};
    return selectBoxFeature(direction, boxSupport(direction), exact);
}

BoxFeature boxFeature(const Polytope& box, const Feature& feature, const Pose* toCommon) {
    BoxFeature geometry;
    geometry.type = feature.type;
    int storage[2];
    const int* indices = nullptr;
    geometry.count = featureVertices(box, feature, &indices, storage);
    // A's own vertices as they are: the identity pose changes no bit.
    for (int i = 0; i < geometry.count; ++i)
        geometry.points[i] = toCommon ? toCommon->apply(box.vertices()[indices[i]]) : box.vertices()[indices[i]];
    if (feature.type == FeatureType::Face) {
        const Polytope::Face& face = box.faces()[feature.index];
        if (toCommon) {
            geometry.planeNormal = toCommon->rotation * face.normal;
            geometry.planeOffset = face.offset + geometry.planeNormal.dot(toCommon->position);
        } else {
            geometry.planeNormal = face.normal;
            geometry.planeOffset = face.offset;
        }
    }
    return geometry;
}

}  // namespace gdc::detail
