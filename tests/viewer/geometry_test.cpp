// The viewer's scene-independent parts against exact answers: camera rays and projection, ray
// casts against convex meshes (analytic and brute-force oracle), reading geoms out of a real ODE
// space, and the drag spring in a real ODE world.
#include "camera.hpp"
#include "ode_precision.hpp"  // realTolerance: poses and lengths pass through dReal
#include "ode_session.hpp"
#include "convex_mesh.hpp"
#include "scene_shapes.hpp"
#include "spring_drag.hpp"

#include <catch2/catch.hpp>
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace gdc;
using namespace gdc::viewer;

namespace {

// ODE must be initialised once per process before any world or geom.
void needOde() { static gdc::testing::OdeSession session; }

Mat3 rotation(double angle, const Vec3& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

void toOde(const Mat3& r, dMatrix3 out) {
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) out[4 * i + j] = r(i, j);
        out[4 * i + 3] = 0;
    }
}

// Oracle for the ray cast: the entry point, if any, is the ray origin or one of the points where
// the ray crosses a face plane; take the nearest candidate that lies in every half-space.
std::optional<double> entryByCandidates(const Ray& ray, const ConvexMesh& mesh) {
    auto inside = [&](const Vec3& p) {
        for (const auto& f : mesh.faces)
            if (f.normal.dot(p) > f.offset + 1e-9) return false;
        return true;
    };
    std::optional<double> best;
    if (inside(ray.origin)) return 0.0;
    for (const auto& f : mesh.faces) {
        const double approach = f.normal.dot(ray.direction);
        if (approach == 0.0) continue;
        const double t = (f.offset - f.normal.dot(ray.origin)) / approach;
        if (t >= 0.0 && inside(ray.at(t)) && (!best || t < *best)) best = t;
    }
    return best;
}

}  // namespace

TEST_CASE("camera ray through the projection of a point passes through that point") {
    OrbitCamera camera(Vec3::UnitZ());
    camera.frame(Vec3(-1, -2, 0), Vec3(3, 1, 2));
    camera.orbit(0.3, -0.2);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
    for (int i = 0; i < 200; ++i) {
        const Vec3 point(coordinate(random), coordinate(random), coordinate(random));
        const Eigen::Vector2d pixel = camera.project(point, 800, 600);
        const Ray ray = camera.rayThroughPixel(pixel.x(), pixel.y(), 800, 600);
        REQUIRE(ray.direction.norm() == Approx(1.0));
        const double along = (point - ray.origin).dot(ray.direction);
        REQUIRE(along > 0.0);
        REQUIRE((ray.at(along) - point).norm() < 1e-9 * (1.0 + along));
    }
}

TEST_CASE("camera looks at its target from above and frames the box it is given") {
    OrbitCamera camera(Vec3::UnitZ());
    camera.frame(Vec3(-1, -1, 0), Vec3(1, 1, 2));
    // The target is the centre of the view.
    const Eigen::Vector2d centre = camera.project(camera.target(), 640, 480);
    CHECK(centre.x() == Approx(320.0));
    CHECK(centre.y() == Approx(240.0));
    CHECK(camera.eye().z() > camera.target().z());  // default pitch looks down
    // Every corner of the framed box is inside the image.
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 2 : 0);
        const Eigen::Vector2d p = camera.project(corner, 640, 480);
        CHECK(p.x() > 0.0);
        CHECK(p.x() < 640.0);
        CHECK(p.y() > 0.0);
        CHECK(p.y() < 480.0);
    }
    // Pitch is clamped short of the pole: the view never flips over.
    camera.orbit(0.0, 10.0);
    CHECK((camera.eye() - camera.target()).normalized().z() < 1.0);
    CHECK(camera.view().allFinite());
}

TEST_CASE("box mesh has outward face normals and twelve edges") {
    const ConvexMesh box = ConvexMesh::box(Vec3(1, 2, 3));
    REQUIRE(box.faces.size() == 6);
    REQUIRE(box.edges.size() == 12);
    for (const auto& face : box.faces) {
        Vec3 centre = Vec3::Zero();
        for (int i : face.loop) centre += box.vertices[i];
        centre /= double(face.loop.size());
        CHECK(face.normal.dot(centre) > 0.0);  // centre of the box is the origin
        CHECK(face.offset == Approx(face.normal.cwiseAbs().dot(Vec3(1, 2, 3))));
    }
    CHECK_THROWS_AS(ConvexMesh::box(Vec3(1, 0, 1)), InvalidInput);
    CHECK_THROWS_AS(ConvexMesh::box(Vec3(1, NAN, 1)), InvalidInput);
}

