#include "solver_seeds.hpp"

#include <scene.hpp>  // samples/scenes: worlds of convex bodies (dBox or dConvex), mass properties

#include <gdcontact/ode.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace gdc::solver_seeds {
namespace {

using gdc::Mat3;
using gdc::Pose;
using gdc::Vec3;
using gdc::scenes::PlacedPart;
using gdc::scenes::Random;
using Clock = std::chrono::steady_clock;

// ---- ODE's messages, counted per process ----------------------------------------------------------
int gMessages = 0;   // this process's count; workers are processes, each runs one seed at a time
int gLcpErrors = 0;

void countMessage(int, const char* format, va_list arguments) {
    char text[512];
    std::vsnprintf(text, sizeof text, format, arguments);
    ++gMessages;
    if (std::strstr(text, "LCP internal error")) ++gLcpErrors;
}

// ---- settings by name ---------------------------------------------------------------------------------
double parseDouble(const std::string& name, const std::string& value) {
    std::size_t used = 0;
    double result = 0;
    try {
        result = std::stod(value, &used);
    } catch (...) {
        used = 0;
    }
    if (used != value.size() || value.empty())
        throw std::invalid_argument("setting " + name + ": '" + value + "' is not a number");
    return result;
}

int parseInt(const std::string& name, const std::string& value) {
    const double number = parseDouble(name, value);
    if (number != std::floor(number) || std::abs(number) > 1e9)
        throw std::invalid_argument("setting " + name + ": '" + value + "' is not an integer");
    return static_cast<int>(number);
}

bool parseBool(const std::string& name, const std::string& value) {
    if (value == "true" || value == "1" || value == "on") return true;
    if (value == "false" || value == "0" || value == "off") return false;
    throw std::invalid_argument("setting " + name + ": '" + value + "' is not true/false/1/0/on/off");
}

/// One line per field of gdc::Settings: its name and how a value is stored into it.
struct SettingField {
    const char* name;
    std::function<void(gdc::Settings&, const std::string&)> set;
};

const std::vector<SettingField>& settingFields() {
    static const std::vector<SettingField> fields = {
        {"rayCastTolerance", [](gdc::Settings& s, const std::string& v) { s.rayCastTolerance = parseDouble("rayCastTolerance", v); }},
        {"maxRayCastIterations", [](gdc::Settings& s, const std::string& v) { s.maxRayCastIterations = parseInt("maxRayCastIterations", v); }},
        {"angularTolerance", [](gdc::Settings& s, const std::string& v) { s.angularTolerance = parseDouble("angularTolerance", v); }},
        {"margin", [](gdc::Settings& s, const std::string& v) { s.margin = parseDouble("margin", v); }},
        {"spanContactRegion", [](gdc::Settings& s, const std::string& v) { s.spanContactRegion = parseBool("spanContactRegion", v); }},
        {"maxContacts", [](gdc::Settings& s, const std::string& v) { s.maxContacts = parseInt("maxContacts", v); }},
        {"bruteForceSupportLimit", [](gdc::Settings& s, const std::string& v) { s.bruteForceSupportLimit = parseInt("bruteForceSupportLimit", v); }},
        {"coplanarTolerance", [](gdc::Settings& s, const std::string& v) { s.coplanarTolerance = parseDouble("coplanarTolerance", v); }},
        {"normalMethod", [](gdc::Settings& s, const std::string& v) {
             if (v == "GrowthDistance" || v == "0") s.normalMethod = gdc::NormalMethod::GrowthDistance;
             else if (v == "SeparatingAxis" || v == "1") s.normalMethod = gdc::NormalMethod::SeparatingAxis;
             else throw std::invalid_argument("setting normalMethod: '" + v + "' is not GrowthDistance or SeparatingAxis");
         }},
        {"manifoldReuseDistance", [](gdc::Settings& s, const std::string& v) { s.manifoldReuseDistance = parseDouble("manifoldReuseDistance", v); }},
        // The contact set the solver gets (its budget is maxContacts).
        {"contactOrder", [](gdc::Settings& s, const std::string& v) {
             if (v == "DeepestLast" || v == "0") s.contactOrder = gdc::ContactOrder::DeepestLast;
             else if (v == "DeepestFirst" || v == "1") s.contactOrder = gdc::ContactOrder::DeepestFirst;
             else if (v == "DeepestFirstWhenLoaded" || v == "2") s.contactOrder = gdc::ContactOrder::DeepestFirstWhenLoaded;
             else throw std::invalid_argument("setting contactOrder: '" + v +
                                              "' is not DeepestLast, DeepestFirst or DeepestFirstWhenLoaded");
         }},
        {"loadedDepthFraction", [](gdc::Settings& s, const std::string& v) { s.loadedDepthFraction = parseDouble("loadedDepthFraction", v); }},
        {"reductionHysteresis", [](gdc::Settings& s, const std::string& v) { s.reductionHysteresis = parseDouble("reductionHysteresis", v); }},
        // New fields of gdc::Settings: one line each here.
        // Per-body-pair contact budget
        {"maxBodyPairContacts", [](gdc::Settings& s, const std::string& v) { s.maxBodyPairContacts = parseInt("maxBodyPairContacts", v); }},
        {"bodyPairNormalTolerance", [](gdc::Settings& s, const std::string& v) { s.bodyPairNormalTolerance = parseDouble("bodyPairNormalTolerance", v); }},
    };
    return fields;
}

// ---- scenes ---------------------------------------------------------------------------------------
/// A world of the scene library built by a function of this file; also records per body the drop
/// its start gap allows (a body starts that far above where it rests).
class BenchScene final : public gdc::scenes::Scene {
public:
    using Builder = std::function<void(BenchScene&)>;
    BenchScene(const std::string& name, bool convexBoxes, Builder builder)
        : Scene(name, options(convexBoxes), solver()), builder_(std::move(builder)) {}

    gdc::scenes::Outcome outcome() const override { return {}; }
    double duration() const override { return 0.0; }

