// A body's convex parts from a Wavefront OBJ file, so a person can drop their own shapes into any
// scene. Two layouts: the whole file as one convex hull, or each object/group of the file as one
// convex part of a composite — the layout that convex decomposition tools (V-HACD, CoACD) write.
// Parsing is tinyobjloader's; hulls are gdc::Polytope::fromPoints (qhull).
#pragma once

#include "geometry.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace gdc::scenes {

enum class ObjLayout {
    Hull,       ///< every vertex of the file → one convex hull
    PartPerObject,  ///< each object (`o`) or group (`g`) with faces → one convex part (its hull)
};

/// What a file turned into: parts placed in a frame whose origin is their common centre of mass
/// (uniform density), so a body made of them sits where it is put.
struct ObjShape {
    std::vector<PlacedPart> parts;
    std::vector<std::string> partNames;  ///< the object/group name of each part ("hull" for Hull)
    double radius = 0.0;                 ///< largest distance of a vertex from the origin (m)
    double volume = 0.0;                 ///< sum of the parts' hull volumes (m³)
};

/// Why a file cannot be used: the message names the file and what is wrong with it.
class ObjError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Loads `path`, scaling every coordinate by `scale` (OBJ files carry no unit; the scenes are in
/// metres). Throws ObjError for a file that cannot be read or parsed, has no vertices, has
/// non-finite coordinates, or has a part with no volume (fewer than 4 points, or all of them on
/// one plane or line).
ObjShape loadObjShape(const std::string& path, ObjLayout layout, double scale = 1.0);
/// The same from OBJ text; `sourceName` stands for the file in error messages.
ObjShape parseObjShape(const std::string& text, ObjLayout layout, double scale = 1.0,
                       const std::string& sourceName = "OBJ text");

}  // namespace gdc::scenes
