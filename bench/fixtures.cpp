#include "fixtures.hpp"

#include <cmath>
#include <ctime>

namespace gdcbench {

const std::vector<int>& hullSizes() {
    static const std::vector<int> sizes{8, 16, 64, 256, 1024, 4096};
    return sizes;
}

Mat3 rotation(const Vec3& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Pose compose(const Pose& outer, const Pose& inner) {
    return {outer.rotation * inner.rotation, outer.rotation * inner.position + outer.position};
}

std::uint64_t Random::next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double Random::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

Vec3 Random::unitVector() {
    const double z = uniform(-1.0, 1.0);
    const double phi = uniform(0.0, 2.0 * M_PI);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Mat3 Random::rotation() {
    // Shoemake's uniform random quaternion.
    const double u1 = uniform(), u2 = uniform(), u3 = uniform();
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    const Eigen::Quaterniond q(b * std::cos(2 * M_PI * u3), a * std::sin(2 * M_PI * u2),
                               a * std::cos(2 * M_PI * u2), b * std::sin(2 * M_PI * u3));
    return q.normalized().toRotationMatrix();
}

double threadCpuSeconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

std::vector<Vec3> boxVertices(const Vec3& h) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    return corners;
}

std::vector<Vec3> fibonacciSphere(int count, double radius) {
    std::vector<Vec3> points;
    points.reserve(count);
    const double goldenAngle = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / count;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = goldenAngle * i;
        points.emplace_back(radius * r * std::cos(phi), radius * r * std::sin(phi), radius * z);
    }
    return points;
}

std::vector<Vec3> sweepHullPoints(int count) {
    if (count == 8) return boxVertices(Vec3::Constant(kSphereRadius / std::sqrt(3.0)));
    return fibonacciSphere(count, kSphereRadius);
}

Pose commonFrame() { return {rotation({1.0, 2.0, 3.0}, 0.7), Vec3(0.3, -0.2, 0.1)}; }

gdc::HalfSpace groundPlane() {
    const Pose frame = commonFrame();
    const Vec3 normal = frame.rotation * Vec3::UnitZ();
    return {normal, normal.dot(frame.position)};
}

std::vector<PairCase> cubePairCases() {
    const double h = kCubeHalfExtent, d = kRestingOverlap;
    const Pose frame = commonFrame();
    const Pose below{Mat3::Identity(), Vec3::Zero()};
    // Rotation that turns the cube's diagonal (1,1,1) to +z: one corner points straight down.
    const Mat3 cornerDown =
        Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitZ()).toRotationMatrix();
    const Mat3 quarterTurn = rotation(Vec3::UnitZ(), M_PI / 4);

    std::vector<PairCase> cases;
    auto add = [&](std::string name, const Pose& a, const Pose& b, int maxContacts, int expected) {
        cases.push_back({std::move(name), compose(frame, a), compose(frame, b), maxContacts, expected});
    };
    // Two equal squares at 45°: the contact region is a regular octagon.
    add("face_face_8", {quarterTurn, {0, 0, 2 * h - d}}, below, 8, 8);
    add("face_face_4", {quarterTurn, {0, 0, 2 * h - d}}, below, 4, 8);
    // A's lowest edge (along x) crosses B's highest edge (along y) at right angles.
    add("edge_edge", {rotation(Vec3::UnitX(), M_PI / 4), {0, 0, 2 * std::sqrt(2.0) * h - d}},
        {rotation(Vec3::UnitY(), M_PI / 4), Vec3::Zero()}, 8, 1);
    add("vertex_face", {cornerDown, {0.05, -0.03, h + std::sqrt(3.0) * h - d}}, below, 8, 1);
    add("separated", {quarterTurn, {0, 0, 2 * h + 0.1}}, below, 8, 0);
    add("deep_overlap", {rotation({1, 2, 3}, 0.35), {0.1, 0.05, 0.45}}, below, 8, -1);
    return cases;
}

std::vector<PlaneCase> cubePlaneCases() {
    const double h = kCubeHalfExtent, d = kRestingOverlap;
    const Pose frame = commonFrame();
    const gdc::HalfSpace plane = groundPlane();
    const Mat3 cornerDown =
        Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitZ()).toRotationMatrix();
    std::vector<PlaneCase> cases;
    auto add = [&](std::string name, const Pose& pose, int maxContacts, int expected) {
        cases.push_back({std::move(name), compose(frame, pose), plane, maxContacts, expected});
    };
    add("face", {rotation(Vec3::UnitZ(), 0.5), {0, 0, h - d}}, 8, 4);
    add("edge", {rotation(Vec3::UnitZ(), 0.2) * rotation(Vec3::UnitX(), M_PI / 4), {0, 0, std::sqrt(2.0) * h - d}}, 8, 2);
    add("vertex", {cornerDown, {0, 0, std::sqrt(3.0) * h - d}}, 8, 1);
    add("separated", {rotation(Vec3::UnitZ(), 0.5), {0, 0, h + 0.1}}, 8, 0);
    add("deep", {rotation({1, 2, 3}, 0.35), {0, 0, 0.1}}, 8, -1);
    return cases;
}

}  // namespace gdcbench
