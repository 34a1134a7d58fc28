// The result of a collision query: one normal and up to kMaxManifoldPoints contact points,
// each with its own depth.
#pragma once

#include <gdcontact/types.hpp>

#include <array>
#include <cstdint>

namespace gdc {

constexpr int kMaxManifoldPoints = 16;

enum class FeatureType : std::uint8_t { Vertex, Edge, Face };

/// A feature of a polytope picked from its Gauss map: a vertex, edge or face index.
struct Feature {
    FeatureType type = FeatureType::Vertex;
    int index = -1;
};

struct ContactPoint {
    /// World position, midway between the two surfaces (inside the overlap region).
    /// The point on A is position + depth/2·normal, the point on B is position − depth/2·normal.
    Vec3 position = Vec3::Zero();
    /// Overlap along the normal (world length). ≥ 0 when touching or overlapping; down to
    /// −Settings::margin for speculative points.
    double depth = 0.0;
};

struct Manifold {
    /// World-frame unit normal pointing from A towards B: translating A by −depth·normal
    /// (or B by +depth·normal) separates the pair at that point. Undefined when pointCount == 0.
    Vec3 normal = Vec3::UnitZ();
    int pointCount = 0;
    /// points[0 .. pointCount); the others are unspecified (an answer repeated from a PairCache
    /// leaves there what an earlier answer had).
    std::array<ContactPoint, kMaxManifoldPoints> points{};
    /// The Gauss-map features the points came from (for diagnostics and tests).
    Feature featureA, featureB;

    bool empty() const { return pointCount == 0; }
    /// Becomes `other`, copying only its pointCount points (the others are left as they were and
    /// are never read): a whole Manifold is 0.6 KB, a typical answer a tenth of that.
    void assignUsed(const Manifold& other) {
        normal = other.normal;
        pointCount = other.pointCount;
        for (int i = 0; i < other.pointCount; ++i) points[i] = other.points[i];
        featureA = other.featureA;
        featureB = other.featureB;
    }
    double maxDepth() const {
        double deepest = -1e300;
        for (int i = 0; i < pointCount; ++i) deepest = points[i].depth > deepest ? points[i].depth : deepest;
        return deepest;
    }
};

}  // namespace gdc
