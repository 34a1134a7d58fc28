#include "obj_shape.hpp"

#include <tiny_obj_loader.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

namespace gdc::scenes {
namespace {

Vec3 vertexAt(const tinyobj::attrib_t& attrib, int index) {
    return Vec3(attrib.vertices[3 * index], attrib.vertices[3 * index + 1], attrib.vertices[3 * index + 2]);
}

/// The hull of one part, or an ObjError that says which part of which file has no volume.
std::shared_ptr<const Polytope> hullOf(const std::vector<Vec3>& points, const std::string& part,
                                       const std::string& sourceName) {
    try {
        return std::make_shared<const Polytope>(Polytope::fromPoints(points));
    } catch (const InvalidInput& e) {
        throw ObjError(sourceName + ": " + part + " cannot be a convex part (" + std::to_string(points.size()) +
                       " points): " + e.what());
    }
}

/// tinyobjloader reads a malformed vertex line ("v 1 2", "v a b c", "v nan 0 0") as zeros without a
/// word; a collision shape made from such a file would be silently wrong, so vertex lines are
/// checked first: three coordinates, an optional w, optionally three colour values after them.
void checkVertexLines(const std::string& text, const std::string& sourceName) {
    std::istringstream lines(text);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
        std::istringstream words(line);
        std::string keyword, word;
        words >> keyword;
        if (keyword != "v") continue;
        std::vector<std::string> values;
        while (words >> word) values.push_back(word);
        bool valid = values.size() == 3 || values.size() == 4 || values.size() == 6 || values.size() == 7;
        for (const std::string& value : values) {
            char* end = nullptr;
            const double x = std::strtod(value.c_str(), &end);
            valid = valid && end != value.c_str() && *end == '\0' && std::isfinite(x);
        }
        if (!valid) {
            while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
            throw ObjError(sourceName + ": line " + std::to_string(number) +
                           ": a vertex needs three finite numbers ('v x y z'), got '" + line + "'");
        }
    }
}

}  // namespace

ObjShape parseObjShape(const std::string& text, ObjLayout layout, double scale, const std::string& sourceName) {
    if (!(scale > 0.0) || !std::isfinite(scale))
        throw ObjError(sourceName + ": the scale must be finite and positive, got " + std::to_string(scale));
    checkVertexLines(text, sourceName);
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // only which vertices a part uses matters: its hull is taken
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // Materials are irrelevant to a collision shape: no MTL text, and `mtllib` lines are ignored.
    if (!reader.ParseFromString(text, "", config)) {
        std::string reason = reader.Error();
        while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
        throw ObjError(sourceName + ": not a readable OBJ file: " + (reason.empty() ? "parse error" : reason));
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const int vertexCount = int(attrib.vertices.size() / 3);
    if (vertexCount == 0) throw ObjError(sourceName + ": no vertices ('v x y z' lines)");

    // Each part as the set of vertex indices it uses; a set, because faces share their vertices.
    std::vector<std::pair<std::string, std::set<int>>> parts;
    if (layout == ObjLayout::Hull) {
        std::set<int> all;
        for (int i = 0; i < vertexCount; ++i) all.insert(i);
        parts.emplace_back("hull", std::move(all));
    } else {
        for (const tinyobj::shape_t& shape : reader.GetShapes()) {
            std::set<int> used;
            for (const tinyobj::index_t& index : shape.mesh.indices) used.insert(index.vertex_index);
            if (used.empty()) continue;  // an object of lines or points only: no solid to collide
            const std::string name = shape.name.empty() ? "object " + std::to_string(parts.size() + 1)
                                                        : "object '" + shape.name + "'";
            parts.emplace_back(name, std::move(used));
        }
        if (parts.empty())
            throw ObjError(sourceName + ": no faces ('f' lines), so no objects to make parts of "
                                        "(load it as one hull instead)");
    }

    ObjShape result;
    std::vector<std::pair<std::shared_ptr<const Polytope>, Vec3>> hulls;  // each about its centroid, and where that is
    for (const auto& [name, indices] : parts) {
        std::vector<Vec3> points;
        for (int index : indices) {
            // tinyobjloader resolves negative (relative) indices; anything still outside is the file's error.
            if (index < 0 || index >= vertexCount)
                throw ObjError(sourceName + ": " + name + " refers to vertex " + std::to_string(index + 1) +
                               " but the file has " + std::to_string(vertexCount));
            points.push_back(scale * vertexAt(attrib, index));
        }
        hulls.push_back(centredOnCentroid(*hullOf(points, name, sourceName)));
        result.partNames.push_back(name);
    }

    // The common centre of mass at uniform density becomes the origin of the parts' frame.
    Vec3 centre = Vec3::Zero();
    for (const auto& [hull, centroid] : hulls) {
        result.volume += hull->volume();
        centre += hull->volume() * centroid;
    }
    centre /= result.volume;
    for (const auto& [hull, centroid] : hulls) {
        PlacedPart part;
        part.shape = hull;
        part.offset.position = centroid - centre;
        result.parts.push_back(part);
        for (const Vec3& v : hull->vertices()) result.radius = std::max(result.radius, part.offset.apply(v).norm());
    }
    return result;
}

ObjShape loadObjShape(const std::string& path, ObjLayout layout, double scale) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw ObjError(path + ": cannot open: " + std::strerror(errno));
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad()) throw ObjError(path + ": cannot read: " + std::strerror(errno));
    return parseObjShape(text.str(), layout, scale, path);
}

}  // namespace gdc::scenes
