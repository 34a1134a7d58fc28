// Prints the contact manifold of a few canonical pairs: a quick look at what gdcontact returns.
#include <gdcontact/gdcontact.hpp>

#include <cmath>
#include <cstdio>

namespace {

gdc::Pose pose(double x, double y, double z, double yaw = 0, double pitch = 0) {
    gdc::Pose p;
    p.rotation = (Eigen::AngleAxisd(yaw, gdc::Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, gdc::Vec3::UnitX()))
                     .toRotationMatrix();
    p.position = gdc::Vec3(x, y, z);
    return p;
}

const char* featureName(gdc::FeatureType type) {
    return type == gdc::FeatureType::Face ? "face" : type == gdc::FeatureType::Edge ? "edge" : "vertex";
}

void print(const char* title, const gdc::Manifold& m) {
    std::printf("%s: %d point(s)", title, m.pointCount);
    if (m.pointCount > 0)
        std::printf(", %s–%s, normal (%.6f %.6f %.6f)", featureName(m.featureA.type), featureName(m.featureB.type),
                    m.normal.x(), m.normal.y(), m.normal.z());
    std::printf("\n");
    for (int i = 0; i < m.pointCount; ++i)
        std::printf("    (% .6f % .6f % .6f)  depth % .6f\n", m.points[i].position.x(), m.points[i].position.y(),
                    m.points[i].position.z(), m.points[i].depth);
}

}  // namespace

int main() {
    const gdc::Polytope cube = gdc::Polytope::box(gdc::Vec3(0.5, 0.5, 0.5));
    print("cube resting on cube, 30° yaw, sunk 1 mm", gdc::collide(cube, pose(0, 0, 0), cube, pose(0.1, 0, 0.999, 0.5236)));
    print("cube on cube, tilted 10° (edge on face)", gdc::collide(cube, pose(0, 0, 0), cube, pose(0, 0, 1.07, 0, 0.1745)));
    print("separated cubes", gdc::collide(cube, pose(0, 0, 0), cube, pose(0, 0, 1.5)));
    print("cube on the ground plane, sunk 2 mm", gdc::collide(cube, pose(0, 0, 0.498), gdc::HalfSpace{gdc::Vec3::UnitZ(), 0}));
    std::vector<gdc::Vec3> points;
    for (int i = 0; i < 6; ++i) {
        double angle = i * M_PI / 3;
        points.emplace_back(0.5 * std::cos(angle), 0.5 * std::sin(angle), -0.25);
        points.emplace_back(0.5 * std::cos(angle), 0.5 * std::sin(angle), 0.25);
    }
    const gdc::Polytope prism = gdc::Polytope::fromPoints(points);
    print("hexagonal prism on cube, sunk 1 mm", gdc::collide(prism, pose(0, 0, 0.749), cube, pose(0, 0, 0)));
    return 0;
}