    void box(const Vec3& half, double density, const Pose& pose, double allowedDrop = 0.0) {
        addBox("box", half, density, pose, {0.7f, 0.7f, 0.7f});
        allowedDrop_.push_back(allowedDrop);
    }
    void body(const std::vector<PlacedPart>& parts, double density, const Pose& pose, double allowedDrop = 0.0) {
        addBody("body", parts, density, pose, {0.7f, 0.7f, 0.7f});
        allowedDrop_.push_back(allowedDrop);
    }
    void ground() { addGroundPlane(); }
    const std::vector<double>& allowedDrop() const { return allowedDrop_; }

private:
    static gdc::scenes::SceneOptions options(bool convexBoxes) {
        gdc::scenes::SceneOptions o;
        o.method = gdc::scenes::Method::Gdcontact;  // unused: this file collides itself
        o.convexBoxes = convexBoxes;
        o.scripted = false;
        return o;
    }
    static gdc::scenes::SolverSettings solver() {
        gdc::scenes::SolverSettings s;
        s.dt = SolverConstants::dt;
        s.erp = SolverConstants::erp;
        s.cfm = SolverConstants::cfm;
        s.mu = SolverConstants::mu;
        return s;
    }
    void build() override {
        allowedDrop_.clear();
        builder_(*this);
    }
    Builder builder_;
    std::vector<double> allowedDrop_;
};

Pose at(double x, double y, double z, double yaw = 0.0) {
    Pose pose;
    pose.position = Vec3(x, y, z);
    pose.rotation = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
    return pose;
}

/// Vertical gap between two bodies resting on each other: none. The start tilt then makes a
/// resting pair overlap by a fraction of a millimetre (0.3 mm for a 20 cm cube, 0.7 mm for a 50 cm
/// plate), which the solver pushes out gently; gaps wide enough to rule that out make a stack fall
/// as a whole and land in a cascade of impacts (a 20-stack's lowest boxes hit at 1 m/s; 1 cm plates
/// passed through each other).
double gapFor(double) { return 0.0; }

PlacedPart boxPart(const Vec3& half, const Vec3& offset) {
    Pose pose;
    pose.position = offset;
    return PlacedPart{gdc::scenes::makeBox(half), pose, true, half};
}

void buildStack(BenchScene& s, int count) {
    s.ground();
    const Vec3 half(0.1, 0.1, 0.1);
    const double gap = gapFor(half.head<2>().norm());
    for (int i = 0; i < count; ++i)
        s.box(half, 1000.0, at(0, 0, half.z() + i * (2 * half.z() + gap) + gap), (i + 1) * gap);
}

void buildHeavyOnLight(BenchScene& s, double ratio) {
    s.ground();
    // Two 1 kg cubes 20 cm apart; a box `ratio` times heavier lying across both.
    const Vec3 light(0.1, 0.1, 0.1), heavy(0.35, 0.15, 0.1);
    const double lightDensity = 1.0 / (8 * light.prod()), heavyDensity = ratio / (8 * heavy.prod());
    const double gap = gapFor(heavy.head<2>().norm());
    s.box(light, lightDensity, at(-0.2, 0, light.z() + gap), gap);
    s.box(light, lightDensity, at(0.2, 0, light.z() + gap), gap);
    s.box(heavy, heavyDensity, at(0, 0, 2 * light.z() + heavy.z() + 2 * gap), 2 * gap);
}

void buildPyramid(BenchScene& s, int base) {
    s.ground();
    const Vec3 half(0.1, 0.1, 0.1);
    const double gap = gapFor(half.head<2>().norm());
    const double pitch = 2 * half.x() + 5e-3;  // 5 mm between neighbours: jitter never makes them touch
    for (int row = 0; row < base; ++row) {
        const int count = base - row;
        for (int i = 0; i < count; ++i) {
            const double x = (i - 0.5 * (count - 1)) * pitch;
            s.box(half, 1000.0, at(x, 0, half.z() + row * (2 * half.z() + gap) + gap), (row + 1) * gap);
        }
    }
}

void buildWall(BenchScene& s) {
    // The brick wall of samples/scenes/brick_wall.cpp: 6 courses of 10 bricks in running bond, the
    // courses that start with a half brick end with one (63 bricks); joints of 5 mm here.
    s.ground();
    const double pitch = 0.30, joint = 5e-3, halfDepth = 0.075, halfHeight = 0.05;
    const double halfLength = 0.5 * pitch - 0.5 * joint;
    const double gap = gapFor(std::hypot(halfLength, halfDepth));
    const double wallHalfLength = 0.5 * pitch * 10;
    for (int course = 0; course < 6; ++course) {
        const double z = halfHeight + course * (2 * halfHeight + gap) + gap;
        const double drop = (course + 1) * gap;
        if (course % 2 == 0) {
            for (int i = 0; i < 10; ++i)
                s.box({halfLength, halfDepth, halfHeight}, 2000.0, at(-wallHalfLength + (i + 0.5) * pitch, 0, z), drop);
        } else {
            const double halfBrick = 0.25 * pitch - 0.5 * joint;
            s.box({halfBrick, halfDepth, halfHeight}, 2000.0, at(-wallHalfLength + 0.25 * pitch, 0, z), drop);
            for (int i = 0; i < 9; ++i)
                s.box({halfLength, halfDepth, halfHeight}, 2000.0, at(-wallHalfLength + (i + 1) * pitch, 0, z), drop);
            s.box({halfBrick, halfDepth, halfHeight}, 2000.0, at(wallHalfLength - 0.25 * pitch, 0, z), drop);
        }
    }
}

void buildPlates(BenchScene& s, double aspect) {
    s.ground();
    const double halfWidth = 0.25, halfThickness = halfWidth / aspect;
    const Vec3 half(halfWidth, halfWidth, halfThickness);
    const double gap = gapFor(half.head<2>().norm());
    for (int i = 0; i < 10; ++i)
        s.box(half, 1000.0, at(0, 0, halfThickness + i * (2 * halfThickness + gap) + gap), (i + 1) * gap);
}

/// The robustness test's thin plates (tests/robustness/world_test.cpp, "thin plates stacked"):
/// five 1 m × 1 m × 1 cm plates of 1 kg (1:100), each turned 0.1 rad about the vertical and
/// shifted 1 cm from the one below, so that every pair meets in an octagon of 8 corners — more
/// than the default budget keeps, which the aligned plates above never reach.
void buildTurnedPlates(BenchScene& s) {
    s.ground();
    const Vec3 half(0.5, 0.5, 0.005);
    for (int i = 0; i < 5; ++i)
        s.box(half, 1.0 / (8 * half.prod()), at(0.01 * i, -0.01 * i, half.z() * (2 * i + 1), 0.1 * i), 0.0);
}

void buildHulls(BenchScene& s) {
    // Hexagonal prisms and irregular slabs (random polygons top and bottom, a random belt), all
    // with flat tops and bottoms, alternately; shapes from a fixed generator (the seed only jitters).
    s.ground();
    Random shapes(7);
    const double radius = 0.15, halfHeight = 0.05;
    const double gap = gapFor(radius);
    for (int i = 0; i < 8; ++i) {
        const auto shape = i % 2 == 0 ? gdc::scenes::makePrism(6, radius, halfHeight)
                                      : gdc::scenes::makeIrregularSlab(shapes, radius, halfHeight);
        s.body({PlacedPart{shape, Pose{}, false, Vec3::Zero()}}, 800.0,
               at(0, 0, halfHeight + i * (2 * halfHeight + gap) + gap, 0.3 * i), (i + 1) * gap);
    }
}

/// Composites of 3 to 5 boxes: an L (3), a T (4), a table (5: top and four legs), a cross (3).
std::vector<std::vector<PlacedPart>> compositeShapes() {
    std::vector<std::vector<PlacedPart>> shapes;
    shapes.push_back({boxPart({0.1, 0.04, 0.04}, {0, 0, 0}), boxPart({0.04, 0.12, 0.04}, {-0.14, 0.08, 0}),
                      boxPart({0.04, 0.04, 0.04}, {0.14, 0, 0})});
    shapes.push_back({boxPart({0.2, 0.04, 0.04}, {0, 0.12, 0}), boxPart({0.04, 0.08, 0.04}, {0, 0, 0}),
                      boxPart({0.06, 0.03, 0.04}, {0, -0.11, 0}), boxPart({0.03, 0.03, 0.04}, {0.23, 0.12, 0})});
    shapes.push_back({boxPart({0.18, 0.12, 0.02}, {0, 0, 0.1}), boxPart({0.02, 0.02, 0.08}, {0.15, 0.09, 0}),
                      boxPart({0.02, 0.02, 0.08}, {-0.15, 0.09, 0}), boxPart({0.02, 0.02, 0.08}, {0.15, -0.09, 0}),
                      boxPart({0.02, 0.02, 0.08}, {-0.15, -0.09, 0})});
    shapes.push_back({boxPart({0.18, 0.04, 0.04}, {0, 0, 0}), boxPart({0.04, 0.07, 0.04}, {0, 0.11, 0}),
                      boxPart({0.04, 0.07, 0.04}, {0, -0.11, 0})});
    return shapes;
}

void buildComposites(BenchScene& s) {
    // Twelve composites in three layers of a 2 × 2 grid 0.6 m apart, each layer shifted a little
    // and landing on the one below, turned by a fixed generator's angles, fall into a heap.
    s.ground();
    const auto shapes = compositeShapes();
    Random turns(11);
    int k = 0;
    for (int layer = 0; layer < 3; ++layer)
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j, ++k)
                s.body(shapes[k % shapes.size()], 700.0,
                       at((i - 0.5) * 0.6 + 0.08 * layer, (j - 0.5) * 0.6 - 0.05 * layer, 0.15 + 0.3 * layer, turns.uniform(-gdc::scenes::kPi, gdc::scenes::kPi)));
}

void buildPile(BenchScene& s) {
    // 1000 cubes of 10 cm in 10 layers of 10 × 10, 15 cm apart; every other layer is shifted by
    // half that and each cube turned by a fixed generator's angle, so they topple into a pile.
    s.ground();
    Random turns(13);
    const Vec3 half(0.05, 0.05, 0.05);
    const double pitch = 0.15;
    for (int layer = 0; layer < 10; ++layer) {
        const double shift = layer % 2 ? 0.5 * pitch : 0.0;
        for (int i = 0; i < 10; ++i)
            for (int j = 0; j < 10; ++j)
                s.box(half, 1000.0,
                      at((i - 4.5) * pitch + shift, (j - 4.5) * pitch + shift, 0.06 + layer * pitch,
                         turns.uniform(-0.4, 0.4)));
    }
}

/// A card (half extents: thickness along x, width along y, height along z) turned by `lean` about y.
Pose cardPose(double x, double z, double lean) {
    Pose pose;
    pose.position = Vec3(x, 0, z);
    pose.rotation = Eigen::AngleAxisd(lean, Vec3::UnitY()).toRotationMatrix();
    return pose;
}

void buildCards(BenchScene& s) {
    // Cards leaning on each other: a row of 6 cards (20 × 30 cm, 5 mm thick) leaning towards a
    // 9 kg book standing on the ground, the first on the book's side, each next one with its top
    // edge on the face of the one before, each leaning more (0.20 rad, then 0.07 rad more per card)
    // so that its top lies below the top of the one it leans on. Every card's thrust passes
    // through the row to the book; feet held by friction. (Card houses of A-frames — two cards
    // meeting top edge on top edge — fell in every seed for every contender, dBox under dWorldStep
    // included: their top edges slide past each other at the first asymmetry.)
    s.ground();
    const double t = 0.0025, w = 0.1, h = 0.15, density = 800.0, lift = 1e-3, gap = 0.5e-3;
    const Vec3 book(0.05, 0.15, 0.2);
    s.box(book, 1500.0, at(0, 0, book.z() + lift), lift);
    // The face the next card leans on: a point on it and its outward normal (x, z).
    double faceX = book.x(), faceZ = 0.0, normalX = 1.0, normalZ = 0.0;
    for (int k = 0; k < 6; ++k) {
        const double lean = 0.20 + 0.07 * k;
        const double c = std::cos(lean), sn = std::sin(lean);
        // Top-left corner (local (−t, h)) relative to the centre, the card turned by −lean about y.
        const double cornerX = -t * c - h * sn, cornerZ = -t * sn + h * c;
        const double centreZ = t * sn + h * c + lift;  // lowest corner `lift` above the ground
        // The corner `gap` off the face: (corner − face point)·normal = gap, solved for the centre's x.
        const double centreX = faceX + (gap - (centreZ + cornerZ - faceZ) * normalZ) / normalX - cornerX;
        s.box({t, w, h}, density, cardPose(centreX, centreZ, -lean), lift);
        // This card's right face (local x = +t): through centre + (t c, t s), normal (c, s).
        faceX = centreX + t * c;
        faceZ = centreZ + t * sn;
        normalX = c;
        normalZ = sn;
    }
}

