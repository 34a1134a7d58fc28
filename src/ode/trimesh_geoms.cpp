// The meshes of ODE's trimesh datas, read through their geoms and cached by data (trimesh_geoms.hpp).
#include "trimesh_geoms.hpp"

#include "free_hook.hpp"
#include "ode_real.hpp"

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gdc::ode::detail {
namespace {

// The triangles compared on every use: the first, the middle and the last.
constexpr int kSamples = 3;
using Triangle = std::array<Vec3, 3>;

std::array<int, kSamples> sampledTriangles(int count) { return {0, count / 2, count - 1}; }

// Triangle t of the geom's data, in the geom's frame.
Triangle readTriangle(dGeomID geom, int t, const Pose& pose) {
    dVector3 world[3];
    dGeomTriMeshGetTriangle(geom, t, &world[0], &world[1], &world[2]);
    Triangle local;
    for (int k = 0; k < 3; ++k)
        local[k] = pose.applyInverse(Vec3(static_cast<double>(world[k][0]), static_cast<double>(world[k][1]),
                                          static_cast<double>(world[k][2])));
    return local;
}

struct Entry {
    std::shared_ptr<const TriangleMesh> mesh;  // null: the build failed (and said why)
    int triangleCount = 0;
    std::array<Triangle, kSamples> samples;  // the sampled triangles as read for the build
    double extent = 0;  // the mesh's size plus its largest coordinate: the scale of the mapping's rounding
    Settings settings;  // those the mesh was built with
};

struct Cache {
    std::mutex mutex;
    std::unordered_map<const void*, Entry> entries;  // by dTriMeshDataID
    // entries.size(), readable without the lock: the free hook skips the lock while it is 0.
    std::atomic<std::size_t> count{0};
};

// Never destroyed: ODE may free datas from static destructors that run after ours would have, and
// the free hook must still find the cache then.
Cache& cache() {
    static Cache* const instance = new Cache;
    return *instance;
}

// How far a vertex read now may be from the same vertex read for the build: the mapping back to
// the geom's frame rounds by a few ulps of the coordinates and the position, and a body's rotation
// is orthonormal only to rounding.
double sampleTolerance(double extent, const Pose& pose) {
    return inputRelativeTolerance(1e-9) * (extent + pose.position.norm());
}

// Equal within the tolerance, or both the same non-number (a data whose build failed on a NaN
// vertex must not be read again on every use).
bool close(double a, double b, double tolerance) {
    return std::abs(a - b) <= tolerance || a == b || (std::isnan(a) && std::isnan(b));
}

bool samplesMatch(const Entry& entry, const std::array<Triangle, kSamples>& now, const Pose& pose) {
    const double tolerance = sampleTolerance(entry.extent, pose);
    for (int s = 0; s < kSamples; ++s)
        for (int k = 0; k < 3; ++k)
            for (int axis = 0; axis < 3; ++axis)
                if (!close(entry.samples[s][k][axis], now[s][k][axis], tolerance)) return false;
    return true;
}

// A grid cell of the welding: coordinates divided by the weld tolerance, rounded down.
struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell& other) const { return x == other.x && y == other.y && z == other.z; }
};
struct CellHash {
    std::size_t operator()(const Cell& c) const {
        std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::uint64_t>(c.y) + 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= static_cast<std::uint64_t>(c.z) + 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h);
    }
};

std::int64_t cellOf(double coordinate, double size) {
    const double cell = std::floor(coordinate / size);
    constexpr double kLimit = 4e18;  // inside int64: the coordinates are finite, their ratio may be large
    return static_cast<std::int64_t>(std::max(-kLimit, std::min(kLimit, cell)));
}

// The corners (3 per triangle, in triangle order) welded: a vertex list and each triangle's
// indices. Two corners within `tolerance` of each other (in every coordinate) are one vertex, the
// first one seen. A grid of cells of that size holds at most one vertex a cell (two in one cell are
// within it), and a vertex within it of a corner lies in one of the corner's 27 cells.
void weld(const std::vector<Vec3>& corners, double tolerance, std::vector<Vec3>& vertices,
          std::vector<std::array<int, 3>>& triangles) {
    std::unordered_map<Cell, int, CellHash> grid;
    grid.reserve(corners.size());
    const bool gridded = tolerance > 0 && std::isfinite(tolerance);
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const Vec3& p = corners[i];
        int found = -1;
        Cell cell{0, 0, 0};
        if (gridded) {
            cell = Cell{cellOf(p.x(), tolerance), cellOf(p.y(), tolerance), cellOf(p.z(), tolerance)};
            for (int dx = -1; dx <= 1 && found < 0; ++dx)
                for (int dy = -1; dy <= 1 && found < 0; ++dy)
                    for (int dz = -1; dz <= 1 && found < 0; ++dz) {
                        auto at = grid.find(Cell{cell.x + dx, cell.y + dy, cell.z + dz});
                        if (at != grid.end() && (vertices[at->second] - p).cwiseAbs().maxCoeff() <= tolerance)
                            found = at->second;
                    }
        } else {  // a mesh of no size: only equal corners are one vertex
            for (std::size_t v = 0; v < vertices.size() && found < 0; ++v)
                if (vertices[v] == p) found = static_cast<int>(v);
        }
        if (found < 0) {
            found = static_cast<int>(vertices.size());
            vertices.push_back(p);
            if (gridded) grid.emplace(cell, found);
        }
        if (i % 3 == 0) triangles.push_back({found, found, found});
        triangles.back()[i % 3] = found;
    }
}

