// The polytope–half-space specialised path (src/contact/half_space.cpp) against the general one
// (generalManifold, the general hooks): the same Manifold — normal, points in order, depths, count, features —
// on random poses of boxes and hulls, and the same errors; pinned where the two could part (a face
// tilted exactly at the angular tolerance, an exact touch, a box with one tiny extent), and the
// box layout the closed form relies on.
#include "general_pipeline.hpp"
#include "contact/gauss_map.hpp"
#include "geometry_oracles.hpp"
#include "contact/half_space.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace gdc;
using namespace gdc::testing;

namespace {

// Largest differences found, relative to the shape's size (for the report).
struct Differences {
    double position = 0, depth = 0, normal = 0;
    long poses = 0, compared = 0, nonEmpty = 0, fastPath = 0;
    long features[3] = {0, 0, 0};  // vertex, edge, face contacts seen
};

// Asserts that the two manifolds agree: counts and features exactly, numbers within rounding of
// `size` (in fact they are computed by the same expressions and agree to the bit).
void requireSame(const Manifold& general, const Manifold& fast, double size, Differences& differences) {
    ++differences.compared;
    REQUIRE(fast.pointCount == general.pointCount);
    if (general.pointCount == 0) return;
    ++differences.nonEmpty;
    ++differences.features[static_cast<int>(general.featureA.type)];
    REQUIRE(fast.featureA.type == general.featureA.type);
    REQUIRE(fast.featureA.index == general.featureA.index);
    REQUIRE(fast.featureB.type == general.featureB.type);
    REQUIRE(fast.featureB.index == general.featureB.index);
    const double normal = (fast.normal - general.normal).cwiseAbs().maxCoeff();
    REQUIRE(normal <= 1e-12);
    differences.normal = std::max(differences.normal, normal);
    for (int i = 0; i < general.pointCount; ++i) {
        const double position = (fast.points[i].position - general.points[i].position).cwiseAbs().maxCoeff() / size;
        const double depth = std::abs(fast.points[i].depth - general.points[i].depth) / size;
        INFO("point " << i);
        REQUIRE(position <= 1e-9);
        REQUIRE(depth <= 1e-9);
        differences.position = std::max(differences.position, position);
        differences.depth = std::max(differences.depth, depth);
    }
}

// The error message of one query ("" when it returns).
template <class Query>
std::string errorOf(Query&& query) {
    try {
        query();
    } catch (const InvalidInput& error) {
        return error.what();
    }
    return "";
}

// Runs the dispatching collide() and the general path on the same input; also the specialised
// path directly where it applies, so that a silent fallback cannot pass for it.
void compareOne(const Polytope& shape, const Pose& pose, const HalfSpace& plane, const Settings& settings,
                Differences& differences) {
    const double size = shape.radius();
    ++differences.poses;
    const Manifold general = generalManifold(shape, pose, plane, settings);
    requireSame(general, collide(shape, pose, plane, settings), size, differences);
    if (detail::halfSpaceFastPathApplies(shape, settings)) {
        ++differences.fastPath;
        Manifold fast;
        detail::collideHalfSpaceInto<detail::ImportanceOrder::Full>(shape, pose, detail::enterHalfSpace(pose, plane),
                                                                    settings, nullptr, fast);
        requireSame(general, fast, size, differences);
    }
}

// A random pose of `shape` against `plane` (normal n̂ once normalised): a face, edge or vertex
// turned towards the plane (or any orientation), tilted a little, spun about n̂, and placed so
// that its deepest vertex is `depth` into the solid.
template <class Random>
Pose randomPose(const Polytope& shape, const Vec3& unitNormal, double unitOffset, Random& random) {
    std::uniform_real_distribution<double> unit(0.0, 1.0), symmetric(-1.0, 1.0);
    const double size = shape.radius();
    // The shape's direction that should point into the solid (along −n̂), in its own frame.
    Vec3 down;
    const double kind = unit(random);
    if (kind < 0.35) {
        down = shape.faces()[static_cast<std::size_t>(unit(random) * shape.faces().size()) % shape.faces().size()].normal;
    } else if (kind < 0.55) {
        const Polytope::Edge& edge = shape.edges()[static_cast<std::size_t>(unit(random) * shape.edges().size()) % shape.edges().size()];
        down = (shape.faces()[edge.leftFace].normal + shape.faces()[edge.rightFace].normal).normalized();
    } else if (kind < 0.7) {
        const Vec3& vertex = shape.vertices()[static_cast<std::size_t>(unit(random) * shape.vertices().size()) % shape.vertices().size()];
        down = (vertex - shape.centroid()).normalized();
    } else {
        down = randomRotation(random).col(0);
    }
    // Tilts: none, within the angular tolerance, around it, or larger.
    const double tiltKind = unit(random);
    const double tilt = tiltKind < 0.15 ? 0.0 : tiltKind < 0.6 ? 0.01 * symmetric(random)
                                              : tiltKind < 0.85 ? 0.1 * symmetric(random) : 0.5 * symmetric(random);
    const Vec3 tiltAxis = randomRotation(random).col(0);
    const Mat3 turnDown = Eigen::Quaterniond::FromTwoVectors(down, -unitNormal).toRotationMatrix();
    const Mat3 rotation = rotationAbout(unitNormal, M_PI * symmetric(random)) * rotationAbout(tiltAxis, tilt) * turnDown;
    // Depth of the deepest vertex: deep, resting, nearly touching, exactly touching, separated.
    const double depthKind = unit(random);
    const double depth = depthKind < 0.15   ? size * unit(random)
                         : depthKind < 0.5  ? 1e-3 * size * unit(random)
                         : depthKind < 0.65 ? 1e-9 * size * symmetric(random)
                         : depthKind < 0.7  ? 0.0
                                            : -0.2 * size * unit(random);
    double lowest = INFINITY;
    for (const Vec3& v : shape.vertices()) lowest = std::min(lowest, unitNormal.dot(rotation * v));
    const Vec3 along = Vec3(symmetric(random), symmetric(random), symmetric(random)) * 2 * size;
    const Vec3 inPlane = along - unitNormal.dot(along) * unitNormal;
    return Pose{rotation, inPlane + (unitOffset - depth - lowest) * unitNormal};
}

template <class Random>
Settings randomSettings(double size, Random& random) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Settings settings;
    settings.maxContacts = 1 + static_cast<int>(unit(random) * 8) % 8;
    if (unit(random) < 0.05) settings.maxContacts = unit(random) < 0.5 ? 0 : 16 + static_cast<int>(unit(random) * 8);
    settings.margin = unit(random) < 0.5 ? 0.0 : 0.05 * size * unit(random);
    settings.spanContactRegion = unit(random) < 0.5;
    const double toleranceKind = unit(random);
    if (toleranceKind < 0.2) settings.angularTolerance = 0.3 * unit(random);
    else if (toleranceKind < 0.25) settings.angularTolerance = 0.0;
    return settings;
}