void buildColumn(BenchScene& s, int lightCount, bool heavyInMiddle, double ratio, bool hulls) {
    // A column of `lightCount` unit cubes of 1 kg and one cube `ratio` times heavier, on top or in
    // the middle (half the light ones, rounded up, below it), stacked without gaps; as dBox geoms or,
    // with `hulls`, as convex hulls (dConvex geoms).
    s.ground();
    const Vec3 half(0.5, 0.5, 0.5);
    const double lightDensity = 1.0 / (8 * half.prod());
    const int below = heavyInMiddle ? (lightCount + 1) / 2 : lightCount;
    for (int i = 0; i <= lightCount; ++i) {
        const double density = (i == below ? ratio : 1.0) * lightDensity;
        const Pose pose = at(0, 0, half.z() + i * 2 * half.z());
        if (hulls) s.body({PlacedPart{gdc::scenes::makeBox(half), Pose{}, false, half}}, density, pose);
        else s.box(half, density, pose);
    }
}

/// The heap of composites let go one by one (SceneSpec::releaseInterval): twelve composites, each
/// placed where it is let go from, in a spiral 0.6 m above the ground rising 8 cm per body.
void buildReleasedHeap(BenchScene& s) {
    s.ground();
    const auto shapes = compositeShapes();
    Random turns(17);
    for (int k = 0; k < 12; ++k) {
        const double angle = 2.4 * k, radius = 0.08;
        s.body(shapes[k % shapes.size()], 700.0,
               at(radius * std::cos(angle), radius * std::sin(angle), 0.6 + 0.08 * k, turns.uniform(-gdc::scenes::kPi, gdc::scenes::kPi)));
    }
}

/// A pose whose local z axis (a cylinder's or capsule's axis) lies along `axis`.
Pose lying(double x, double y, double z, const Vec3& axis) {
    Pose pose;
    pose.position = Vec3(x, y, z);
    pose.rotation = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis).toRotationMatrix();
    return pose;
}

// The curved scenes (issue 33; SceneSpec::curved): ODE's dCylinder and dCapsule geoms, made by the
// scene library from makeCylinderPart / makeCapsulePart with ODE's exact mass properties. Stacked
// without gaps, as the boxes.
void buildCans(BenchScene& s) {
    // Three cans standing cap on cap (cylinders of radius 10 cm, 20 cm tall, 1000 kg/m³: 6.3 kg,
    // a full paint pail) and a board (40 × 40 × 4 cm, 600 kg/m³: 3.8 kg) lying on the top one:
    // cylinder–plane, cylinder–cylinder (cap on cap) and cylinder–box.
    s.ground();
    const double radius = 0.1, length = 0.2;
    for (int i = 0; i < 3; ++i)
        s.body({gdc::scenes::makeCylinderPart(radius, length)}, 1000.0, at(0, 0, 0.5 * length + i * length));
    const Vec3 board(0.2, 0.2, 0.02);
    s.box(board, 600.0, at(0, 0, 3 * length + board.z()));
}

void buildTins(BenchScene& s) {
    // Ten tins stacked cap on cap (cylinders of radius 4 cm, 12 cm tall, 1000 kg/m³: 0.6 kg): a
    // column 1.2 m tall on an 8 cm foot, the curved counterpart of stack10.
    s.ground();
    const double radius = 0.04, length = 0.12;
    for (int i = 0; i < 10; ++i)
        s.body({gdc::scenes::makeCylinderPart(radius, length)}, 1000.0, at(0, 0, 0.5 * length + i * length));
}

void buildLogs(BenchScene& s) {
    // Logs between chocks: two logs (cylinders of radius 5 cm, 60 cm long, 600 kg/m³: 2.8 kg)
    // lying along y on the ground 5 mm apart, a third in their groove, and two chocks (beams
    // 10 × 60 × 10 cm, 2000 kg/m³: 12 kg) on the ground 2.5 mm off the lower logs' outer sides:
    // cylinder–plane, cylinder–cylinder along a line, cylinder–box (once the lower logs are pushed
    // out), box–plane. What fell in every seed tried (3 to 5) for both contenders under every
    // stepper, so was left out: the same three logs without the chocks (the lower logs roll
    // apart, as real pipe stacks do), a pyramid of 3, 2 and 1 logs between the chocks, and a crib
    // (layers crossing at right angles: a bed of rollers, each layer rolling on the one below).
    s.ground();
    const double radius = 0.05, length = 0.6, pitch = 2 * radius + 5e-3;
    const double rise = std::sqrt(4 * radius * radius - 0.25 * pitch * pitch);  // the upper log touching both
    s.body({gdc::scenes::makeCylinderPart(radius, length)}, 600.0, lying(-0.5 * pitch, 0, radius, Vec3::UnitY()));
    s.body({gdc::scenes::makeCylinderPart(radius, length)}, 600.0, lying(0.5 * pitch, 0, radius, Vec3::UnitY()));
    s.body({gdc::scenes::makeCylinderPart(radius, length)}, 600.0, lying(0, 0, radius + rise, Vec3::UnitY()));
    const Vec3 chock(0.05, 0.3, 0.05);
    for (const double side : {-1.0, 1.0})
        s.box(chock, 2000.0, at(side * (0.5 * pitch + radius + 2.5e-3 + chock.x()), 0, chock.z()));
}

void buildPipe(BenchScene& s) {
    // A pipe on two blocks: two 20 cm cubes (1000 kg/m³: 8 kg) 40 cm apart on the ground and a
    // capsule (radius 5 cm, 60 cm between its ball centres, 1000 kg/m³: 5.2 kg) lying across
    // both, along a line on each (capsule–box, box–plane).
    s.ground();
    const Vec3 block(0.1, 0.1, 0.1);
    s.box(block, 1000.0, at(-0.2, 0, block.z()));
    s.box(block, 1000.0, at(0.2, 0, block.z()));
    s.body({gdc::scenes::makeCapsulePart(0.05, 0.6)}, 1000.0, lying(0, 0, 2 * block.z() + 0.05, Vec3::UnitX()));
}

/// "column" + light cubes (2–4) + "top" or "mid" + the heavy cube's mass ratio (10, 100, 1000) +
/// "h" for hulls, e.g. column3mid100h; false if `name` is not one.
bool parseColumn(const std::string& name, int& lightCount, bool& middle, double& ratio, bool& hulls) {
    char where[4] = {};
    int count = 0, r = 0, used = 0;
    if (std::sscanf(name.c_str(), "column%d%3[a-z]%d%n", &count, where, &r, &used) != 3) return false;
    const std::string rest = name.substr(static_cast<std::size_t>(used));
    if (count < 1 || r < 1 || (std::string(where) != "top" && std::string(where) != "mid") || (rest != "" && rest != "h")) return false;
    lightCount = count;
    middle = std::string(where) == "mid";
    ratio = r;
    hulls = rest == "h";
    return true;
}

BenchScene::Builder builderFor(const std::string& name) {
    int lightCount = 0;
    bool middle = false, hulls = false;
    double ratio = 1;
    if (parseColumn(name, lightCount, middle, ratio, hulls))
        return [=](BenchScene& s) { buildColumn(s, lightCount, middle, ratio, hulls); };
    if (name == "heap12") return buildReleasedHeap;
    if (name == "stack10") return [](BenchScene& s) { buildStack(s, 10); };
    if (name == "stack20") return [](BenchScene& s) { buildStack(s, 20); };
    if (name == "heavy100") return [](BenchScene& s) { buildHeavyOnLight(s, 100.0); };
    if (name == "heavy1000") return [](BenchScene& s) { buildHeavyOnLight(s, 1000.0); };
    if (name == "pyramid") return [](BenchScene& s) { buildPyramid(s, 8); };
    if (name == "wall") return buildWall;
    if (name == "plates20") return [](BenchScene& s) { buildPlates(s, 20.0); };
    if (name == "plates50") return [](BenchScene& s) { buildPlates(s, 50.0); };
    if (name == "plates100") return buildTurnedPlates;
    if (name == "hulls") return buildHulls;
    if (name == "composites") return buildComposites;
    if (name == "pile1000") return buildPile;
    if (name == "cards") return buildCards;
    if (name == "cans") return buildCans;
    if (name == "tins") return buildTins;
    if (name == "logs") return buildLogs;
    if (name == "pipe") return buildPipe;
    throw std::invalid_argument("no builder for scene " + name);
}

// ---- a world of one contender ---------------------------------------------------------------------
struct BodyState {
    dReal position[3], quaternion[4], linear[3], angular[3];
};