TEST_CASE("ray cast against a box: analytic entry distances") {
    const ConvexMesh box = ConvexMesh::box(Vec3(1, 1, 1));
    // Straight down onto the top face from z = 5.
    auto t = intersect(Ray{Vec3(0.3, -0.2, 5), Vec3(0, 0, -1)}, box);
    REQUIRE(t);
    CHECK(*t == Approx(4.0));
    // Diagonal through the corner region: enters through x = -1 at t = 2·√2 ... along (1,1,0)/√2.
    t = intersect(Ray{Vec3(-3, -2.5, 0), Vec3(1, 1, 0).normalized()}, box);
    REQUIRE(t);
    CHECK(*t == Approx(2.0 * std::sqrt(2.0)));
    // Misses: passes beside, points away, parallel outside a face.
    CHECK_FALSE(intersect(Ray{Vec3(0, 1.5, 5), Vec3(0, 0, -1)}, box));
    CHECK_FALSE(intersect(Ray{Vec3(0, 0, 5), Vec3(0, 0, 1)}, box));
    CHECK_FALSE(intersect(Ray{Vec3(-5, 1.0 + 1e-9, 0), Vec3(1, 0, 0)}, box));
    // Origin inside: distance 0.
    t = intersect(Ray{Vec3(0.5, 0.5, 0.5), Vec3(1, 0, 0)}, box);
    REQUIRE(t);
    CHECK(*t == 0.0);
    // Placed box: rotated 90° about z and moved; a ray down the world z axis above it.
    const Pose pose{rotation(M_PI / 2, Vec3::UnitZ()), Vec3(10, 0, 1)};
    const ConvexMesh plank = ConvexMesh::box(Vec3(2, 0.5, 0.25));  // long along local x → world y
    CHECK(intersect(Ray{Vec3(10, 1.8, 5), Vec3(0, 0, -1)}, plank, pose));
    CHECK_FALSE(intersect(Ray{Vec3(11.8, 0, 5), Vec3(0, 0, -1)}, plank, pose));
    t = intersect(Ray{Vec3(10, 0, 5), Vec3(0, 0, -1)}, plank, pose);
    REQUIRE(t);
    CHECK(*t == Approx(5.0 - 1.25));
}

TEST_CASE("ray cast against random hulls agrees with the brute-force oracle") {
    std::mt19937 random(2010);
    std::normal_distribution<double> gaussian;
    int hits = 0, misses = 0;
    for (int shape = 0; shape < 20; ++shape) {
        std::vector<Vec3> points;
        for (int i = 0; i < 30; ++i) points.emplace_back(gaussian(random), 0.5 * gaussian(random), 2.0 * gaussian(random));
        const ConvexMesh mesh = ConvexMesh::fromPolytope(Polytope::fromPoints(points));
        for (int r = 0; r < 200; ++r) {
            const Vec3 origin(3 * gaussian(random), 3 * gaussian(random), 3 * gaussian(random));
            const Vec3 aim(gaussian(random), gaussian(random), gaussian(random));
            const Ray ray{origin, (aim - origin).normalized()};
            const auto fast = intersect(ray, mesh);
            const auto oracle = entryByCandidates(ray, mesh);
            REQUIRE(fast.has_value() == oracle.has_value());
            if (fast) {
                CHECK(*fast == Approx(*oracle).margin(1e-9));
                ++hits;
            } else {
                ++misses;
            }
        }
    }
    // Both outcomes were exercised.
    CHECK(hits > 100);
    CHECK(misses > 100);
}

TEST_CASE("half-space ray cast hits the plane only from outside") {
    const Vec3 up = Vec3::UnitZ();
    auto t = intersectHalfSpace(Ray{Vec3(1, 2, 3), Vec3(0, 0.6, -0.8)}, up, 0.5);
    REQUIRE(t);
    CHECK(*t == Approx(2.5 / 0.8));
    CHECK_FALSE(intersectHalfSpace(Ray{Vec3(1, 2, 3), Vec3(0, 0.6, 0.8)}, up, 0.5));
    CHECK_FALSE(intersectHalfSpace(Ray{Vec3(1, 2, 0), Vec3(0, 0, -1)}, up, 0.5));
}

