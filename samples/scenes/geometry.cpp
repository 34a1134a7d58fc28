#include "geometry.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace gdc::scenes {
namespace {

/// Unit directions of a polytope's edges in the world, parallel duplicates removed (a box has 12
/// edges but 3 directions; the SAT needs each direction once).
std::vector<Vec3> edgeDirections(const Polytope& shape, const Mat3& rotation) {
    std::vector<Vec3> directions;
    for (const Polytope::Edge& edge : shape.edges()) {
        Vec3 direction = shape.vertices()[edge.head] - shape.vertices()[edge.tail];
        const double length = direction.norm();
        if (length <= 0.0) continue;
        direction = rotation * (direction / length);
        const bool duplicate = std::any_of(directions.begin(), directions.end(), [&](const Vec3& known) {
            return known.cross(direction).squaredNorm() < 1e-20;
        });
        if (!duplicate) directions.push_back(direction);
    }
    return directions;
}

/// Overlap of the two vertex sets' projections on `axis` (negative: a gap).
double overlapAlong(const Vec3& axis, const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double minA = std::numeric_limits<double>::infinity(), maxA = -minA;
    double minB = minA, maxB = -minA;
    for (const Vec3& v : a) {
        const double s = axis.dot(v);
        minA = std::min(minA, s);
        maxA = std::max(maxA, s);
    }
    for (const Vec3& v : b) {
        const double s = axis.dot(v);
        minB = std::min(minB, s);
        maxB = std::max(maxB, s);
    }
    return std::min(maxA - minB, maxB - minA);
}

}  // namespace

double penetrationDepth(const Polytope& a, const Pose& poseA, const Polytope& b, const Pose& poseB) {
    // Work relative to A's position so that far-from-origin scenes keep their precision.
    const Vec3 origin = poseA.position;
    std::vector<Vec3> worldA, worldB;
    worldA.reserve(a.vertices().size());
    worldB.reserve(b.vertices().size());
    for (const Vec3& v : a.vertices()) worldA.push_back(poseA.rotation * v);
    for (const Vec3& v : b.vertices()) worldB.push_back(poseB.rotation * v + (poseB.position - origin));

    // The minimum translation distance is the smallest overlap over the face normals of the
    // Minkowski difference; those are among A's and B's face normals and the edge-edge cross
    // products, and any other axis only over-estimates, so the minimum over this set is exact.
    double depth = std::numeric_limits<double>::infinity();
    auto consider = [&](const Vec3& axis) {
        depth = std::min(depth, overlapAlong(axis, worldA, worldB));
        return depth > 0.0;
    };
    for (const Polytope::Face& face : a.faces())
        if (!consider(poseA.rotation * face.normal)) return 0.0;
    for (const Polytope::Face& face : b.faces())
        if (!consider(poseB.rotation * face.normal)) return 0.0;
    const std::vector<Vec3> edgesA = edgeDirections(a, poseA.rotation);
    const std::vector<Vec3> edgesB = edgeDirections(b, poseB.rotation);
    for (const Vec3& edgeA : edgesA) {
        for (const Vec3& edgeB : edgesB) {
            const Vec3 axis = edgeA.cross(edgeB);
            const double length = axis.norm();
            if (length < 1e-9) continue;  // parallel edges: their plane's normal is already a face normal
            if (!consider(axis / length)) return 0.0;
        }
    }
    return std::max(depth, 0.0);
}

double penetrationDepth(const Polytope& a, const Pose& poseA, const HalfSpace& halfSpace) {
    const Vec3 normal = halfSpace.normal.normalized();
    double deepest = 0.0;
    for (const Vec3& v : a.vertices()) deepest = std::max(deepest, halfSpace.offset - normal.dot(poseA.apply(v)));
    return deepest;
}

MassProperties massProperties(const Polytope& shape) {
    // Decompose into tetrahedra (apex at an interior point, base a fan triangle of a face) and sum
    // their volumes, first and second moments; the covariance formula of a tetrahedron with
    // vertices v0..v3 is  ∫ x xᵀ dV = V/20 · (Σ vᵢvᵢᵀ + s sᵀ),  s = Σ vᵢ.
    const Vec3 apex = shape.centroid();
    double volume = 0.0;
    Vec3 firstMoment = Vec3::Zero();
    Mat3 covariance = Mat3::Zero();
    const auto& vertices = shape.vertices();
    for (const Polytope::Face& face : shape.faces()) {
        const Vec3& v0 = vertices[shape.faceVertices()[face.first]];
        for (int k = 1; k + 1 < face.count; ++k) {
            const Vec3& v1 = vertices[shape.faceVertices()[face.first + k]];
            const Vec3& v2 = vertices[shape.faceVertices()[face.first + k + 1]];
            const double tetraVolume = (v0 - apex).dot((v1 - apex).cross(v2 - apex)) / 6.0;
            const Vec3 sum = apex + v0 + v1 + v2;
            volume += tetraVolume;
            firstMoment += tetraVolume * sum / 4.0;
            Mat3 outer = apex * apex.transpose() + v0 * v0.transpose() + v1 * v1.transpose() +
                         v2 * v2.transpose() + sum * sum.transpose();
            covariance += tetraVolume / 20.0 * outer;
        }
    }
    MassProperties result;
    result.volume = volume;
    result.centroid = firstMoment / volume;
    const Mat3 centred = covariance - volume * result.centroid * result.centroid.transpose();
    result.inertiaAboutCentroid = centred.trace() * Mat3::Identity() - centred;
    return result;
}

double Random::uniform(double low, double high) {
    // SplitMix64: tiny, well mixed and fully specified.
    state_ += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    const double unit = static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);  // 53 bits
    return low + (high - low) * unit;
}

