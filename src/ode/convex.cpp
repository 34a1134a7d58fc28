// gdc::ode::createConvex / createConvexStrict: dConvex geoms whose hull gdcontact knows.
#include <gdcontact/ode.hpp>

#include "convex_registry.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace gdc::ode {
namespace {

using detail::ConvexRecord;

// The precision dCreateConvex data is checked to, relative to the shape's size: data printed with
// 6 significant digits is off by up to ~5e-7 of each coordinate, so a point lies a few 1e-6 of
// the size off its plane and a normal's length is 1 ± 1e-6. 1e-5 passes that (and floats), and
// still tells a misplaced, flipped or reordered plane (off by a sizeable part of the shape).
constexpr double kDataPrecision = 1e-5;

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

std::shared_ptr<const Polytope> hullOf(const std::vector<Vec3>& points) {
    return std::make_shared<const Polytope>(Polytope::fromPoints(points));
}

// The caller's data, read and checked against itself. `problem` is empty when the planes and
// polygons describe the hull of the points within the data's precision, else it says (for a
// human) the first way they do not. Errors that make the data unreadable — null arrays, an index
// out of range, a non-finite number — throw: ODE itself would read out of bounds or compute NaN.
struct Layout {
    std::vector<Vec3> vertices;
    std::vector<std::vector<int>> faces;
    std::size_t polygonLength = 0;  // entries of `polygons` read
    std::string problem;
};

Layout readLayout(const dReal* planes, unsigned planeCount, const dReal* points, unsigned pointCount,
                  const unsigned* polygons, const char* function) {
    const std::string prefix = std::string(function) + ": ";
    Layout layout;
    layout.vertices = readPoints(points, pointCount, function);
    if (pointCount < 4)
        throw InvalidInput(prefix + "a closed convex needs at least 4 points, got " + std::to_string(pointCount));
    if (planeCount > 0 && !planes) throw InvalidInput(prefix + "planes is null");
    if (planeCount > 0 && !polygons) throw InvalidInput(prefix + "polygons is null");
    const std::vector<Vec3>& vertices = layout.vertices;
    auto note = [&](const std::string& what) {
        if (layout.problem.empty()) layout.problem = what;
    };

    // Tolerances relative to the shape's size, so that data typed with a few decimals (or as
    // floats) passes at any scale while a wrong sign or a misplaced plane does not.
    double size = 0.0;
    Vec3 lower = vertices[0], upper = vertices[0];
    for (const Vec3& vertex : vertices) {
        size = std::max(size, vertex.cwiseAbs().maxCoeff());
        lower = lower.cwiseMin(vertex);
        upper = upper.cwiseMax(vertex);
    }
    const double extent = (upper - lower).norm();
    if (!(extent > 0.0)) throw InvalidInput(prefix + "all points coincide");
    const double distanceTolerance = kDataPrecision * std::max(extent, size);

    if (planeCount < 4) note("a closed convex needs at least 4 planes, got " + std::to_string(planeCount));
    layout.faces.resize(planeCount);
    std::vector<Vec3> normals(planeCount);
    std::vector<double> offsets(planeCount);
    std::size_t cursor = 0;
    for (unsigned plane = 0; plane < planeCount; ++plane) {
        const std::string name = "plane " + std::to_string(plane);
        const Vec3 normal(planes[4 * plane], planes[4 * plane + 1], planes[4 * plane + 2]);
        const double offset = planes[4 * plane + 3];
        if (!normal.allFinite() || !std::isfinite(offset)) throw InvalidInput(prefix + name + " is not finite");
        const unsigned count = polygons[cursor++];
        if (count > pointCount)
            throw InvalidInput(prefix + "polygon of " + name + " has more vertices (" + std::to_string(count) +
                               ") than there are points");
        for (unsigned k = 0; k < count; ++k) {
            const unsigned index = polygons[cursor + k];
            if (index >= pointCount)
                throw InvalidInput(prefix + "polygon of " + name + " names point " + std::to_string(index) +
                                   " of " + std::to_string(pointCount));
            layout.faces[plane].push_back(static_cast<int>(index));
        }
        cursor += count;
        normals[plane] = normal;
        offsets[plane] = offset;
        if (!layout.problem.empty()) continue;  // one problem is enough; keep reading for the bounds

        if (std::abs(normal.norm() - 1.0) > kDataPrecision) {
            std::ostringstream message;
            message << name << " has a normal of length " << normal.norm() << " (dCreateConvex needs unit normals)";
            note(message.str());
            continue;
        }
        if (count < 3) {
            note("polygon of " + name + " has " + std::to_string(count) + " vertices (at least 3)");
            continue;
        }
        // Every corner must turn the same way about the plane normal: left (counter-clockwise
        // seen from outside) at all corners is right, right at all is the wrong winding, a mix is
        // a bow tie or a dent. Collinear corners (turn ≈ 0) are allowed.
        int leftTurns = 0, rightTurns = 0;
        double totalTurn = 0.0;  // radians; 2π for a simple convex polygon, 4π for a pentagram
        std::string offPlane;
        for (unsigned k = 0; k < count; ++k) {
            const std::vector<int>& loop = layout.faces[plane];
            const Vec3& previous = vertices[loop[k]];
            const Vec3& corner = vertices[loop[(k + 1) % count]];
            const Vec3& next = vertices[loop[(k + 2) % count]];
            const double onPlane = normal.dot(corner) - offset;
            if (std::abs(onPlane) > distanceTolerance && offPlane.empty()) {
                std::ostringstream message;
                message << name << " (offset " << offset << ") does not pass through its polygon: point "
                        << loop[(k + 1) % count] << " lies " << onPlane
                        << " from it (n·x must equal d; planes in another order than their polygons, or a "
                           "non-planar face)";
                offPlane = message.str();
            }
            const double turn = (corner - previous).cross(next - corner).dot(normal);
            if (turn > distanceTolerance * distanceTolerance) ++leftTurns;
            if (turn < -distanceTolerance * distanceTolerance) ++rightTurns;
            totalTurn += std::atan2(turn, (corner - previous).dot(next - corner));
        }
        if (!offPlane.empty()) {
            note(offPlane);
        } else if (leftTurns == 0 && rightTurns > 0) {
            note("polygon of " + name +
                 " is wound clockwise seen from outside (dCreateConvex needs counter-clockwise), "
                 "or the plane's normal points inwards");
        } else if (rightTurns > 0 || leftTurns < 3 || std::abs(totalTurn - 2 * M_PI) > 1e-3) {
            note("polygon of " + name + " is not a convex polygon (self-intersecting, dented or degenerate)");
        }
    }
    layout.polygonLength = cursor;
    if (!layout.problem.empty()) return layout;

    for (unsigned plane = 0; plane < planeCount && layout.problem.empty(); ++plane)
        for (unsigned point = 0; point < pointCount; ++point) {
            const double outside = normals[plane].dot(vertices[point]) - offsets[plane];
            if (outside > distanceTolerance) {
                std::ostringstream message;
                message << "point " << point << " lies " << outside << " outside plane " << plane
                        << ": the planes do not bound the points (a plane facing inwards, or the "
                           "points are not convex)";
                note(message.str());
                break;
            }
        }
    if (!layout.problem.empty()) return layout;

    // A closed surface: every directed edge once, and its reverse in another polygon.
    std::map<std::pair<int, int>, int> edges;
    for (unsigned plane = 0; plane < planeCount; ++plane) {
        const std::vector<int>& loop = layout.faces[plane];
        for (std::size_t k = 0; k < loop.size(); ++k) ++edges[{loop[k], loop[(k + 1) % loop.size()]}];
    }
    for (const auto& [edge, uses] : edges) {
        const auto reverse = edges.find({edge.second, edge.first});
        if (uses != 1 || reverse == edges.end() || reverse->second != 1) {
            note("the polygons do not form a closed surface (a face is missing or repeated, near the edge "
                 "from point " + std::to_string(edge.first) + " to point " + std::to_string(edge.second) + ")");
            break;
        }
    }
    return layout;
}

dGeomID create(dSpaceID space, const dReal* planes, unsigned planeCount, const dReal* points,
               unsigned pointCount, const unsigned* polygons, bool strict) {
    const char* function = strict ? "createConvexStrict" : "createConvex (dCreateConvex layout)";
    Layout layout = readLayout(planes, planeCount, points, pointCount, polygons, function);
    auto record = std::make_shared<ConvexRecord>();
    if (layout.problem.empty()) {
        // The caller's faces, if they pass the polytope's own (tighter, 1e-7) checks; data rounded
        // to fewer digits gets the hull of its points instead — the same solid within the data's
        // precision. ODE gets the caller's data (copied): its colliders behave as with dCreateConvex.
        // The faces are used only when every point is a corner of one: the geom's AABB, which ODE
        // computes from all the points, must be the polytope's (the adapter checks it to see
        // dGeomSetConvex), and a point no polygon names may lie outside by the data's precision.
        std::vector<bool> used(layout.vertices.size(), false);
        for (const std::vector<int>& face : layout.faces)
            for (int index : face) used[static_cast<std::size_t>(index)] = true;
        const bool allUsed = std::find(used.begin(), used.end(), false) == used.end();
        if (allUsed) {
            try {
                record->polytope =
                    std::make_shared<const Polytope>(Polytope::fromFaces(layout.vertices, layout.faces));
            } catch (const InvalidInput&) {  // rounded beyond fromFaces' 1e-7: the hull below
            }
        }
        if (!record->polytope) record->polytope = hullOf(layout.vertices);
        record->planes.assign(planes, planes + 4 * static_cast<std::size_t>(planeCount));
        record->points.assign(points, points + 3 * static_cast<std::size_t>(pointCount));
        record->polygons.assign(polygons, polygons + layout.polygonLength);
        return detail::createRegisteredConvex(space, std::move(record));
    }
    if (strict) throw InvalidInput(std::string(function) + ": " + layout.problem);
    // The planes and polygons disagree with the points. ODE's libccd colliders use only the
    // points, so the solid ODE collides is their hull: gdcontact uses it and hands ODE the hull's
    // own planes and polygons, so that ODE's plane-based colliders (sphere, ray, ...) agree.
    record->polytope = hullOf(layout.vertices);  // throws for points without interior
    fillOdeArrays(*record->polytope, *record);
    dMessage(d_ERR_UNKNOWN,
             "gdcontact: createConvex: %s. Using the convex hull of the %u points (%zu faces), the solid "
             "ODE's convex collider sees; ODE is given the hull's planes and polygons. "
             "gdc::ode::createConvexStrict reports such data as an error instead.",
             layout.problem.c_str(), pointCount, record->polytope->faces().size());
    return detail::createRegisteredConvex(space, std::move(record));
}

}  // namespace

dGeomID createConvex(dSpaceID space, const dReal* points, unsigned pointCount) {
    const std::vector<Vec3> cloud = readPoints(points, pointCount, "createConvex");
    auto record = std::make_shared<ConvexRecord>();
    record->polytope = hullOf(cloud);
    fillOdeArrays(*record->polytope, *record);
    return detail::createRegisteredConvex(space, std::move(record));
}

dGeomID createConvex(dSpaceID space, const dReal* planes, unsigned planeCount,
                     const dReal* points, unsigned pointCount, const unsigned* polygons) {
    return create(space, planes, planeCount, points, pointCount, polygons, false);
}

dGeomID createConvexStrict(dSpaceID space, const dReal* planes, unsigned planeCount,
                           const dReal* points, unsigned pointCount, const unsigned* polygons) {
    return create(space, planes, planeCount, points, pointCount, polygons, true);
}

}  // namespace gdc::ode