struct World {
    std::unique_ptr<BenchScene> scene;
    dJointGroupID contacts = nullptr;
    std::vector<dBodyID> bodies;
    std::vector<Vec3> startPosition;
    std::vector<Vec3> startUp;
    std::vector<double> size;    // least horizontal extent at the start (m)
    std::vector<double> height;  // vertical extent at the start (m)
    std::vector<double> allowedDrop;
    std::vector<double> extent;  // largest horizontal extent at the start (m)
    // Heaps let go one by one: each body's start state, whether it was let go, where it was when
    // the heap settled.
    std::vector<BodyState> startState;
    std::vector<char> released;
    std::vector<Vec3> settledPosition;
    double mu = SolverConstants::mu;
    int contactsAsked = SolverConstants::contactsAsked;
    const Contender* contender = nullptr;  // the pair order's rule (JointMaker)
    bool record = false;                   // keep every joint's contact (compareContacts)
    std::vector<std::pair<dJointID, dContactGeom>> recorded;
    std::unordered_map<dGeomID, int> serial;  // creation order: pairs are collided in it
    struct Pair {
        int first, second;
        dGeomID g1, g2;
        bool operator<(const Pair& o) const { return first != o.first ? first < o.first : second < o.second; }
    };
    std::vector<Pair> pairs;
    std::vector<dContactGeom> buffer = std::vector<dContactGeom>(SolverConstants::contactsAsked);
    int invalid = 0;

    World() = default;
    World(const World&) = delete;
    World& operator=(const World&) = delete;
    ~World() {
        if (contacts) dJointGroupDestroy(contacts);
    }
};

Vec3 upAxis(dBodyID body) {
    const dReal* r = dBodyGetRotation(body);
    return Vec3(r[2], r[6], r[10]);
}

std::uint64_t jitterSeed(int seed, std::size_t body) {
    return (static_cast<std::uint64_t>(seed) + 1) * 0x9E3779B97F4A7C15ull ^ (body + 1) * 0xBF58476D1CE4E5B9ull;
}

BodyState stateOf(dBodyID body);
void setState(dBodyID body, const BodyState& s);

std::unique_ptr<World> makeWorld(const SceneSpec& spec, const Stepper& stepper, ColliderKind kind, int seed, bool sleep,
                                 double jitter = 1.0) {
    auto w = std::make_unique<World>();
    w->scene = std::make_unique<BenchScene>(spec.name, kind == ColliderKind::OdeConvex, builderFor(spec.name));
    w->scene->reset();
    dWorldID world = w->scene->world();
    dWorldSetQuickStepNumIterations(world, stepper.iterations);
    dWorldSetCFM(world, stepper.cfm);
    w->mu = stepper.mu;
    w->contactsAsked = stepper.contactsAsked;
    w->contacts = dJointGroupCreate(0);
    int next = 0;
    for (dGeomID geom : w->scene->staticGeoms()) w->serial[geom] = next++;
    w->allowedDrop = w->scene->allowedDrop();
    for (std::size_t i = 0; i < w->scene->bodies().size(); ++i) {
        const gdc::scenes::Body& body = w->scene->bodies()[i];
        for (const gdc::scenes::Part& part : body.parts) w->serial[part.geom] = next++;
        // The seed's jitter: horizontal offset, a turn about the vertical and small tilts.
        Random random(jitterSeed(seed, i));
        const double dx = jitter * random.uniform(-Jitter::position, Jitter::position);
        const double dy = jitter * random.uniform(-Jitter::position, Jitter::position);
        const double yaw = jitter * random.uniform(-Jitter::yaw, Jitter::yaw);
        const double tiltX = jitter * random.uniform(-Jitter::tilt, Jitter::tilt);
        const double tiltY = jitter * random.uniform(-Jitter::tilt, Jitter::tilt);
        const dReal* p = dBodyGetPosition(body.body);
        const dReal* r = dBodyGetRotation(body.body);
        Mat3 rotation;
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 3; ++column) rotation(row, column) = r[row * 4 + column];
        const Mat3 turn = (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(tiltY, Vec3::UnitY()) *
                           Eigen::AngleAxisd(tiltX, Vec3::UnitX())).toRotationMatrix();
        // Turned about the body's own centre, so the gap the builder left stays.
        rotation = turn * rotation;
        dMatrix3 out;
        for (int row = 0; row < 3; ++row) {
            for (int column = 0; column < 3; ++column) out[row * 4 + column] = rotation(row, column);
            out[row * 4 + 3] = 0;
        }
        dBodySetRotation(body.body, out);
        dBodySetPosition(body.body, p[0] + dx, p[1] + dy, p[2]);
        w->bodies.push_back(body.body);
        w->startPosition.push_back(Vec3(p[0], p[1], p[2]));
        w->startUp.push_back(upAxis(body.body));
        // Extents at the start, from the parts' vertices.
        Vec3 low = Vec3::Constant(1e300), high = Vec3::Constant(-1e300);
        for (const gdc::scenes::Part& part : body.parts) {
            const Pose pose = gdc::ode::poseOf(part.geom);
            for (const Vec3& v : part.shape->vertices()) {
                low = low.cwiseMin(pose.apply(v));
                high = high.cwiseMax(pose.apply(v));
            }
        }
        w->size.push_back(std::min(high.x() - low.x(), high.y() - low.y()));
        w->extent.push_back(std::max(high.x() - low.x(), high.y() - low.y()));
        w->height.push_back(high.z() - low.z());
    }
    if (w->allowedDrop.size() != w->bodies.size()) w->allowedDrop.assign(w->bodies.size(), 0.0);
    dWorldSetAutoDisableFlag(world, sleep ? 1 : 0);  // ODE's default thresholds
    for (dBodyID body : w->bodies) dBodySetAutoDisableDefaults(body);
    w->released.assign(w->bodies.size(), 1);
    if (spec.releaseInterval > 0) {
        // Every body waits disabled, 20 m up and 3 m from the next, until it is let go.
        for (std::size_t i = 0; i < w->bodies.size(); ++i) {
            w->startState.push_back(stateOf(w->bodies[i]));
            w->released[i] = 0;
            dBodySetPosition(w->bodies[i], 3.0 * static_cast<double>(i + 1), 30.0, 20.0);
            dBodyDisable(w->bodies[i]);
        }
    }
    return w;
}

/// Heaps let go one by one: lets go every body whose time has come by the step that ends at `time`.
void releaseBodies(World& w, const SceneSpec& spec, double time) {
    if (spec.releaseInterval <= 0) return;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.released[i] || time + 1e-9 < spec.releaseInterval * static_cast<double>(i)) continue;
        setState(w.bodies[i], w.startState[i]);
        w.released[i] = 1;
    }
}

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
    // Only collect: the broad phase's order follows memory addresses; pairs are collided in
    // creation order (below), so a seed replays exactly and every contender sees the same order.
    World& w = *static_cast<World*>(data);
    auto a = w.serial.find(o1), b = w.serial.find(o2);
    if (a == w.serial.end() || b == w.serial.end()) return;
    if (a->second < b->second) w.pairs.push_back({a->second, b->second, o1, o2});
    else w.pairs.push_back({b->second, a->second, o2, o1});
}

/// The contact joints of one geom pair's contacts (each valid one), counted in `made`.
struct JointMaker {
    World* w;
    int made;
    static void handler(void* data, dGeomID g1, dGeomID g2, dContactGeom* contacts, int count) {
        JointMaker& maker = *static_cast<JointMaker*>(data);
        World& w = *maker.w;
        dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
        // The order the solver meets the rows: the reverse of their creation (RowOrder).
        std::vector<int> created(static_cast<std::size_t>(std::max(count, 0)));
        for (int i = 0; i < count; ++i) created[i] = i;
        RowOrder order = w.contender ? w.contender->order : RowOrder::AsIs;
        if (order == RowOrder::HeavyDeepestFirst) {
            double m1 = 0, m2 = 0;
            if (b1) { dMass m; dBodyGetMass(b1, &m); m1 = m.mass; }
            if (b2) { dMass m; dBodyGetMass(b2, &m); m2 = m.mass; }
            const bool heavy = b1 && b2 && std::max(m1, m2) >= w.contender->massRatio * std::min(m1, m2);
            order = heavy ? RowOrder::DeepestFirst : RowOrder::DeepestLast;
        }
        if (order == RowOrder::DeepDeepestFirst) {
            double deepest = 0;
            for (int i = 0; i < count; ++i) deepest = std::max(deepest, static_cast<double>(contacts[i].depth));
            order = deepest > w.contender->massRatio ? RowOrder::DeepestFirst : RowOrder::DeepestLast;
        }
        if (order == RowOrder::Reversed) std::reverse(created.begin(), created.end());
        if (order == RowOrder::DeepestFirst)  // created shallowest first: met deepest first
            std::stable_sort(created.begin(), created.end(), [&](int a, int b) { return contacts[a].depth < contacts[b].depth; });
        if (order == RowOrder::DeepestLast)
            std::stable_sort(created.begin(), created.end(), [&](int a, int b) { return contacts[a].depth > contacts[b].depth; });
        for (int k = 0; k < count; ++k) {
            const dContactGeom& c = contacts[created[k]];
            const double length = std::sqrt(c.normal[0] * c.normal[0] + c.normal[1] * c.normal[1] + c.normal[2] * c.normal[2]);
            // ODE's convex collider gives a zero normal for exactly touching shapes (ODE would abort).
            if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-6 || !std::isfinite(c.depth) ||
                !std::isfinite(c.pos[0] + c.pos[1] + c.pos[2])) {
                ++w.invalid;
                continue;
            }
            dContact contact{};
            contact.surface.mode = dContactApprox1;
            contact.surface.mu = w.mu;
            contact.geom = c;
            contact.geom.g1 = g1;
            contact.geom.g2 = g2;
            dJointID joint = dJointCreateContact(w.scene->world(), w.contacts, &contact);
            dJointAttach(joint, b1, b2);
            if (w.record) w.recorded.push_back({joint, contact.geom});
            ++maker.made;
        }
    }
};