TEST_CASE("scene shapes read boxes, offsets, transforms, nested spaces and planes from ODE") {
    needOde();
    dWorldID world = dWorldCreate();
    dSpaceID space = dSimpleSpaceCreate(nullptr);

    // A body with a box geom at an offset.
    const Mat3 bodyRotation = rotation(0.7, Vec3(1, 2, 3));
    const Vec3 bodyPosition(1, -2, 3);
    dBodyID body = dBodyCreate(world);
    dBodySetPosition(body, bodyPosition.x(), bodyPosition.y(), bodyPosition.z());
    dMatrix3 r;
    toOde(bodyRotation, r);
    dBodySetRotation(body, r);
    dGeomID offsetBox = dCreateBox(space, 0.2, 0.4, 0.6);
    dGeomSetBody(offsetBox, body);
    const Mat3 offsetRotation = rotation(-0.4, Vec3(0, 1, 1));
    const Vec3 offsetPosition(0.5, 0, -0.25);
    dGeomSetOffsetPosition(offsetBox, offsetPosition.x(), offsetPosition.y(), offsetPosition.z());
    toOde(offsetRotation, r);
    dGeomSetOffsetRotation(offsetBox, r);

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
    // A box wrapped in a dGeomTransform on a second body.
    dBodyID carrier = dBodyCreate(world);
    dBodySetPosition(carrier, -3, 0, 1);
    dGeomID transform = dCreateGeomTransform(space);
    dGeomID inner = dCreateBox(nullptr, 1, 1, 1);
    dGeomTransformSetGeom(transform, inner);
    dGeomTransformSetCleanup(transform, 1);
    dGeomSetPosition(inner, 0, 0, 2);
    toOde(rotation(M_PI / 4, Vec3::UnitZ()), r);
    dGeomSetRotation(inner, r);
    dGeomSetBody(transform, carrier);
#pragma GCC diagnostic pop

    // A static box inside a nested space, a plane, and a sphere the viewer does not draw.
    dSpaceID nested = dSimpleSpaceCreate(space);
    dGeomID staticBox = dCreateBox(nested, 2, 2, 2);
    dGeomSetPosition(staticBox, 0, 5, 1);
    dCreatePlane(space, 0, 0, 2, 1);  // z = 0.5 written unnormalised
    dCreateSphere(space, 0.5);

    SceneShapes shapes;
    shapes.update(space);
    CHECK(shapes.skipped() == 1);
    REQUIRE(shapes.shapes().size() == 4);

    int found = 0;
    for (const auto& shape : shapes.shapes()) {
        if (shape.geom == offsetBox) {
            ++found;
            CHECK(shape.body == body);
            const Mat3 expectedRotation = bodyRotation * offsetRotation;
            const Vec3 expectedPosition = bodyRotation * offsetPosition + bodyPosition;
            CHECK((shape.pose.rotation - expectedRotation).norm() < gdc::ode::test::realTolerance(1e-12));
            CHECK((shape.pose.position - expectedPosition).norm() < gdc::ode::test::realTolerance(1e-12));
            // The mesh is the box of the geom's lengths.
            Vec3 extent = Vec3::Zero();
            for (const auto& v : shape.mesh->vertices) extent = extent.cwiseMax(v.cwiseAbs());
            CHECK((extent - Vec3(0.1, 0.2, 0.3)).norm() < gdc::ode::test::realTolerance(1e-15));
        } else if (shape.geom == inner) {
            ++found;
            CHECK(shape.placed == transform);
            CHECK(shape.body == carrier);
            CHECK((shape.pose.position - Vec3(-3, 0, 3)).norm() < 1e-12);
            CHECK((shape.pose.rotation - rotation(M_PI / 4, Vec3::UnitZ())).norm() < gdc::ode::test::realTolerance(1e-12));
        } else if (shape.geom == staticBox) {
            ++found;
            CHECK(shape.body == nullptr);
            CHECK((shape.pose.position - Vec3(0, 5, 1)).norm() == 0.0);
        } else if (shape.isPlane()) {
            ++found;
            CHECK((shape.planeNormal - Vec3::UnitZ()).norm() < 1e-15);
            CHECK(shape.planeOffset == Approx(0.5));
        }
    }
    CHECK(found == 4);

    // Picking: straight down onto the transformed box's top face (z = 3.5), then beside all
    // boxes onto the plane (z = 0.5); the nearest shape wins.
    auto hit = shapes.pick(Ray{Vec3(-3, 0, 10), Vec3(0, 0, -1)});
    REQUIRE(hit);
    CHECK(shapes.shapes()[hit->shape].geom == inner);
    CHECK(hit->point.z() == Approx(3.5));
    hit = shapes.pick(Ray{Vec3(-6, -6, 10), Vec3(0, 0, -1)});
    REQUIRE(hit);
    CHECK(shapes.shapes()[hit->shape].isPlane());
    CHECK(hit->point.z() == Approx(0.5));

    // A resized box is re-read, not served from the cache.
    dGeomBoxSetLengths(staticBox, 4, 4, 4);
    shapes.update(space);
    hit = shapes.pick(Ray{Vec3(0, 5, 10), Vec3(0, 0, -1)});
    REQUIRE(hit);
    CHECK(hit->point.z() == Approx(3.0));

    dSpaceDestroy(space);
    dWorldDestroy(world);
}

