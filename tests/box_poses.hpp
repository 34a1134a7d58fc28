// Random box pairs by kind of contact, shared by the tests and tools that prove the box–box path
// equal to what it replaced (box_box_test, equality/manifold_dump).
#pragma once

#include "geometry_oracles.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace gdc::testing {

/// A small rotation: about a random axis by an angle in [-limit, limit].
inline Mat3 tilt(std::mt19937& random, double limit) {
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> angle(-limit, limit);
    return rotationAbout(Vec3(normal(random), normal(random), normal(random)).normalized(), angle(random));
}

/// Half extents of a random box: cubes, plates, large and small boxes, and any proportions.
inline Vec3 randomHalfExtents(std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0, 1), extent(0.05, 2.0);
    const double kind = unit(random);
    Vec3 half(extent(random), extent(random), extent(random));
    if (kind < 0.2) half.setConstant(half.x());  // cube
    else if (kind < 0.35) half[static_cast<int>(unit(random) * 3) % 3] = 0.002 + 0.01 * unit(random);  // plate
    else if (kind < 0.45) half *= 10;  // large, against a box of the usual size
    else if (kind < 0.55) half *= 0.05;  // small
    return half;
}

enum class BoxPoseKind { RestingFace, FaceNearTolerance, EdgeEdge, VertexFace, Deep, NearlyTouching, Scattered, Count };

/// A pose of B against A (A at the identity) of the given kind; the caller moves both together.
/// `angularTolerance` is the pipeline's (FaceNearTolerance tilts B about it); Scattered places B
/// anywhere within `scatter` times the pair's size of A (beyond 1: mostly separated).
inline Pose boxPoseOfKind(BoxPoseKind kind, const Vec3& halfA, const Vec3& halfB, double angularTolerance,
                          double scatter, std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0, 1), symmetric(-1, 1);
    const double size = halfA.norm() + halfB.norm();
    auto restOnTop = [&](const Mat3& rotation, double sink) {
        // B's lowest point along z just `sink` below A's top face, over a random point of that face.
        const double lowest = (rotation.transpose() * Vec3::UnitZ()).cwiseAbs().dot(halfB);
        const Vec3 over(symmetric(random) * halfA.x(), symmetric(random) * halfA.y(), 0);
        return Pose{rotation, over + Vec3(0, 0, halfA.z() + lowest - sink)};
    };
    // A turned by `rotationA` and B by `rotationB` (about a vertical z), B's lowest support point
    // above A's highest, moved by `offset` and sunk by `sink`; as B's pose in A's frame.
    auto touching = [&](const Mat3& rotationA, const Mat3& rotationB, const Vec3& offset, double sink) {
        const Vec3 up = Vec3::UnitZ();
        const Vec3 highestA = rotationA * (rotationA.transpose() * up).cwiseSign().cwiseProduct(halfA);
        const Vec3 lowestB = rotationB * -(rotationB.transpose() * up).cwiseSign().cwiseProduct(halfB);
        const Vec3 position = highestA - lowestB + offset - sink * up;
        return Pose{rotationA.transpose() * rotationB, rotationA.transpose() * position};
    };
    switch (kind) {
        case BoxPoseKind::RestingFace: {
            const Mat3 yaw = rotationAbout(Vec3::UnitZ(), unit(random) < 0.5 ? 0.0 : symmetric(random) * M_PI);
            return restOnTop(tilt(random, 0.01) * yaw, (symmetric(random) * 0.5 + 0.5) * 0.002 * size);
        }
        case BoxPoseKind::FaceNearTolerance: {
            const double angle = angularTolerance * (1 + 0.2 * symmetric(random));
            const Vec3 axis = rotationAbout(Vec3::UnitZ(), symmetric(random) * M_PI) * Vec3::UnitX();
            return restOnTop(rotationAbout(axis, angle), unit(random) * 0.002 * size);
        }
        case BoxPoseKind::EdgeEdge: {
            // A with an edge up (about y), B with an edge down (about x) turned by a random yaw.
            const Mat3 aEdgeUp = rotationAbout(Vec3::UnitY(), M_PI / 4 + 0.05 * symmetric(random));
            const Mat3 edgeDown = rotationAbout(Vec3::UnitZ(), symmetric(random) * M_PI) *
                                  rotationAbout(Vec3::UnitX(), M_PI / 4 + 0.05 * symmetric(random));
            const double reach = 0.3 * std::min(halfA.minCoeff(), halfB.minCoeff());
            return touching(aEdgeUp, edgeDown, Vec3(symmetric(random), symmetric(random), 0) * reach,
                            unit(random) * 0.01 * size);
        }
        case BoxPoseKind::VertexFace: {
            const Mat3 cornerDown = Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1).normalized(), -Vec3::UnitZ())
                                        .toRotationMatrix();
            return restOnTop(tilt(random, 0.2) * cornerDown, unit(random) * 0.01 * size);
        }
        case BoxPoseKind::Deep:
            return Pose{randomRotation(random), Vec3(symmetric(random), symmetric(random), symmetric(random)) *
                                                    (0.3 * halfA.minCoeff())};
        case BoxPoseKind::NearlyTouching: {
            // Random orientations, B's lowest point over A's highest, from 0.5 % of the size apart
            // to 0.5 % overlapping: every pair of features, touching or within a margin.
            const double reach = 0.3 * std::min(halfA.minCoeff(), halfB.minCoeff());
            return touching(randomRotation(random), randomRotation(random),
                            Vec3(symmetric(random), symmetric(random), 0) * reach, 0.005 * size * symmetric(random));
        }
        default:
            return Pose{randomRotation(random),
                        Vec3(symmetric(random), symmetric(random), symmetric(random)) * (scatter * size)};
    }
}

/// Random settings for a box pair's equality tests: a budget of 1 to 8, a margin up to 2 % of
/// `size` on half the poses, the region spanned on half, an angular tolerance up to 0.7 rad on a
/// fifth (the box path's range).
inline Settings randomBoxPairSettings(std::mt19937& random, double size) {
    std::uniform_real_distribution<double> unit(0, 1);
    Settings settings;
    settings.maxContacts = 1 + static_cast<int>(unit(random) * 8) % 8;
    settings.margin = unit(random) < 0.5 ? 0.0 : unit(random) * 0.02 * size;
    settings.spanContactRegion = unit(random) < 0.5;
    if (unit(random) < 0.2) settings.angularTolerance = unit(random) * 0.7;
    return settings;
}

}  // namespace gdc::testing