// A plane with a random normal — unit, tiny or huge, sometimes the ground — and offset.
template <class Random>
HalfSpace randomPlane(double size, Random& random) {
    std::uniform_real_distribution<double> unit(0.0, 1.0), symmetric(-1.0, 1.0);
    const double kind = unit(random);
    const Vec3 normal = kind < 0.3 ? Vec3(Vec3::UnitZ()) : Vec3(randomRotation(random).col(2));
    const double scale = kind < 0.5 ? 1.0 : kind < 0.75 ? 1e-3 : 1e3;
    return HalfSpace{scale * normal, scale * 2 * size * symmetric(random)};
}

template <class Random>
void compareMany(const Polytope& shape, int poses, Random& random, Differences& differences) {
    for (int i = 0; i < poses; ++i) {
        const HalfSpace plane = randomPlane(shape.radius(), random);
        const double length = plane.normal.norm();
        const Pose pose = randomPose(shape, plane.normal / length, plane.offset / length, random);
        const Settings settings = randomSettings(shape.radius(), random);
        INFO("pose " << i << " rotation\n" << pose.rotation << "\nposition " << pose.position.transpose() << "\nplane "
                     << plane.normal.transpose() << " | " << plane.offset << "\nmaxContacts " << settings.maxContacts
                     << " margin " << settings.margin << " span " << settings.spanContactRegion << " tolerance "
                     << settings.angularTolerance);
        compareOne(shape, pose, plane, settings, differences);
    }
}