/// One collision pass: every pair of the broad phase through the contender's collider, a contact
/// joint per valid contact. gdcontact's contacts go through gdc::ode::BodyPairContacts, so that
/// Settings::maxBodyPairContacts applies where bodies touch through several geom pairs (as
/// gdc::ode::spaceCollide applies it); pairs are added in creation order. Returns the contacts made.
int collideAll(World& w, const Contender& contender) {
    w.pairs.clear();
    dSpaceCollide(w.scene->space(), &w, &nearCallback);
    std::sort(w.pairs.begin(), w.pairs.end());
    JointMaker maker{&w, 0};
    w.contender = &contender;
    const bool gdcontact = contender.kind == ColliderKind::Gdcontact;
    std::optional<gdc::ode::BodyPairContacts> collected;
    if (gdcontact) collected.emplace(contender.settings);
    for (const World::Pair& pair : w.pairs) {
        dBodyID b1 = dGeomGetBody(pair.g1), b2 = dGeomGetBody(pair.g2);
        if (b1 == b2) continue;  // parts of one composite, or two static geoms
        if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) continue;
        // gdcontact takes the pairs install() would route to it (gdc::ode::handles); the others
        // (capsule–plane, capsule–capsule, sphere–box, ...) go to dCollide, as after install().
        const bool mine = gdcontact && gdc::ode::handles(dGeomGetClass(pair.g1), dGeomGetClass(pair.g2));
        const int count = mine
                              ? gdc::ode::collide(pair.g1, pair.g2, w.contactsAsked, w.buffer.data(),
                                                  sizeof(dContactGeom), contender.settings)
                              : dCollide(pair.g1, pair.g2, w.contactsAsked, w.buffer.data(), sizeof(dContactGeom));
        if (gdcontact) collected->add(pair.g1, pair.g2, w.buffer.data(), count);
        else if (count > 0) JointMaker::handler(&maker, pair.g1, pair.g2, w.buffer.data(), count);
    }
    if (gdcontact) collected->deliver(&maker, &JointMaker::handler);
    return maker.made;
}

void stepWorld(World& w, const Stepper& stepper, const RunOptions& options) {
    if (options.rootIslandsAtLowest) rootIslandsAtLowest(w.bodies);
    if (stepper.quick) dWorldQuickStep(w.scene->world(), SolverConstants::dt);
    else dWorldStep(w.scene->world(), SolverConstants::dt);
}

BodyState stateOf(dBodyID body) {
    BodyState s;
    const dReal* p = dBodyGetPosition(body);
    const dReal* q = dBodyGetQuaternion(body);
    const dReal* v = dBodyGetLinearVel(body);
    const dReal* a = dBodyGetAngularVel(body);
    for (int k = 0; k < 3; ++k) {
        s.position[k] = p[k];
        s.linear[k] = v[k];
        s.angular[k] = a[k];
    }
    for (int k = 0; k < 4; ++k) s.quaternion[k] = q[k];
    return s;
}

void setState(dBodyID body, const BodyState& s) {
    dBodySetPosition(body, s.position[0], s.position[1], s.position[2]);
    dBodySetQuaternion(body, s.quaternion);
    dBodySetLinearVel(body, s.linear[0], s.linear[1], s.linear[2]);
    dBodySetAngularVel(body, s.angular[0], s.angular[1], s.angular[2]);
    dBodySetForce(body, 0, 0, 0);
    dBodySetTorque(body, 0, 0, 0);
    dBodyEnable(body);
}

double ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// ODE's default auto-disable criterion (dWorldCreate: 0.01 m/s and 0.01 rad/s, 10 steps, one
// sample), emulated where sleeping is off so that the time is reported either way.
constexpr double kIdleSpeed = 0.01;
constexpr int kIdleSteps = 10;

}  // namespace

// ---- public ---------------------------------------------------------------------------------------
void setSetting(gdc::Settings& settings, const std::string& name, const std::string& value) {
    for (const SettingField& field : settingFields()) {
        if (name == field.name) {
            field.set(settings, value);
            return;
        }
    }
    std::string known;
    for (const SettingField& field : settingFields()) known += std::string(known.empty() ? "" : ", ") + field.name;
    throw std::invalid_argument("unknown setting '" + name + "' (known: " + known + ")");
}

std::vector<std::string> settingNames() {
    std::vector<std::string> names;
    for (const SettingField& field : settingFields()) names.push_back(field.name);
    return names;
}

Contender parseContender(const std::string& full) {
    Contender c;
    c.name = full;
    std::string spec = full;
    bool relativeDeep = false;
    const auto plus = full.find("+order=");
    if (plus != std::string::npos) {
        spec = full.substr(0, plus);
        std::string order = full.substr(plus + 7);
        const auto colon = order.find(':');
        if (colon != std::string::npos) {
            c.massRatio = parseDouble("+order ratio", order.substr(colon + 1));
            order = order.substr(0, colon);
        }
        if (order == "as-is") c.order = RowOrder::AsIs;
        else if (order == "reversed") c.order = RowOrder::Reversed;
        else if (order == "deepest-first") c.order = RowOrder::DeepestFirst;
        else if (order == "deepest-last") c.order = RowOrder::DeepestLast;
        else if (order == "heavy-deepest-first") c.order = RowOrder::HeavyDeepestFirst;
        else if (order == "deep-deepest-first") c.order = RowOrder::DeepDeepestFirst;
        else if (order == "relative-deep-deepest-first") {
            // The library's rule (gdc::ContactOrder::DeepestFirstWhenLoaded), the ratio its
            // loadedDepthFraction: set on the gdc contender's settings below, rows left as written.
            if (spec.rfind("gdc", 0) != 0)
                throw std::invalid_argument("contender '" + full + "': relative-deep-deepest-first is gdcontact's "
                                            "contactOrder=DeepestFirstWhenLoaded, for gdc contenders only");
            relativeDeep = true;
        } else throw std::invalid_argument("contender '" + full + "': order '" + order +
                                         "' is not as-is, reversed, deepest-first, deepest-last, heavy-deepest-first[:RATIO], "
                                         "deep-deepest-first[:METRES] or relative-deep-deepest-first[:FRACTION]");
    }
    if (relativeDeep) {  // before the settings variant, which may set either field itself
        c.settings.contactOrder = gdc::ContactOrder::DeepestFirstWhenLoaded;
        if (full.find("+order=relative-deep-deepest-first:") != std::string::npos)
            c.settings.loadedDepthFraction = c.massRatio;
        c.order = RowOrder::AsIs;
    }
    if (spec == "gdc") return c;
    if (spec == "ode-box") {
        c.kind = ColliderKind::OdeBox;
        return c;
    }
    if (spec == "ode-convex") {
        c.kind = ColliderKind::OdeConvex;
        return c;
    }
    if (spec.rfind("gdc:", 0) != 0)
        throw std::invalid_argument("contender '" + spec + "': expected gdc, ode-box, ode-convex or gdc:NAME=VALUE,...");
    std::stringstream list(spec.substr(4));
    std::string item;
    while (std::getline(list, item, ',')) {
        const auto equals = item.find('=');
        if (equals == std::string::npos || equals == 0)
            throw std::invalid_argument("contender '" + spec + "': '" + item + "' is not NAME=VALUE");
        setSetting(c.settings, item.substr(0, equals), item.substr(equals + 1));
    }
    try {
        gdc::validate(c.settings);
    } catch (const std::exception& e) {
        throw std::invalid_argument("contender '" + spec + "': " + e.what());
    }
    return c;
}

std::vector<Stepper> allSteppers() {
    return {{"quick10", true, 10}, {"quick20", true, 20}, {"quick50", true, 50}, {"world", false, 20}};
}

Stepper parseStepper(const std::string& name) {
    std::stringstream parts(name);
    std::string base, item;
    std::getline(parts, base, '/');
    for (Stepper s : allSteppers()) {
        if (s.name != base) continue;
        s.name = name;
        while (std::getline(parts, item, '/')) {
            const auto equals = item.find('=');
            const std::string key = item.substr(0, equals), value = equals == std::string::npos ? "" : item.substr(equals + 1);
            if (key == "cfm") s.cfm = parseDouble("cfm", value);
            else if (key == "mu") s.mu = parseDouble("mu", value);
            else if (key == "maxc") s.contactsAsked = parseInt("maxc", value);
            else throw std::invalid_argument("stepper '" + name + "': '" + item + "' is not cfm=X, mu=X or maxc=N");
        }
        if (s.contactsAsked < 1 || s.contactsAsked > SolverConstants::contactsAsked || !(s.cfm >= 0) || !(s.mu >= 0))
            throw std::invalid_argument("stepper '" + name + "': maxc 1..16, cfm and mu >= 0");
        return s;
    }
    throw std::invalid_argument("unknown stepper '" + name + "' (quick10, quick20, quick50, world; /cfm=X/mu=X/maxc=N)");
}

