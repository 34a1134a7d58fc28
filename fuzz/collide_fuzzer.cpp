// libFuzzer target over hull construction and collide: the bytes choose point clouds or explicit
// face lists (any garbage: NaN, duplicates, coplanar sets, bad windings), poses and settings.
// Construction may refuse the input (gdc::InvalidInput) — anything else it throws, and any
// contact that breaks an invariant, is a finding (the sanitizers catch memory errors and UB).
#include <gdcontact/gdcontact.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

namespace {

// Reads the fuzzer's bytes as a stream of small numbers; past the end everything is zero.
class Bytes {
public:
    Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    std::uint8_t byte() { return position_ < size_ ? data_[position_++] : 0; }
    double raw() {  // any double, NaN and infinities included
        std::uint64_t bits = 0;
        for (int i = 0; i < 8; ++i) bits = bits << 8 | byte();
        double value;
        std::memcpy(&value, &bits, sizeof value);
        return value;
    }
    // Mostly well-formed coordinates in [−range, range] on a coarse grid (so coplanar and
    // coincident points are common); now and then a raw double.
    double coordinate(double range) {
        const std::uint8_t kind = byte();
        if (kind == 255) return raw();
        const int grid = static_cast<std::int16_t>(byte() << 8 | byte());
        return range * grid / 32768.0 * (kind % 4 == 0 ? 1e-3 : 1.0);
    }
    bool empty() const { return position_ >= size_; }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t position_ = 0;
};

std::optional<gdc::Polytope> makePolytope(Bytes& in, const gdc::Settings& settings) {
    try {
        switch (in.byte() % 3) {
            case 0:
                return gdc::Polytope::box(gdc::Vec3(in.coordinate(2), in.coordinate(2), in.coordinate(2)));
            case 1: {
                std::vector<gdc::Vec3> points(in.byte() % 40);
                for (gdc::Vec3& p : points) p = gdc::Vec3(in.coordinate(1), in.coordinate(1), in.coordinate(1));
                return gdc::Polytope::fromPoints(points, settings);
            }
            default: {
                std::vector<gdc::Vec3> vertices(in.byte() % 12);
                for (gdc::Vec3& p : vertices) p = gdc::Vec3(in.coordinate(1), in.coordinate(1), in.coordinate(1));
                std::vector<std::vector<int>> faces(in.byte() % 10);
                for (auto& face : faces) {
                    face.resize(in.byte() % 6);
                    for (int& index : face) index = static_cast<int>(in.byte() % 14) - 1;  // some out of range
                }
                return gdc::Polytope::fromFaces(vertices, faces, settings);
            }
        }
    } catch (const gdc::InvalidInput&) {
        return std::nullopt;  // refused with a message: the intended outcome for bad input
    }
}

gdc::Pose makePose(Bytes& in) {
    const bool rawPose = in.byte() == 255;
    Eigen::Quaterniond q(in.coordinate(1), in.coordinate(1), in.coordinate(1), in.coordinate(1));
    if (!(q.norm() > 1e-6) || !q.coeffs().allFinite()) q = Eigen::Quaterniond::Identity();
    gdc::Pose pose{q.normalized().toRotationMatrix(), gdc::Vec3(in.coordinate(2), in.coordinate(2), in.coordinate(2))};
    if (rawPose) pose.position.x() = in.raw();
    const std::uint8_t far = in.byte();
    if (far >= 250) pose.position += gdc::Vec3::Constant(std::pow(10.0, far - 244));  // 1e6 … 1e11
    return pose;
}

void check(bool condition) {
    if (!condition) std::abort();  // an invariant broke: libFuzzer saves the input
}

void checkManifold(const gdc::Manifold& m, const gdc::Settings& settings, double size) {
    check(m.pointCount >= 0 && m.pointCount <= std::max(1, settings.maxContacts));
    if (m.empty()) return;
    check(m.normal.allFinite() && std::abs(m.normal.norm() - 1) < 1e-9);
    for (int i = 0; i < m.pointCount; ++i) {
        check(m.points[i].position.allFinite() && std::isfinite(m.points[i].depth));
        check(m.points[i].depth >= -settings.margin - 1e-6 * size);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes in(data, size);
    gdc::Settings settings;
    settings.maxContacts = 1 + in.byte() % 16;
    settings.angularTolerance = 0.2 * (in.byte() / 255.0);
    settings.margin = in.byte() % 4 == 0 ? 0.01 : 0.0;
    settings.bruteForceSupportLimit = in.byte() % 2 ? 32 : 0;  // both support searches
    std::optional<gdc::Polytope> a = makePolytope(in, settings);
    std::optional<gdc::Polytope> b = makePolytope(in, settings);
    const gdc::Pose poseA = makePose(in), poseB = makePose(in);
    try {
        if (a && b) {
            const double size = a->radius() + b->radius();
            const gdc::Manifold ab = gdc::collide(*a, poseA, *b, poseB, settings);
            const gdc::Manifold ba = gdc::collide(*b, poseB, *a, poseA, settings);
            checkManifold(ab, settings, size);
            checkManifold(ba, settings, size);
            check(ab.empty() == ba.empty() || size > 1e6 * std::max(1.0, poseA.position.norm()));
        }
        if (a) {
            const gdc::Vec3 normal(in.coordinate(1), in.coordinate(1), in.coordinate(1));
            const gdc::Manifold ground = gdc::collide(*a, poseA, gdc::HalfSpace{normal, in.coordinate(2)}, settings);
            checkManifold(ground, settings, a->radius());
        }
    } catch (const gdc::InvalidInput&) {
        // non-finite poses and zero half-space normals are refused with a message
    }
    return 0;
}