void report(const char* what, const Differences& d) {
    WARN(what << ": " << d.poses << " random poses (" << d.fastPath << " through the specialised path; "
              << d.compared << " comparisons, " << d.nonEmpty
              << " with contacts: " << d.features[0] << " vertex, " << d.features[1] << " edge, " << d.features[2]
              << " face); largest difference ÷ size: position " << d.position << ", depth "
              << d.depth << ", normal " << d.normal);
}

std::vector<Vec3> cubeCorners(double half) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? half : -half, i & 2 ? half : -half, i & 4 ? half : -half);
    return corners;
}

// A box tilted about x so that the contact direction's z component is exactly `cosine`.
Pose tiltedAbout(double cosine, double height) {
    const double sine = std::sqrt(1 - cosine * cosine);
    Mat3 rotation;
    rotation << 1, 0, 0, 0, cosine, -sine, 0, sine, cosine;
    return Pose{rotation, Vec3(0, 0, height)};
}

}  // namespace

TEST_CASE("half-space: Polytope::box's layout, which the closed-form box feature relies on") {
    for (const Vec3& extents : {Vec3(0.5, 0.5, 0.5), Vec3(2, 0.3, 1e-3), Vec3(1e-60, 3e-60, 2e-60), Vec3(1e60, 0.3e60, 0.7e60)}) {
        const Polytope box = Polytope::box(extents);
        INFO("extents " << extents.transpose());
        REQUIRE(box.isBox());
        REQUIRE(box.vertices().size() == 8);
        for (int v = 0; v < 8; ++v)
            for (int k = 0; k < 3; ++k) REQUIRE(box.vertices()[v][k] == ((v >> k) & 1 ? extents[k] : -extents[k]));
        REQUIRE(box.faces().size() == 6);
        for (int f = 0; f < 6; ++f) {
            Vec3 axis = Vec3::Zero();
            axis[f / 2] = f % 2 ? 1 : -1;
            REQUIRE(box.faces()[f].normal == axis);  // exactly: ±e_k, face 2k negative, 2k + 1 positive
            REQUIRE(box.faces()[f].nearestNeighbourCosine == 0);
        }
        const int edges[12][2] = {{0, 1}, {0, 2}, {0, 4}, {1, 3}, {1, 5}, {2, 3},
                                  {2, 6}, {3, 7}, {4, 5}, {4, 6}, {5, 7}, {6, 7}};
        REQUIRE(box.edges().size() == 12);
        for (int e = 0; e < 12; ++e) {
            REQUIRE(box.edges()[e].tail == edges[e][0]);
            REQUIRE(box.edges()[e].head == edges[e][1]);
            // Its direction normalises to exactly an axis (what selectFeature compares).
            const Vec3 along = (box.vertices()[edges[e][1]] - box.vertices()[edges[e][0]]).normalized();
            REQUIRE(along.cwiseAbs().maxCoeff() == 1);
            REQUIRE(along.cwiseAbs().sum() == 1);
        }
        // The smallest and largest boxes the specialised path takes agree with the general path.
        REQUIRE(detail::halfSpaceFastPathApplies(box, Settings{}));
        std::mt19937_64 random(9);
        Differences differences;
        compareMany(box, 2000, random, differences);
        CHECK(differences.fastPath == 2000);
    }
}

TEST_CASE("half-space: the specialised path equals the general one on random boxes, poses and planes") {
    std::mt19937_64 random(20261123);
    std::uniform_real_distribution<double> extent(0.01, 2.0), unit(0.0, 1.0);
    Differences differences;
    for (int shape = 0; shape < 200; ++shape) {
        Vec3 extents(extent(random), extent(random), extent(random));
        if (shape % 4 == 1) extents[shape % 3] *= 1e-3;  // thin plates
        if (shape % 4 == 2) extents = Vec3::Constant(0.5);
        if (shape % 12 == 3) extents *= 1e4 * unit(random);  // other scales
        const Polytope box = Polytope::box(extents);
        compareMany(box, 600, random, differences);
    }
    report("boxes", differences);
    for (long seen : differences.features) CHECK(seen >= 10000);
    CHECK(differences.fastPath >= 100000);
    CHECK(differences.nonEmpty >= differences.compared / 2);
}