const std::vector<SceneSpec>& sceneSpecs() {
    static const std::vector<SceneSpec> specs = {
        {"stack10", "10 cubes of 20 cm, 1 kg/dm³, stacked", 4.0, true, false, true, "", 50},
        {"stack20", "20 cubes of 20 cm stacked", 4.0, true, false, true, "", 50, 20},
        {"heavy100", "a 100 kg box (70×30×20 cm) across two 1 kg cubes 20 cm apart", 3.0, true, false, true, "", 50},
        {"heavy1000", "a 1000 kg box across two 1 kg cubes", 3.0, true, false, true, "", 50},
        {"pyramid", "a pyramid of 36 cubes (base 8), 5 mm apart", 4.0, true, false, true, "", 50, 12},
        {"wall", "the brick wall: 6 courses of 10 bricks (30×15×10 cm) in running bond, 63 bricks", 3.0, true, false,
         false, "one island of 63 bricks: a dWorldStep of the wall took 1.1 s (issue 22)", 50},
        {"plates20", "10 plates 50×50×2.5 cm (1:20) stacked", 3.0, true, false, true, "", 50},
        {"plates50", "10 plates 50×50×1 cm (1:50) stacked", 3.0, true, false, true, "", 50},
        {"plates100", "5 plates 1 m × 1 m × 1 cm (1:100), 1 kg, each turned 0.1 rad and shifted 1 cm on the one below (octagons of 8 corners)",
         3.0, true, false, true, "", 50},
        {"hulls", "8 hulls stacked: hexagonal prisms and irregular slabs (30 cm, 10 cm high)", 3.0, false, false, true, "", 50},
        {"composites", "12 composites of 3–5 boxes (L, T, table, cross) dropped into a heap", 3.0, true, true, true, "", 50},
        {"pile1000", "1000 cubes of 10 cm dropped from a staggered 10×10×10 grid into a pile", 1.5, true, true, false,
         "one island of 1000 bodies", 4},
        {"cards", "6 cards (20×30 cm, 5 mm) leaning in a row on each other and on a 9 kg book, each edge on the face of the one before", 3.0, true,
         false, true, "", 50},
    };
    static const std::vector<SceneSpec> all = [] {
        std::vector<SceneSpec> list = specs;
        // Curved scenes (issue 33): ODE's dCylinder and dCapsule; ode-box is ODE's own colliders
        // on the same geoms (SceneSpec::curved).
        const std::vector<SceneSpec> curved = {
            {"cans", "3 cans (cylinders r 10 cm, 20 cm tall, 6.3 kg) standing cap on cap, a 40×40×4 cm board (3.8 kg) on top",
             4.0, false, false, true, "", 50},
            {"tins", "10 tins (cylinders r 4 cm, 12 cm tall, 0.6 kg) standing cap on cap", 4.0, false, false, true, "", 50},
            {"logs", "3 logs (cylinders r 5 cm, 60 cm long, 2.8 kg) lying side by side, two on the ground between two 12 kg chocks (10×60×10 cm), one in their groove",
             3.0, false, false, true, "", 50},
            {"pipe", "a pipe (capsule r 5 cm, 60 cm between its ball centres, 5.2 kg) lying across two 20 cm cubes 40 cm apart",
             3.0, false, false, true, "", 50},
        };
        for (SceneSpec c : curved) {
            c.curved = true;
            c.fullSeeds = 100;
            list.push_back(c);
        }
        // Columns (issue 35): 2–4 light unit cubes of 1 kg and a heavy one on top or in the middle.
        for (const bool hulls : {false, true})
            for (const char* where : {"top", "mid"})
                for (const int ratio : {10, 100, 1000})
                    for (int light = 2; light <= 4; ++light) {
                        SceneSpec c;
                        c.name = "column" + std::to_string(light) + where + std::to_string(ratio) + (hulls ? "h" : "");
                        c.description = std::to_string(light) + " unit cubes of 1 kg and one of " + std::to_string(ratio) + " kg " +
                                        (std::string(where) == "top" ? "on top" : "in the middle") + ", stacked" +
                                        (hulls ? ", as convex hulls" : ", as boxes");
                        c.duration = 10.0;
                        c.jitterScale = 10.0;
                        c.neverSleeps = true;
                        c.hasBoxes = !hulls;
                        c.defaultSeeds = 20;
                        c.defaultWorldSeeds = 20;
                        c.fullSeeds = 200;
                        c.family = "column";
                        list.push_back(c);
                    }
        SceneSpec heap;
        heap.name = "heap12";
        heap.description = "12 composites of 3–5 boxes (table, cross, L, T) let go one by one, 0.5 s apart, onto a heap; creep watched for 5 s from 2 s after the last";
        heap.duration = 12.5;
        heap.heap = true;
        heap.defaultSeeds = 10;
        heap.defaultWorldSeeds = 5;
        heap.fullSeeds = 60;
        heap.releaseInterval = 0.5;
        heap.settleTime = 2.0;
        heap.family = "heap";
        heap.neverSleeps = true;
        list.push_back(heap);
        return list;
    }();
    return all;
}

const SceneSpec& findScene(const std::string& name) {
    for (const SceneSpec& s : sceneSpecs())
        if (s.name == name) return s;
    // Any other column by its name (e.g. column19top1: a 20-stack of unit cubes), as the listed ones.
    int lightCount = 0;
    bool middle = false, hulls = false;
    double ratio = 1;
    if (parseColumn(name, lightCount, middle, ratio, hulls)) {
        static std::deque<SceneSpec> more;  // stable addresses; one process builds its list once
        for (const SceneSpec& s : more)
            if (s.name == name) return s;
        SceneSpec c = findScene(std::string("column2top10") + (hulls ? "h" : ""));
        c.name = name;
        c.description = std::to_string(lightCount) + " unit cubes of 1 kg and one " + std::to_string(static_cast<int>(ratio)) +
                        " times heavier " + (middle ? "in the middle" : "on top") + (hulls ? ", as convex hulls" : ", as boxes");
        more.push_back(c);
        return more.back();
    }
    std::string known;
    for (const SceneSpec& s : sceneSpecs()) known += (known.empty() ? "" : ", ") + s.name;
    throw std::invalid_argument("unknown scene '" + name + "' (" + known + ")");
}

const char* failureName(Failure failure) {
    switch (failure) {
        case Failure::None: return "none";
        case Failure::Exploded: return "exploded";
        case Failure::Tunnelled: return "tunnelled";
        case Failure::Flung: return "flung";
        case Failure::Drift: return "drift";
        case Failure::Tilt: return "tilt";
        case Failure::Drop: return "drop";
        case Failure::Crashed: return "crashed";
        case Failure::Creep: return "creep";
    }
    return "?";
}

namespace {
constexpr double kExplodedDistance = 100.0;  // m from the origin
constexpr double kFlungDistance = 5.0;       // m horizontally from the origin (heaps)
constexpr double kDriftFraction = 0.5;       // of the body's least horizontal extent
constexpr double kTiltLimit = 0.25;          // rad
constexpr double kDropFraction = 0.5;        // of the body's height, beyond its start gap
constexpr double kCreepDistance = 0.05;      // m horizontally since a heap let go one by one settled
constexpr double kFellOverTilt = 0.7853981633974483;  // rad (45°): curved scenes' collapse
}  // namespace

const std::vector<FailureLimit>& failureLimits() {
    // A run fails when a limit is crossed and still crossed at the end of the run (an impact may
    // compress a stack for a moment and heal), or at once when a body explodes.
    static const std::vector<FailureLimit> limits = {
        {Failure::Exploded, "all", "a body's position is not finite or lies more than 100 m from the origin (the run stops)"},
        {Failure::Tunnelled, "all", "a body's centre of mass is below the ground (z < 0) at the end"},
        {Failure::Flung, "heaps", "a body lies more than 5 m (horizontally) from the scene's centre at the end"},
        {Failure::Drift, "standing", "a body lies more than half its least horizontal extent (horizontally) from its start at the end"},
        {Failure::Tilt, "standing", "a body's up axis is turned more than 0.25 rad (14°) from its start at the end"},
        {Failure::Drop, "standing", "a body's centre is lower than its start by more than half its height (plus the gap it started above its support) at the end"},
        {Failure::Crashed, "all", "the run did not finish (ODE aborted the worker process)"},
        {Failure::Creep, "heaps let go one by one", "a body lies more than 50 mm (horizontally) from where it was when the heap settled, at the end"},
    };
    return limits;
}

const std::vector<FailureLimit>& collapseLimits() {
    static const std::vector<FailureLimit> limits = {
        {Failure::Drop, "standing", "a body's centre is lower than its start by more than half its height (plus its start gap) at the end: the structure fell"},
        {Failure::Creep, "heaps let go one by one", "a body lies farther from where it was when the heap settled than its largest horizontal extent, at the end"},
        {Failure::Tilt, "curved", "a body's axis is turned more than 45° from its start at the end: it fell over (a can on its side sinks less than half its height)"},
        {Failure::Drift, "curved", "a body lies farther (horizontally) from its start than its least horizontal extent at the end: it rolled or slid away (a log its diameter)"},
        {Failure::Exploded, "all", "exploded, tunnelled, flung or crashed (as in the fine limits)"},
    };
    return limits;
}