// Reads every triangle of the geom's data and builds its mesh into `entry` (mesh null when the data
// cannot be a mesh: the error is thrown after the entry is filled, so that it is said once).
void build(dGeomID geom, int count, const Pose& pose, const Settings& settings, Entry& entry,
           std::string& error) {
    std::vector<Vec3> corners;
    corners.reserve(static_cast<std::size_t>(count) * 3);
    Vec3 lower = Vec3::Constant(std::numeric_limits<double>::infinity()), upper = -lower;
    double largest = 0;
    for (int t = 0; t < count; ++t) {
        const Triangle triangle = readTriangle(geom, t, pose);
        for (const Vec3& p : triangle) {
            if (!p.allFinite()) {
                error = "trimesh: triangle " + std::to_string(t) +
                        " has a vertex that is not finite (in the data, or from the geom's pose)";
                return;
            }
            lower = lower.cwiseMin(p), upper = upper.cwiseMax(p);
            largest = std::max(largest, p.cwiseAbs().maxCoeff());
            corners.push_back(p);
        }
    }
    const double size = (upper - lower).norm();
    entry.extent = size + largest;
    // A billionth of the mesh's size, or the rounding of the mapping back where that is larger (a
    // small mesh far from its frame's origin or from the world's).
    const double tolerance =
        std::max(inputRelativeTolerance(1e-9) * size,
                 16 * std::numeric_limits<dReal>::epsilon() * (largest + pose.position.norm()));
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;
    weld(corners, tolerance, vertices, triangles);
    try {
        entry.mesh = std::make_shared<const TriangleMesh>(std::move(vertices), triangles, settings);
    } catch (const InvalidInput& failure) {
        error = failure.what();
    }
}

}  // namespace

std::shared_ptr<const TriangleMesh> trimeshOf(dGeomID geom, const Pose& pose, const Settings& settings) {
    const dTriMeshDataID data = dGeomTriMeshGetData(geom);
    if (!data) throw InvalidInput("a trimesh geom has no data (dGeomTriMeshSetData)");
    if (!pose.isFinite()) throw InvalidInput("the trimesh geom's pose is not finite");
    const int count = dGeomTriMeshGetTriangleCount(geom);
    if (count <= 0) return nullptr;
    std::array<Triangle, kSamples> samples;
    const std::array<int, kSamples> sampled = sampledTriangles(count);
    for (int s = 0; s < kSamples; ++s) samples[s] = readTriangle(geom, sampled[s], pose);

    Cache& c = cache();
    {
        std::lock_guard lock(c.mutex);
        auto found = c.entries.find(data);
        if (found != c.entries.end() && found->second.triangleCount == count && found->second.settings == settings &&
            samplesMatch(found->second, samples, pose))
            return found->second.mesh;
    }
    // Built outside the lock (ODE's getters, and the mesh's tree: the time of reading the mesh).
    // Two threads meeting a new data at once both build it; the later one's entry stays.
    ensureFreeHook();
    Entry entry;
    entry.triangleCount = count;
    entry.samples = samples;
    entry.settings = settings;
    std::string error;
    build(geom, count, pose, settings, entry, error);
    std::shared_ptr<const TriangleMesh> mesh = entry.mesh;
    {
        Entry replaced;  // an earlier mesh of this address, released after the lock
        std::lock_guard lock(c.mutex);
        auto [at, inserted] = c.entries.try_emplace(data);
        if (!inserted) replaced = std::move(at->second);
        at->second = std::move(entry);
        c.count.store(c.entries.size(), std::memory_order_relaxed);
    }
    if (!error.empty()) {
        // InvalidInput's own message begins "gdcontact: "; the mesh's error already carries it.
        const std::string prefix = "gdcontact: ";
        if (error.compare(0, prefix.size(), prefix) == 0) error.erase(0, prefix.size());
        throw InvalidInput(error + " (the trimesh's pairs get no contacts until its data changes)");
    }
    return mesh;
}

void forgetTrimeshData(const void* address) noexcept {
    Cache& c = cache();
    if (c.count.load(std::memory_order_relaxed) == 0) return;
    Entry released;  // destroyed after the lock is dropped
    try {
        std::lock_guard lock(c.mutex);
        auto found = c.entries.find(address);
        if (found == c.entries.end()) return;
        released = std::move(found->second);
        c.entries.erase(found);
        c.count.store(c.entries.size(), std::memory_order_relaxed);
    } catch (...) {  // a lock failure: the entry stays, and the sampled triangles guard its next use
    }
}

std::size_t cachedTrimeshCount() {
    Cache& c = cache();
    std::lock_guard lock(c.mutex);
    return c.entries.size();
}

}  // namespace gdc::ode::detail