TEST_CASE("half-space: the specialised path equals the general one on random hulls, poses and planes") {
    std::mt19937_64 random(1123);
    std::uniform_real_distribution<double> symmetric(-1.0, 1.0), unit(0.0, 1.0);
    Differences differences;
    // The 8-vertex hull of a cube (not a box: the general adjacency is searched).
    const Polytope cubeHull = Polytope::fromPoints(cubeCorners(0.5));
    REQUIRE_FALSE(cubeHull.isBox());
    compareMany(cubeHull, 30000, random, differences);
    // Random hulls of 6–32 points, some flattened or stretched.
    for (int shape = 0; shape < 100; ++shape) {
        const int count = 6 + shape % 27;
        const Vec3 stretch(1 + 2 * unit(random), 1, shape % 5 == 0 ? 0.05 : 1.0);
        std::vector<Vec3> points;
        for (int i = 0; i < count; ++i)
            points.push_back(Vec3(symmetric(random), symmetric(random), symmetric(random)).cwiseProduct(stretch));
        const Polytope hull = Polytope::fromPoints(points);
        compareMany(hull, 800, random, differences);
    }
    // Noisy cubes: each side split into near-coplanar faces (a face's cap of several faces).
    for (int shape = 0; shape < 20; ++shape) {
        std::vector<Vec3> points = cubeCorners(0.5);
        for (int side = 0; side < 6; ++side)
            for (int i = 0; i < 3; ++i) {
                Vec3 point(0.4 * symmetric(random), 0.4 * symmetric(random), 0.5 + 2e-3 * unit(random));
                if (side % 2) point.z() = -point.z();
                std::swap(point[2], point[side / 2]);
                points.push_back(point);
            }
        const Polytope hull = Polytope::fromPoints(points);
        compareMany(hull, 1000, random, differences);
    }
    report("hulls", differences);
    for (long seen : differences.features) CHECK(seen >= 10000);
    CHECK(differences.fastPath >= 100000);
    CHECK(differences.nonEmpty >= differences.compared / 2);

    // A hull above Settings::bruteForceSupportLimit is left to the general path, and still agrees.
    std::vector<Vec3> sphere;
    for (int i = 0; i < 200; ++i) sphere.push_back(randomRotation(random).col(0));
    const Polytope large = Polytope::fromPoints(sphere);
    REQUIRE(static_cast<int>(large.vertices().size()) > Settings{}.bruteForceSupportLimit);
    REQUIRE_FALSE(detail::halfSpaceFastPathApplies(large, Settings{}));
    Differences largeDifferences;
    compareMany(large, 2000, random, largeDifferences);
    CHECK(largeDifferences.fastPath == 0);
    // ... unless the limit is raised above its vertex count (up to the path's own bound).
    Settings raised;
    raised.bruteForceSupportLimit = 1000;
    CHECK(detail::halfSpaceFastPathApplies(large, raised) ==
          (static_cast<int>(large.vertices().size()) <= detail::kMaxSmallHullVertices));
}