void installMessageCounter() { dSetMessageHandler(&countMessage); }

SeedResult runSeed(const SceneSpec& spec, const Stepper& stepper, const Contender& contender, int seed,
                   const RunOptions& options) {
    SeedResult result;
    auto w = makeWorld(spec, stepper, contender.kind, seed, options.sleep && !spec.neverSleeps, options.jitterScale * spec.jitterScale);
    dRandSetSeed(static_cast<unsigned long>(seed));
    const int messagesBefore = gMessages, lcpBefore = gLcpErrors;
    const std::size_t n = w->bodies.size();
    result.bodies = static_cast<int>(n);
    std::vector<int> idle(n, 0);
    const int steps = static_cast<int>(std::lround(spec.duration * options.durationScale / SolverConstants::dt));
    double contacts = 0, collision = 0, solver = 0;
    // A run fails when a limit is crossed and stays crossed to the end of the run (an impact may
    // compress a stack for a moment; that heals and is no failure), or at once when it explodes.
    Failure violated = Failure::None;  // the limit crossed in the current streak of steps
    double violatedSince = -1;
    std::size_t violator = 0;
    int step = 0;
    const double settleAt = spec.releaseInterval > 0
                                ? spec.releaseInterval * static_cast<double>(n > 0 ? n - 1 : 0) + spec.settleTime
                                : -1.0;
    for (; step < steps; ++step) {
        releaseBodies(*w, spec, step * SolverConstants::dt);
        const auto t0 = Clock::now();
        contacts += collideAll(*w, contender);
        const auto t1 = Clock::now();
        stepWorld(*w, stepper, options);
        const auto t2 = Clock::now();
        dJointGroupEmpty(w->contacts);
        collision += ms(t1 - t0);
        solver += ms(t2 - t1);
        const double time = (step + 1) * SolverConstants::dt;

        bool exploded = false;
        int asleep = 0;
        Failure now = Failure::None;
        std::size_t nowBody = 0;
        auto fail = [&](Failure f, std::size_t i) {
            if (now == Failure::None) {
                now = f;
                nowBody = i;
            }
        };
        const bool settling = settleAt >= 0 && w->settledPosition.empty() && time + 1e-9 >= settleAt;
        for (std::size_t i = 0; i < n; ++i) {
            dBodyID body = w->bodies[i];
            if (!w->released[i]) {
                ++asleep;
                continue;
            }
            const dReal* p = dBodyGetPosition(body);
            const Vec3 position(p[0], p[1], p[2]);
            if (settling) w->settledPosition.push_back(position);
            if (!position.allFinite() || position.norm() > kExplodedDistance) {
                exploded = true;
                break;
            }
            if (position.z() < 0) fail(Failure::Tunnelled, i);
            const double tilt = std::atan2(upAxis(body).cross(w->startUp[i]).norm(), upAxis(body).dot(w->startUp[i]));
            result.maxTilt = std::max(result.maxTilt, tilt);
            if (spec.heap) {
                if (position.head<2>().norm() > kFlungDistance) fail(Failure::Flung, i);
                if (!settling && !w->settledPosition.empty() &&
                    (position - w->settledPosition[i]).head<2>().norm() > kCreepDistance)
                    fail(Failure::Creep, i);
            } else {
                const Vec3 moved = position - w->startPosition[i];
                if (moved.head<2>().norm() > kDriftFraction * w->size[i]) fail(Failure::Drift, i);
                if (tilt > kTiltLimit) fail(Failure::Tilt, i);
                if (-moved.z() > kDropFraction * w->height[i] + w->allowedDrop[i]) fail(Failure::Drop, i);
            }
            if (options.sleep && !spec.neverSleeps) {
                asleep += dBodyIsEnabled(body) ? 0 : 1;
            } else {
                const dReal* v = dBodyGetLinearVel(body);
                const dReal* a = dBodyGetAngularVel(body);
                const bool still = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] <= kIdleSpeed * kIdleSpeed &&
                                   a[0] * a[0] + a[1] * a[1] + a[2] * a[2] <= kIdleSpeed * kIdleSpeed;
                idle[i] = still ? idle[i] + 1 : 0;
                asleep += idle[i] >= kIdleSteps ? 1 : 0;
            }
        }
        if (exploded) {
            violated = Failure::Exploded;
            violatedSince = time;
            ++step;
            break;
        }
        if (now == Failure::None) {
            violated = Failure::None;
            violatedSince = -1;
        } else if (violated == Failure::None) {
            violated = now;
            violatedSince = time;
            violator = nowBody;
        }
        if (asleep == static_cast<int>(n) && result.sleepTime < 0) result.sleepTime = time;
        result.asleepAtEnd = n ? static_cast<double>(asleep) / n : 0.0;
    }
    result.steps = step;
    result.failure = static_cast<int>(violated);
    result.failTime = violatedSince;
    if (violated != Failure::None && std::getenv("SOLVER_SEEDS_DEBUG")) {
        const dReal* p = dBodyGetPosition(w->bodies[violator]);
        std::fprintf(stderr, "%s %s %s seed %d: %s since %.2f s, body %zu at (%.4f %.4f %.4f) from (%.4f %.4f %.4f), size %.3f height %.3f allowed drop %.4f\n",
                     spec.name.c_str(), stepper.name.c_str(), contender.name.c_str(), seed, failureName(violated), violatedSince,
                     violator, p[0], p[1], p[2], w->startPosition[violator].x(), w->startPosition[violator].y(),
                     w->startPosition[violator].z(), w->size[violator], w->height[violator], w->allowedDrop[violator]);
        for (std::size_t i = 0; i < n; ++i) {
            const dReal* q = dBodyGetPosition(w->bodies[i]);
            std::fprintf(stderr, "   body %zu at (%.4f %.4f %.4f) from (%.4f %.4f %.4f) tilt %.3f\n", i, q[0], q[1], q[2],
                         w->startPosition[i].x(), w->startPosition[i].y(), w->startPosition[i].z(),
                         std::acos(std::min(1.0, upAxis(w->bodies[i]).dot(w->startUp[i]))));
        }
    }
    for (std::size_t i = 0; i < n && result.failure != static_cast<int>(Failure::Exploded); ++i) {
        if (!w->released[i]) continue;
        const dReal* p = dBodyGetPosition(w->bodies[i]);
        result.drift = std::max(result.drift, std::hypot(p[0] - w->startPosition[i].x(), p[1] - w->startPosition[i].y()));
    }
    if (result.failure == static_cast<int>(Failure::Exploded)) result.drift = kExplodedDistance;
    // The gross criterion (collapseLimits()): at the end, a standing scene's body sank by half its
    // height (in a curved scene also: fell over, or rolled or slid away), or a heap body let go one by one moved more than its size since the heap settled;
    // in every scene, a run that exploded, tunnelled, was flung or crashed.
    const Failure f = static_cast<Failure>(result.failure);
    result.collapsed = f == Failure::Exploded || f == Failure::Tunnelled || f == Failure::Flung;
    for (std::size_t i = 0; i < n && !result.collapsed; ++i) {
        const dReal* p = dBodyGetPosition(w->bodies[i]);
        const Vec3 position(p[0], p[1], p[2]);
        if (!spec.heap) {
            if (w->startPosition[i].z() - position.z() > kDropFraction * w->height[i] + w->allowedDrop[i]) result.collapsed = 1;
            if (spec.curved) {  // fell over, or rolled / slid away
                const Vec3 up = upAxis(w->bodies[i]);
                if (std::atan2(up.cross(w->startUp[i]).norm(), up.dot(w->startUp[i])) > kFellOverTilt) result.collapsed = 1;
                if ((position - w->startPosition[i]).head<2>().norm() > w->size[i]) result.collapsed = 1;
            }
        } else if (!w->settledPosition.empty()) {
            const double moved = (position - w->settledPosition[i]).head<2>().norm();
            result.creep = std::max(result.creep, moved);
            if (moved > w->extent[i]) result.collapsed = 1;
        }
    }
    for (std::size_t i = 0; i < n && !w->settledPosition.empty() && f != Failure::Exploded; ++i) {
        const dReal* p = dBodyGetPosition(w->bodies[i]);
        result.creep = std::max(result.creep, (Vec3(p[0], p[1], p[2]) - w->settledPosition[i]).head<2>().norm());
    }
    if (step > 0) {
        result.contactsPerStep = contacts / step;
        result.collisionMs = collision / step;
        result.solverMs = solver / step;
    }
    result.messages = gMessages - messagesBefore;
    result.lcpErrors = gLcpErrors - lcpBefore;
    result.invalidContacts = w->invalid;
    result.done = 1;
    return result;
}