std::pair<std::shared_ptr<const Polytope>, Vec3> centredOnCentroid(const Polytope& shape) {
    std::vector<Vec3> points;
    for (const Vec3& v : shape.vertices()) points.push_back(v - shape.centroid());
    return {std::make_shared<const Polytope>(Polytope::fromPoints(points)), shape.centroid()};
}

std::shared_ptr<const Polytope> makeBox(const Vec3& halfExtents) {
    return std::make_shared<const Polytope>(Polytope::box(halfExtents));
}

std::shared_ptr<const Polytope> makePrism(int sides, double radius, double halfHeight) {
    std::vector<Vec3> points;
    for (int i = 0; i < sides; ++i) {
        const double angle = 2.0 * kPi * i / sides;
        points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), -halfHeight);
        points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), halfHeight);
    }
    return std::make_shared<const Polytope>(Polytope::fromPoints(points));
}

namespace {

void checkRoundSize(double radius, double length, int sides) {
    if (!(radius > 0.0) || !(length > 0.0) || !std::isfinite(radius) || !std::isfinite(length) || sides < 3)
        throw InvalidInput("a cylinder or capsule needs a finite radius and length > 0 and at least 3 sides");
}

/// Points on a capsule's surface: `sides` points on each ring, rings every 90°/⌈sides/4⌉ of latitude
/// on both end balls, and the two poles.
std::vector<Vec3> capsuleSurfacePoints(double radius, double length, int sides) {
    const int rings = std::max(1, (sides + 3) / 4);
    std::vector<Vec3> points{Vec3(0, 0, 0.5 * length + radius), Vec3(0, 0, -0.5 * length - radius)};
    for (int ring = 0; ring < rings; ++ring) {
        const double latitude = 0.5 * kPi * ring / rings;
        const double rho = radius * std::cos(latitude), height = radius * std::sin(latitude);
        for (int i = 0; i < sides; ++i) {
            const double angle = 2.0 * kPi * i / sides;
            for (double end : {-1.0, 1.0})
                points.emplace_back(rho * std::cos(angle), rho * std::sin(angle), end * (0.5 * length + height));
        }
    }
    return points;
}

PlacedPart roundPart(RoundKind kind, std::shared_ptr<const Polytope> tessellation, double radius, double length) {
    PlacedPart part;
    part.shape = std::move(tessellation);
    part.round = kind;
    part.roundRadius = radius;
    part.roundLength = length;
    return part;
}

}  // namespace

PlacedPart makeCylinderPart(double radius, double length, int sides) {
    checkRoundSize(radius, length, sides);
    return roundPart(RoundKind::Cylinder, makePrism(sides, radius, 0.5 * length), radius, length);
}

PlacedPart makeCapsulePart(double radius, double length, int sides) {
    checkRoundSize(radius, length, sides);
    auto hull = std::make_shared<const Polytope>(Polytope::fromPoints(capsuleSurfacePoints(radius, length, sides)));
    return roundPart(RoundKind::Capsule, std::move(hull), radius, length);
}

MassProperties massProperties(const PlacedPart& part) {
    if (part.round == RoundKind::None) return massProperties(*part.shape);
    // ODE's own formulas at unit density: the mass is the volume, the inertia per kg/m³.
    dMass mass;
    if (part.round == RoundKind::Cylinder) dMassSetCylinder(&mass, 1.0, 3, part.roundRadius, part.roundLength);
    else dMassSetCapsule(&mass, 1.0, 3, part.roundRadius, part.roundLength);
    MassProperties properties;
    properties.volume = mass.mass;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) properties.inertiaAboutCentroid(row, column) = mass.I[row * 4 + column];
    return properties;
}

std::shared_ptr<const Polytope> makeIrregularSlab(Random& random, double radius, double halfHeight) {
    std::vector<Vec3> points;
    auto ring = [&](int count, double z, double minRadius, double maxRadius) {
        const double start = random.uniform(0.0, 2.0 * kPi);
        for (int i = 0; i < count; ++i) {
            const double angle = start + 2.0 * kPi * (i + random.uniform(-0.3, 0.3)) / count;
            const double r = random.uniform(minRadius, maxRadius);
            points.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
        }
    };
    ring(6, -halfHeight, 0.75 * radius, radius);
    ring(6, halfHeight, 0.65 * radius, 0.9 * radius);
    for (int i = 0; i < 6; ++i) {  // the irregular belt
        const double angle = random.uniform(0.0, 2.0 * kPi);
        const double r = random.uniform(0.6 * radius, radius);
        points.emplace_back(r * std::cos(angle), r * std::sin(angle), random.uniform(-0.8, 0.8) * halfHeight);
    }
    return std::make_shared<const Polytope>(Polytope::fromPoints(points));
}

std::vector<PlacedPart> makeGear(double hubRadius, int hubSides, int teeth, const Vec3& toothHalfExtents,
                                 double halfThickness) {
    std::vector<PlacedPart> parts;
    parts.push_back({makePrism(hubSides, hubRadius, halfThickness), Pose{}, false, Vec3::Zero()});
    const Vec3 toothHalf(toothHalfExtents.x(), toothHalfExtents.y(), halfThickness);
    const auto tooth = makeBox(toothHalf);
    for (int i = 0; i < teeth; ++i) {
        const double angle = 2.0 * kPi * (i + 0.5) / teeth;
        Pose offset;
        offset.rotation = Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
        // The tooth's inner half overlaps the hub (parts of one body may overlap), its outer half sticks out.
        offset.position = offset.rotation * Vec3(hubRadius * std::cos(kPi / hubSides), 0.0, 0.0);
        parts.push_back({tooth, offset, false, toothHalf});  // a convex part like the hub
    }
    return parts;
}

}  // namespace gdc::scenes