TEST_CASE("half-space: settings outside the specialised path's range go to the general path") {
    const Polytope box = Polytope::box(Vec3(0.5, 0.4, 0.3));
    Settings wide;
    wide.angularTolerance = 1.0;  // a box's face cap could hold two faces
    CHECK_FALSE(detail::halfSpaceFastPathApplies(box, wide));
    Settings negative;
    negative.angularTolerance = -0.1;
    CHECK_FALSE(detail::halfSpaceFastPathApplies(box, negative));
    Settings nan;
    nan.angularTolerance = NAN;
    CHECK_FALSE(detail::halfSpaceFastPathApplies(box, nan));
    CHECK(detail::halfSpaceFastPathApplies(box, Settings{}));
    // Polytope::box accepts extents of 1e-80, where Newell's normals of its faces turn subnormal
    // in the normalisation and come out an ulp off the axes: the general path's.
    const Polytope tiny = Polytope::box(Vec3(1e-80, 3e-80, 2e-80));
    CHECK(tiny.faces()[0].normal != Vec3(-1, 0, 0));
    CHECK_FALSE(detail::halfSpaceFastPathApplies(tiny, Settings{}));
    const Polytope hull = Polytope::fromPoints(cubeCorners(0.5));
    Settings small;
    small.bruteForceSupportLimit = 4;  // hill climbing may pick another of equal supports
    CHECK_FALSE(detail::halfSpaceFastPathApplies(hull, small));
    // Those still agree, through collide()'s dispatch.
    std::mt19937_64 random(5);
    Differences differences;
    for (const Settings& settings : {wide, small}) {
        for (int i = 0; i < 200; ++i) {
            const Vec3 n = randomRotation(random).col(2);
            for (const Polytope* shape : {&box, &hull}) {
                const Pose pose = randomPose(*shape, n, 0.0, random);
                const double size = shape->radius();
                requireSame(generalManifold(*shape, pose, HalfSpace{n, 0.0}, settings),
                            collide(*shape, pose, HalfSpace{n, 0.0}, settings), size, differences);
            }
        }
    }
}

TEST_CASE("half-space: a face tilted exactly at the angular tolerance is a face, a hair beyond an edge") {
    const Settings settings;
    const detail::AngularTolerance tolerance(settings.angularTolerance);
    const Polytope box = Polytope::box(Vec3(0.5, 0.5, 0.5));
    const Polytope hull = Polytope::fromPoints(cubeCorners(0.5));
    const HalfSpace ground{Vec3::UnitZ(), 0.0};
    Differences differences;
    for (const Polytope* shape : {&box, &hull}) {
        // The contact direction in the box's frame is −(third row of the rotation): its z
        // component is the cosine itself, compared with >= in selectFeature.
        const Manifold atTolerance = collide(*shape, tiltedAbout(tolerance.cosine, 0.5), ground, settings);
        const Manifold beyond = collide(*shape, tiltedAbout(std::nextafter(tolerance.cosine, 0.0), 0.5), ground, settings);
        CHECK(atTolerance.featureA.type == FeatureType::Face);
        CHECK(beyond.featureA.type == FeatureType::Edge);
        for (double cosine : {tolerance.cosine, std::nextafter(tolerance.cosine, 0.0), std::nextafter(tolerance.cosine, 1.0)})
            for (double height : {0.5, 0.49, 0.5 * (cosine + std::sqrt(1 - cosine * cosine))}) {
                const Pose pose = tiltedAbout(cosine, height);
                requireSame(generalManifold(*shape, pose, ground, settings), collide(*shape, pose, ground, settings),
                            shape->radius(), differences);
            }
    }
    // An edge turned exactly the tolerance's sine off the plane is an edge, a hair beyond a vertex:
    // the contact direction's x component is the sine itself.
    for (double sine : {tolerance.sine, std::nextafter(tolerance.sine, 1.0)}) {
        const double rest = std::sqrt((1 - sine * sine) / 2);
        const Vec3 row3(sine, rest, rest);  // −(contact direction), the rotation's third row
        const Vec3 row1 = Vec3::UnitY().cross(row3).normalized();
        const Vec3 row2 = row3.cross(row1);
        Mat3 rotation;
        rotation.row(0) = row1, rotation.row(1) = row2, rotation.row(2) = row3;
        const Pose pose{rotation, Vec3(0, 0, 0.5)};
        const Manifold general = generalManifold(box, pose, ground, settings);
        const Manifold fast = collide(box, pose, ground, settings);
        CHECK(general.featureA.type == (sine == tolerance.sine ? FeatureType::Edge : FeatureType::Vertex));
        requireSame(general, fast, 0.5, differences);
        requireSame(generalManifold(hull, pose, ground, settings), collide(hull, pose, ground, settings), 0.5,
                    differences);
    }
}