std::vector<CostResult> measureCost(const SceneSpec& spec, const Stepper& stepper, const std::vector<Contender>& contenders,
                                    const Contender& reference, int seed, int states, int repetitions,
                                    const RunOptions& options) {
    // The reference run, its states sampled at the middles of `states` equal parts of the run.
    std::vector<std::vector<BodyState>> sampled;
    {
        auto w = makeWorld(spec, stepper, reference.kind, seed, options.sleep && !spec.neverSleeps, options.jitterScale * spec.jitterScale);
        dRandSetSeed(static_cast<unsigned long>(seed));
        const int steps = static_cast<int>(std::lround(spec.duration * options.durationScale / SolverConstants::dt));
        int nextSample = 0;
        for (int step = 0; step < steps && nextSample < states; ++step) {
            const int sampleStep = static_cast<int>((nextSample + 0.5) * steps / states);
            if (step == sampleStep) {
                std::vector<BodyState> state;
                for (dBodyID body : w->bodies) state.push_back(stateOf(body));
                sampled.push_back(std::move(state));
                ++nextSample;
            }
            releaseBodies(*w, spec, step * SolverConstants::dt);
            collideAll(*w, reference);
            stepWorld(*w, stepper, options);
            dJointGroupEmpty(w->contacts);
        }
    }
    std::vector<std::unique_ptr<World>> worlds;
    for (const Contender& c : contenders) worlds.push_back(makeWorld(spec, stepper, c.kind, seed, false, options.jitterScale * spec.jitterScale));
    std::vector<CostResult> results(contenders.size());
    for (std::size_t s = 0; s < sampled.size(); ++s) {
        std::vector<double> bestCollision(contenders.size(), 1e300), bestSolver(contenders.size(), 1e300);
        std::vector<int> made(contenders.size(), 0);
        for (int r = 0; r < repetitions; ++r) {
            for (std::size_t c = 0; c < contenders.size(); ++c) {  // interleaved: the machine's load hits all alike
                World& w = *worlds[c];
                // One untimed step from the same state first: the timed step then finds its own
                // world's data and code in the caches, as every step of a running simulation
                // does, instead of the previous contender's. Without it the contender measured
                // after another collider's world paid 5–15 % more for the same contacts (budgets 8
                // and 6 giving the same contacts read 1.02–1.18x by their place in the list). No
                // pair-cache hit follows: these worlds' bodies are enabled, which the cache skips.
                for (std::size_t i = 0; i < w.bodies.size(); ++i) setState(w.bodies[i], sampled[s][i]);
                dRandSetSeed(static_cast<unsigned long>(seed * 1000 + static_cast<int>(s)));
                collideAll(w, contenders[c]);
                stepWorld(w, stepper, options);
                dJointGroupEmpty(w.contacts);
                for (std::size_t i = 0; i < w.bodies.size(); ++i) setState(w.bodies[i], sampled[s][i]);
                dRandSetSeed(static_cast<unsigned long>(seed * 1000 + static_cast<int>(s)));
                const auto t0 = Clock::now();
                made[c] = collideAll(w, contenders[c]);
                const auto t1 = Clock::now();
                stepWorld(w, stepper, options);
                const auto t2 = Clock::now();
                dJointGroupEmpty(w.contacts);
                bestCollision[c] = std::min(bestCollision[c], ms(t1 - t0));
                bestSolver[c] = std::min(bestSolver[c], ms(t2 - t1));
            }
        }
        for (std::size_t c = 0; c < contenders.size(); ++c) {
            results[c].collisionMs += bestCollision[c];
            results[c].solverMs += bestSolver[c];
            results[c].contacts += made[c];
            ++results[c].states;
        }
    }
    for (CostResult& r : results) {
        if (r.states == 0) continue;
        r.collisionMs /= r.states;
        r.solverMs /= r.states;
        r.contacts /= r.states;
    }
    return results;
}

namespace {
/// The order dWorldQuickStep meets the joints of `bodies` in (ODE 0.16's dxProcessIslands): the
/// world's body list newest first, depth first, each body's joints newest first (dBodyGetJoint 0).
std::vector<dJointID> solverJointOrder(const std::vector<dBodyID>& bodies) {
    std::vector<dJointID> order;
    std::unordered_map<dBodyID, bool> seenBody;
    std::unordered_map<dJointID, bool> seenJoint;
    for (auto it = bodies.rbegin(); it != bodies.rend(); ++it) {
        if (seenBody[*it] || !dBodyIsEnabled(*it)) continue;
        std::vector<dBodyID> stack{*it};
        seenBody[*it] = true;
        while (!stack.empty()) {
            dBodyID b = stack.back();
            stack.pop_back();
            for (int j = 0; j < dBodyGetNumJoints(b); ++j) {
                dJointID joint = dBodyGetJoint(b, j);
                if (seenJoint[joint] || !dJointIsEnabled(joint)) continue;
                seenJoint[joint] = true;
                order.push_back(joint);
                for (int end = 0; end < 2; ++end) {
                    dBodyID other = dJointGetBody(joint, end);
                    if (other && !seenBody[other]) {
                        seenBody[other] = true;
                        stack.push_back(other);
                    }
                }
            }
        }
    }
    return order;
}
}  // namespace

void compareContacts(const SceneSpec& spec, const Stepper& stepper, const std::vector<Contender>& contenders,
                     const Contender& reference, int seed, double time, const RunOptions& options, std::FILE* out) {
    // The reference run to `time`, its state then copied into every contender's world.
    std::vector<BodyState> state;
    {
        auto w = makeWorld(spec, stepper, reference.kind, seed, false, options.jitterScale * spec.jitterScale);
        dRandSetSeed(static_cast<unsigned long>(seed));
        const int steps = static_cast<int>(std::lround(time / SolverConstants::dt));
        for (int step = 0; step < steps; ++step) {
            releaseBodies(*w, spec, step * SolverConstants::dt);
            collideAll(*w, reference);
            stepWorld(*w, stepper, options);
            dJointGroupEmpty(w->contacts);
        }
        for (dBodyID body : w->bodies) state.push_back(stateOf(body));
    }
    std::fprintf(out, "contender,met,body1,body2,pair_row,pos_x,pos_y,pos_z,depth,normal_x,normal_y,normal_z,fdir1_x,fdir1_y,fdir1_z\n");
    for (const Contender& c : contenders) {
        auto w = makeWorld(spec, stepper, c.kind, seed, false, options.jitterScale * spec.jitterScale);
        for (std::size_t i = 0; i < w->bodies.size(); ++i) setState(w->bodies[i], state[i]);
        std::unordered_map<dBodyID, int> index;
        for (std::size_t i = 0; i < w->bodies.size(); ++i) index[w->bodies[i]] = static_cast<int>(i);
        w->record = true;
        collideAll(*w, c);
        std::unordered_map<dJointID, dContactGeom> geomOf(w->recorded.begin(), w->recorded.end());
        std::map<std::pair<int, int>, int> rowOfPair;
        int met = 0;
        for (dJointID joint : solverJointOrder(w->bodies)) {
            const auto found = geomOf.find(joint);
            if (found == geomOf.end()) continue;
            const dContactGeom& g = found->second;
            dBodyID b1 = dJointGetBody(joint, 0), b2 = dJointGetBody(joint, 1);
            const int i1 = b1 ? index[b1] : -1, i2 = b2 ? index[b2] : -1;
            // ODE's friction directions for a contact without dContactFDir1 (dContactApprox1 here).
            dVector3 t1, t2;
            dPlaneSpace(g.normal, t1, t2);
            std::fprintf(out, "%s,%d,%d,%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", c.name.c_str(), met++, i1, i2,
                         rowOfPair[{i1, i2}]++, g.pos[0], g.pos[1], g.pos[2], g.depth, g.normal[0], g.normal[1], g.normal[2],
                         t1[0], t1[1], t1[2]);
        }
        dJointGroupEmpty(w->contacts);
    }
}

void rootIslandsAtLowest(const std::vector<dBodyID>& bodies) {
    const std::size_t n = bodies.size();
    std::unordered_map<dBodyID, std::size_t> indexOf;
    for (std::size_t i = 0; i < n; ++i) indexOf[bodies[i]] = i;
    std::vector<char> seen(n, 0);
    std::vector<std::size_t> group, stack;
    for (std::size_t start = 0; start < n; ++start) {
        if (seen[start]) continue;
        group.clear();
        stack.assign(1, start);
        seen[start] = 1;
        while (!stack.empty()) {
            const std::size_t b = stack.back();
            stack.pop_back();
            group.push_back(b);
            const int joints = dBodyGetNumJoints(bodies[b]);
            for (int j = 0; j < joints; ++j) {
                dJointID joint = dBodyGetJoint(bodies[b], j);
                if (!dJointIsEnabled(joint)) continue;
                for (int end = 0; end < 2; ++end) {
                    const auto other = indexOf.find(dJointGetBody(joint, end));
                    if (other == indexOf.end() || seen[other->second]) continue;
                    seen[other->second] = 1;
                    stack.push_back(other->second);
                }
            }
        }
        std::size_t root = n;
        for (std::size_t b : group)
            if (dBodyIsEnabled(bodies[b]) && (root == n || dBodyGetPosition(bodies[b])[2] < dBodyGetPosition(bodies[root])[2]))
                root = b;
        if (root == n) continue;
        for (std::size_t b : group)
            if (b != root && dBodyIsEnabled(bodies[b])) dBodyDisable(bodies[b]);
    }
}

}  // namespace gdc::solver_seeds