TEST_CASE("a dConvex geom is drawn from the polytope the lookup gives") {
    needOde();
    dSpaceID space = dSimpleSpaceCreate(nullptr);
    // dCreateConvex's layout for a unit cube (planes, points, polygons); ODE keeps the pointers.
    static const dReal planes[] = {1, 0, 0, 0.5, -1, 0, 0, 0.5, 0, 1, 0, 0.5, 0, -1, 0, 0.5, 0, 0, 1, 0.5, 0, 0, -1, 0.5};
    static const dReal points[] = {-0.5, -0.5, -0.5, 0.5, -0.5, -0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5,
                                   -0.5, -0.5, 0.5,  0.5, -0.5, 0.5,  -0.5, 0.5, 0.5,  0.5, 0.5, 0.5};
    static const unsigned polygons[] = {4, 1, 3, 7, 5, 4, 0, 4, 6, 2, 4, 2, 6, 7, 3, 4, 0, 1, 5, 4, 4, 4, 5, 7, 6, 4, 0, 2, 3, 1};
    dGeomID convex = dCreateConvex(space, planes, 6, points, 8, polygons);
    dGeomSetPosition(convex, 0, 0, 1);
    const auto cube = std::make_shared<const Polytope>(Polytope::box(Vec3(0.5, 0.5, 0.5)));

    SceneShapes shapes;
    shapes.update(space);
    CHECK(shapes.shapes().empty());  // nobody said what this convex is
    CHECK(shapes.skipped() == 1);

    shapes.setPolytopeLookup([&](dGeomID geom) { return geom == convex ? cube : nullptr; });
    shapes.update(space);
    REQUIRE(shapes.shapes().size() == 1);
    CHECK(shapes.shapes()[0].mesh->vertices.size() == 8);
    const auto hit = shapes.pick(Ray{Vec3(0.2, 0.1, 5), Vec3(0, 0, -1)});
    REQUIRE(hit);
    CHECK(hit->point.z() == Approx(1.5));
    dSpaceDestroy(space);
}

TEST_CASE("cylinder and capsule meshes are closed, convex, outward, with their vertices on the surface") {
    const double radius = 0.3, length = 0.8;
    const ConvexMesh cylinder = ConvexMesh::cylinder(radius, length, 16);
    const ConvexMesh capsule = ConvexMesh::capsule(radius, length, 16);
    const ConvexMesh ball = ConvexMesh::capsule(radius, 0.0, 16);  // a zero-length capsule: a sphere
    CHECK(cylinder.faces.size() == 16 + 2);  // the band and two 16-gon caps
    for (const ConvexMesh* mesh : {&cylinder, &capsule, &ball}) {
        // Euler: V − E + F = 2 for a closed surface; every vertex inside every face's half-space.
        CHECK(int(mesh->vertices.size()) - int(mesh->edges.size()) + int(mesh->faces.size()) == 2);
        for (const auto& face : mesh->faces)
            for (const Vec3& v : mesh->vertices) CHECK(face.normal.dot(v) <= face.offset + 1e-12);
    }
    for (const Vec3& v : cylinder.vertices) {
        CHECK(v.head<2>().norm() == Approx(radius));
        CHECK(std::abs(v.z()) == Approx(0.5 * length));
    }
    for (const Vec3& v : capsule.vertices) {  // `radius` from the nearest point of its segment
        const Vec3 axisPoint(0, 0, std::clamp(v.z(), -0.5 * length, 0.5 * length));
        CHECK((v - axisPoint).norm() == Approx(radius));
    }
    // Straight down the axis: the cap at h/2, the pole at L/2 + r.
    const Ray down{Vec3(0, 0, 5), Vec3(0, 0, -1)};
    CHECK(*intersect(down, cylinder) == Approx(5.0 - 0.5 * length));
    CHECK(*intersect(down, capsule) == Approx(5.0 - 0.5 * length - radius));
    CHECK_THROWS_AS(ConvexMesh::cylinder(0.0, 1.0), InvalidInput);
    CHECK_THROWS_AS(ConvexMesh::capsule(0.3, -1.0), InvalidInput);
}