TEST_CASE("half-space: exactly touching, a face flat on the plane at depth 0") {
    Settings settings;
    settings.maxContacts = 8;
    for (const Polytope& shape : {Polytope::box(Vec3(0.5, 0.5, 0.5)), Polytope::fromPoints(cubeCorners(0.5))}) {
        for (const HalfSpace& ground : {HalfSpace{Vec3::UnitZ(), 0.0}, HalfSpace{Vec3(0, 0, 4), 8.0}}) {
            const Pose pose{Mat3::Identity(), Vec3(0.25, -1, ground.offset / ground.normal.z() + 0.5)};
            const Manifold fast = collide(shape, pose, ground, settings);
            REQUIRE(fast.pointCount == 4);
            CHECK(fast.featureA.type == FeatureType::Face);
            for (int i = 0; i < 4; ++i) CHECK(fast.points[i].depth == 0);
            Differences differences;
            requireSame(generalManifold(shape, pose, ground, settings), fast, 0.5, differences);
            CHECK(differences.position == 0);
            // A hair above: apart, no contact; with a margin, four speculative ones.
            const Pose above{Mat3::Identity(), pose.position + Vec3(0, 0, 1e-6)};
            CHECK(collide(shape, above, ground, settings).empty());
            Settings margin = settings;
            margin.margin = 1e-5;
            const Manifold speculative = collide(shape, above, ground, margin);
            CHECK(speculative.pointCount == 4);
            requireSame(generalManifold(shape, above, ground, margin), speculative, 0.5, differences);
        }
    }
}

TEST_CASE("half-space: a box with one tiny extent") {
    const Polytope plate = Polytope::box(Vec3(1, 0.5, 1e-9));
    REQUIRE(detail::halfSpaceFastPathApplies(plate, Settings{}));
    const HalfSpace ground{Vec3::UnitZ(), 0.0};
    Differences differences;
    std::mt19937_64 random(77);
    std::uniform_real_distribution<double> small(-0.02, 0.02);
    for (const Mat3& base : {Mat3(Mat3::Identity()), rotationAbout(Vec3::UnitX(), M_PI / 2),
                             rotationAbout(Vec3::UnitY(), M_PI / 2), rotationAbout(Vec3(1, 1, 0), M_PI / 2)}) {
        for (int i = 0; i < 200; ++i) {
            const Mat3 rotation = rotationAbout(Vec3::UnitX(), small(random)) * rotationAbout(Vec3::UnitY(), small(random)) * base;
            double lowest = INFINITY;
            for (const Vec3& v : plate.vertices()) lowest = std::min(lowest, (rotation * v).z());
            for (double depth : {0.0, 1e-12, 1e-3, -1e-3}) {
                const Pose pose{rotation, Vec3(0, 0, -lowest - depth)};
                for (int maxContacts : {1, 2, 4, 8})
                    for (bool span : {false, true}) {
                        Settings settings;
                        settings.maxContacts = maxContacts;
                        settings.spanContactRegion = span;
                        compareOne(plate, pose, ground, settings, differences);
                    }
            }
        }
    }
    // Resting flat on its large face: the four corners.
    const Manifold flat = collide(plate, Pose{Mat3::Identity(), Vec3(0, 0, 1e-9 - 1e-4)}, ground);
    CHECK(flat.pointCount == 4);
    CHECK(flat.featureA.type == FeatureType::Face);
    CHECK(flat.featureA.index == 4);
    report("thin plate", differences);
}

