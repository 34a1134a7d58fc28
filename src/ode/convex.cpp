// gdc::ode::createConvex: dConvex geoms whose hull gdcontact knows.
#include <gdcontact/ode.hpp>

#include "state.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace gdc::ode {
namespace {

using detail::ConvexRecord;

std::vector<Vec3> readPoints(const dReal* points, unsigned pointCount, const char* function) {
    if (!points) throw InvalidInput(std::string(function) + ": points is null");
    std::vector<Vec3> result;
    result.reserve(pointCount);
    for (unsigned i = 0; i < pointCount; ++i) {
        const Vec3 point(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
        if (!point.allFinite()) {
            std::ostringstream message;
            message << function << ": point " << i << " is not finite";
            throw InvalidInput(message.str());
        }
        result.push_back(point);
    }
    return result;
}

// ODE's layout of a polytope: a unit outward normal and offset per face, the vertices, and per
// face its vertex count followed by its vertex indices, counter-clockwise seen from outside.
void fillOdeArrays(const Polytope& hull, ConvexRecord& record) {
    for (const Vec3& vertex : hull.vertices())
        for (int axis = 0; axis < 3; ++axis) record.points.push_back(static_cast<dReal>(vertex[axis]));
    for (const Polytope::Face& face : hull.faces()) {
        for (int axis = 0; axis < 3; ++axis) record.planes.push_back(static_cast<dReal>(face.normal[axis]));
        record.planes.push_back(static_cast<dReal>(face.offset));
        record.polygons.push_back(static_cast<unsigned>(face.count));
        for (int k = 0; k < face.count; ++k)
            record.polygons.push_back(static_cast<unsigned>(hull.faceVertices()[face.first + k]));
    }
}

[[noreturn]] void reject(const std::string& what) {
    throw InvalidInput("createConvex (dCreateConvex layout): " + what);
}

}  // namespace

dGeomID createConvex(dSpaceID space, const dReal* points, unsigned pointCount) {
    const std::vector<Vec3> cloud = readPoints(points, pointCount, "createConvex");
    auto record = std::make_shared<ConvexRecord>();
    record->polytope = std::make_shared<const Polytope>(Polytope::fromPoints(cloud));
    fillOdeArrays(*record->polytope, *record);
    return detail::createRegisteredConvex(space, std::move(record));
}

dGeomID createConvex(dSpaceID space, const dReal* planes, unsigned planeCount,
                     const dReal* points, unsigned pointCount, const unsigned* polygons) {
    if (!planes) reject("planes is null");
    if (!polygons) reject("polygons is null");
    if (planeCount < 4) reject("a closed convex needs at least 4 planes, got " + std::to_string(planeCount));
    if (pointCount < 4) reject("a closed convex needs at least 4 points, got " + std::to_string(pointCount));
    const std::vector<Vec3> vertices = readPoints(points, pointCount, "createConvex (dCreateConvex layout)");

    // Tolerances relative to the shape's size, so that data typed with a few decimals (or as
    // floats) passes at any scale while a wrong sign or a misplaced plane does not.
    double size = 0.0;
    for (const Vec3& vertex : vertices) size = std::max(size, vertex.cwiseAbs().maxCoeff());
    Vec3 lower = vertices[0], upper = vertices[0];
    for (const Vec3& vertex : vertices) { lower = lower.cwiseMin(vertex); upper = upper.cwiseMax(vertex); }
    const double extent = (upper - lower).norm();
    if (!(extent > 0.0)) reject("all points coincide");
    const double distanceTolerance = 1e-6 * std::max(extent, size);
    constexpr double kNormalLengthTolerance = 1e-6;

    std::vector<std::vector<int>> faces(planeCount);
    std::vector<Vec3> normals(planeCount);
    std::vector<double> offsets(planeCount);
    std::size_t cursor = 0;
    for (unsigned plane = 0; plane < planeCount; ++plane) {
        const std::string name = "plane " + std::to_string(plane);
        const Vec3 normal(planes[4 * plane], planes[4 * plane + 1], planes[4 * plane + 2]);
        const double offset = planes[4 * plane + 3];
        if (!normal.allFinite() || !std::isfinite(offset)) reject(name + " is not finite");
        if (std::abs(normal.norm() - 1.0) > kNormalLengthTolerance) {
            std::ostringstream message;
            message << name << " has a normal of length " << normal.norm()
                    << "; dCreateConvex needs unit normals";
            reject(message.str());
        }
        const unsigned count = polygons[cursor++];
        if (count < 3) reject("polygon of " + name + " has " + std::to_string(count) + " vertices (at least 3)");
        if (count > pointCount) reject("polygon of " + name + " has more vertices than there are points");
        for (unsigned k = 0; k < count; ++k) {
            const unsigned index = polygons[cursor + k];
            if (index >= pointCount)
                reject("polygon of " + name + " names point " + std::to_string(index) + " of " +
                       std::to_string(pointCount));
            faces[plane].push_back(static_cast<int>(index));
        }
        // Every corner must turn the same way about the plane normal: left (counter-clockwise
        // seen from outside) at all corners is right, right at all is the wrong winding, a mix is
        // a bow tie or a dent. Collinear corners (turn ≈ 0) are allowed.
        int leftTurns = 0, rightTurns = 0;
        double totalTurn = 0.0;  // radians; 2π for a simple convex polygon, 4π for a pentagram
        for (unsigned k = 0; k < count; ++k) {
            const Vec3& previous = vertices[faces[plane][k]];
            const Vec3& corner = vertices[faces[plane][(k + 1) % count]];
            const Vec3& next = vertices[faces[plane][(k + 2) % count]];
            const double onPlane = normal.dot(corner) - offset;
            if (std::abs(onPlane) > distanceTolerance) {
                std::ostringstream message;
                message << name << " offset " << offset << " does not match its polygon: point "
                        << faces[plane][(k + 1) % count] << " lies " << onPlane
                        << " from the plane (n·x must equal d)";
                reject(message.str());
            }
            const double turn = (corner - previous).cross(next - corner).dot(normal);
            if (turn > distanceTolerance * distanceTolerance) ++leftTurns;
            if (turn < -distanceTolerance * distanceTolerance) ++rightTurns;
            totalTurn += std::atan2(turn, (corner - previous).dot(next - corner));
        }
        if (leftTurns == 0 && rightTurns > 0)
            reject("polygon of " + name +
                   " is wound clockwise seen from outside (dCreateConvex needs counter-clockwise), "
                   "or the plane's normal points inwards");
        if (rightTurns > 0 || leftTurns < 3 || std::abs(totalTurn - 2 * M_PI) > 1e-3)
            reject("polygon of " + name + " is not a convex polygon (self-intersecting, dented or degenerate)");
        cursor += count;
        normals[plane] = normal;
        offsets[plane] = offset;
    }
    for (unsigned plane = 0; plane < planeCount; ++plane)
        for (unsigned point = 0; point < pointCount; ++point) {
            const double outside = normals[plane].dot(vertices[point]) - offsets[plane];
            if (outside > distanceTolerance) {
                std::ostringstream message;
                message << "point " << point << " lies " << outside << " outside plane " << plane
                        << ": the shape is not convex (or the plane faces the wrong way)";
                reject(message.str());
            }
        }

    auto record = std::make_shared<ConvexRecord>();
    // fromFaces checks the topology: closed, consistently wound, non-degenerate.
    record->polytope = std::make_shared<const Polytope>(Polytope::fromFaces(vertices, faces));
    // ODE gets the caller's data (copied): its own colliders then behave as with dCreateConvex.
    record->planes.assign(planes, planes + 4 * static_cast<std::size_t>(planeCount));
    record->points.assign(points, points + 3 * static_cast<std::size_t>(pointCount));
    record->polygons.assign(polygons, polygons + cursor);
    return detail::createRegisteredConvex(space, std::move(record));
}

}  // namespace gdc::ode
