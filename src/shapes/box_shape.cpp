// The box's shape hooks (box_shape.hpp).
#include "shapes/box_shape.hpp"

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

}  // namespace gdc::detail