TEST_CASE("half-space: the specialised path refuses bad input with the general path's errors") {
    const Polytope box = Polytope::box(Vec3(0.5, 0.5, 0.5));
    const Polytope hull = Polytope::fromPoints(cubeCorners(0.5));
    const Pose resting{Mat3::Identity(), Vec3(0, 0, 0.4)};
    Pose nanPose = resting, infPose = resting;
    nanPose.rotation(1, 2) = NAN;
    infPose.position.y() = INFINITY;
    struct Case {
        Pose pose;
        HalfSpace plane;
    };
    const Case cases[] = {
        {nanPose, HalfSpace{}},
        {infPose, HalfSpace{}},
        {resting, HalfSpace{Vec3::Zero(), 0}},
        {resting, HalfSpace{Vec3(NAN, 0, 1), 0}},
        {resting, HalfSpace{Vec3(INFINITY, 0, 1), 0}},
        {resting, HalfSpace{Vec3::UnitZ(), INFINITY}},
        {resting, HalfSpace{Vec3::UnitZ(), NAN}},
        {resting, HalfSpace{Vec3(0, 0, 1e-10), 1e300}},                                    // offset overflows
        {Pose{Mat3::Identity(), Vec3(0, 0, -1.7e308)}, HalfSpace{Vec3(0, 0, 1), 1.7e308}},  // contact overflows
        {Pose{Mat3::Identity(), Vec3(0, 0, 1.7e308)}, HalfSpace{Vec3(0, 0, 1), 1.7e308}},   // offset − n·p overflows
        {Pose{Mat3::Identity(), Vec3(1e308, 0, 0.4)}, HalfSpace{Vec3(1, 1, 1), 1e308}},
        {resting, HalfSpace{Vec3(1e-310, 0, 0), 0}},  // denormal normal: normalised through its largest component
        {resting, HalfSpace{Vec3(1e300, 1e300, 0), 0}},
    };
    int errors = 0;
    for (const Polytope* shape : {&box, &hull})
        for (const Case& c : cases) {
            INFO("position " << c.pose.position.transpose() << " plane " << c.plane.normal.transpose() << " | " << c.plane.offset);
            const std::string general = errorOf([&] { generalManifold(*shape, c.pose, c.plane, Settings{}); });
            const std::string fast = errorOf([&] { collide(*shape, c.pose, c.plane, Settings{}); });
            CHECK(fast == general);
            errors += !general.empty();
            if (general.empty()) {
                Differences differences;
                requireSame(generalManifold(*shape, c.pose, c.plane, Settings{}),
                            collide(*shape, c.pose, c.plane, Settings{}), shape->radius(), differences);
            }
        }
    CHECK(errors >= 2 * 9);
}

TEST_CASE("half-space: exact ties between a box's axes go where selectFeature sends them") {
    // Contact directions with equal components: the vertex exactly down, an edge at exactly 45°,
    // and two edges exactly equally near perpendicular (a wide tolerance), with every sign and
    // order. Ties must resolve as selectFeature resolves them (the lowest face or edge index).
    const Polytope box = Polytope::box(Vec3(0.5, 0.4, 0.3));
    const Polytope hull = Polytope::fromPoints(cubeCorners(0.5));
    const HalfSpace ground{Vec3::UnitZ(), 0.0};
    const double third = std::sqrt(1.0 / 3), half = std::sqrt(0.5), b = std::sqrt(1 - 2 * 0.55 * 0.55);
    const Vec3 directions[] = {Vec3(third, third, third), Vec3(0, half, half), Vec3(0.55, 0.55, b), Vec3(0, 0, 1)};
    Differences differences;
    int edges = 0;
    for (const Vec3& base : directions)
        for (int signs = 0; signs < 8; ++signs)
            for (int order = 0; order < 3; ++order) {
                Vec3 row3;
                for (int k = 0; k < 3; ++k) row3[(k + order) % 3] = (signs >> k) & 1 ? -base[k] : base[k];
                const Vec3 helper = std::abs(row3.x()) < 0.9 ? Vec3(Vec3::UnitX()) : Vec3(Vec3::UnitY());
                const Vec3 row1 = helper.cross(row3).normalized();
                Mat3 rotation;
                rotation.row(0) = row1, rotation.row(1) = row3.cross(row1), rotation.row(2) = row3;
                for (double tolerance : {0.05, 0.7})
                    for (const Polytope* shape : {&box, &hull}) {
                        Settings settings;
                        settings.angularTolerance = tolerance;
                        double lowest = INFINITY;
                        for (const Vec3& v : shape->vertices()) lowest = std::min(lowest, (rotation * v).z());
                        const Pose pose{rotation, Vec3(0, 0, -1e-3 - lowest)};
                        const Manifold general = generalManifold(*shape, pose, ground, settings);
                        edges += general.featureA.type == FeatureType::Edge;
                        requireSame(general, collide(*shape, pose, ground, settings), shape->radius(), differences);
                    }
            }
    CHECK(differences.nonEmpty == differences.compared);
    CHECK(edges > 0);
}