TEST_CASE("scene shapes draw dCylinder and dCapsule geoms and re-read them when resized") {
    needOde();
    dSpaceID space = dSimpleSpaceCreate(nullptr);
    dGeomID cylinder = dCreateCylinder(space, 0.5, 2.0);
    dGeomSetPosition(cylinder, 0, 0, 1);
    dGeomID capsule = dCreateCapsule(space, 0.25, 1.0);
    dGeomSetPosition(capsule, 3, 0, 1);
    dMatrix3 r;
    toOde(rotation(M_PI / 2, Vec3::UnitX()), r);  // lying: its axis along y
    dGeomSetRotation(capsule, r);
    dCreateSphere(space, 0.5);  // still not drawn

    SceneShapes shapes;
    shapes.update(space);
    CHECK(shapes.skipped() == 1);
    REQUIRE(shapes.shapes().size() == 2);
    auto hit = shapes.pick(Ray{Vec3(0, 0, 10), Vec3(0, 0, -1)});
    REQUIRE(hit);
    CHECK(shapes.shapes()[hit->shape].geom == cylinder);
    CHECK(hit->point.z() == Approx(2.0));  // the top cap
    hit = shapes.pick(Ray{Vec3(3, 0.3, 10), Vec3(0, 0, -1)});  // onto the lying capsule's side
    REQUIRE(hit);
    CHECK(shapes.shapes()[hit->shape].geom == capsule);
    CHECK(hit->point.z() == Approx(1.25).margin(0.25 * (1.0 - std::cos(M_PI / 24))));  // within the sagitta

    dGeomCylinderSetParams(cylinder, 0.5, 4.0);
    shapes.update(space);
    hit = shapes.pick(Ray{Vec3(0, 0, 10), Vec3(0, 0, -1)});
    REQUIRE(hit);
    CHECK(hit->point.z() == Approx(3.0));
    dSpaceDestroy(space);
}

TEST_CASE("the drag spring holds a grabbed body where gravity and spring balance") {
    needOde();
    dWorldID world = dWorldCreate();
    const double gravity = 9.81;
    dWorldSetGravity(world, 0, 0, -gravity);
    dBodyID body = dBodyCreate(world);
    dMass mass;
    dMassSetBoxTotal(&mass, 3.0, 0.4, 0.2, 0.1);
    dBodySetMass(body, &mass);
    dBodySetPosition(body, 0, 0, 1);

    SpringDrag drag;
    // Grab at the centre of mass (no torque), 10 m along a ray from the camera.
    const Vec3 eye(0, -10, 1);
    drag.begin(body, Vec3(0, 0, 1), 10.0);
    REQUIRE(drag.active());
    // Move the cursor so the target is 0.5 m to the right and 0.3 m up.
    const Vec3 target(0.5, 0, 1.3);
    drag.moveTo(Ray{eye, (target - eye).normalized()});
    CHECK((drag.target() - (eye + 10.0 * (target - eye).normalized())).norm() < 1e-12);
    const Vec3 aim = drag.target();
    for (int step = 0; step < 500; ++step) {  // 5 s: many time constants of the spring
        drag.apply();
        dWorldStep(world, 0.01);
    }
    // Equilibrium of a linear spring against gravity: the anchor hangs g/k below the target.
    const Vec3 anchor = drag.anchorWorld();
    CHECK(anchor.x() == Approx(aim.x()).margin(1e-4));
    CHECK(anchor.y() == Approx(aim.y()).margin(1e-4));
    CHECK(aim.z() - anchor.z() == Approx(gravity / drag.stiffnessPerMass).margin(1e-4));
    const dReal* velocity = dBodyGetLinearVel(body);
    CHECK(Vec3(velocity[0], velocity[1], velocity[2]).norm() < 1e-3);

    drag.end();
    CHECK_FALSE(drag.active());
    dWorldDestroy(world);
}
