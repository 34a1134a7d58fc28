#include "demo_support.hpp"

#include <gdcontact/polytope.hpp>

#include <algorithm>
#include <cstdlib>

namespace dropin {
namespace {

double sixDecimals(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6f", value);
    return std::strtod(text, nullptr);
}

ConvexData layoutOf(const gdc::Polytope& hull) {
    ConvexData data;
    for (const gdc::Vec3& v : hull.vertices())
        for (int axis = 0; axis < 3; ++axis) data.points.push_back(sixDecimals(v[axis]));
    for (const gdc::Polytope::Face& face : hull.faces()) {
        for (int axis = 0; axis < 3; ++axis) data.planes.push_back(sixDecimals(face.normal[axis]));
        data.planes.push_back(sixDecimals(face.offset));
        data.polygons.push_back(static_cast<unsigned>(face.count));
        for (int k = 0; k < face.count; ++k)
            data.polygons.push_back(static_cast<unsigned>(hull.faceVertices()[face.first + k]));
    }
    return data;
}

}  // namespace

ConvexData roundedIcosahedron(double radius, bool inwards) {
    const double phi = (1 + std::sqrt(5.0)) / 2, scale = radius / std::sqrt(1 + phi * phi);
    std::vector<gdc::Vec3> points;
    for (double a : {-1.0, 1.0})
        for (double b : {-phi, phi}) {
            points.emplace_back(0, a * scale, b * scale);
            points.emplace_back(a * scale, b * scale, 0);
            points.emplace_back(b * scale, 0, a * scale);
        }
    ConvexData data = layoutOf(gdc::Polytope::fromPoints(points));
    if (inwards)
        for (dReal& value : data.planes) value = -value;
    return data;
}

ConvexData roundedPrismShuffled(double r, double h) {
    std::vector<gdc::Vec3> points;
    for (int k = 0; k < 6; ++k)
        for (double z : {-h, h}) points.emplace_back(r * std::cos(k * M_PI / 3), r * std::sin(k * M_PI / 3), z);
    ConvexData data = layoutOf(gdc::Polytope::fromPoints(points));
    // The planes in reverse order; the polygons stay as they were.
    std::vector<dReal> reversed;
    for (std::size_t p = data.planes.size() / 4; p-- > 0;)
        reversed.insert(reversed.end(), data.planes.begin() + 4 * p, data.planes.begin() + 4 * p + 4);
    data.planes = reversed;
    return data;
}

}  // namespace dropin
