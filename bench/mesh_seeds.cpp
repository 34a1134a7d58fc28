// Bodies on triangle meshes over many seeds (issue 34, item 5), gdcontact against ODE's own
// colliders in the same worlds: each seed sets dRandSetSeed (QuickStep's row order) and jitters the
// start poses with dRand, the same for both contenders, and a scene fails by a fine and a gross
// criterion; the fails are paired by seed (a two-sided sign test on the seeds where exactly one
// contender fails).
//   rest  — 6 rocks (random hulls) and 4 boxes dropped 1 cm onto a flat floor of 512 triangles
//           (16 × 16 cells of 25 cm). From 2 s to 5 s: fine, a body moves more than 1 mm or is
//           still faster than 5 mm/s at the end; gross, a body moves more than 5 cm.
//   slide — a frictionless box (60 × 40 × 30 cm) pushed at 1–2 m/s in a random heading across the
//           seams of a floor like rest's, 8 m wide (2048 triangles), for 2 s. After 0.2 s: fine, a vertical speed above 1 cm/s or a turn
//           above 1°; gross, a turn above 10° or a hop of 1 cm.
//   pile  — 16 rocks dropped in a staggered column onto a bumpy terrain (sines of 10 cm in a
//           shallow bowl, 3200 triangles). From 4 s to 6 s: fine, a rock moves more than 5 mm; gross, more than 10 cm
//           or below the terrain.
// Under dWorldQuickStep (20 iterations) and dWorldStep, dt 0.01, ODE's contact mode dContactApprox1.
//   bench_mesh_seeds [--seeds N]
#include <gdcontact/ode.hpp>
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace {

constexpr double kDt = 0.01;

struct Terrain {
    std::vector<dReal> vertices;
    std::vector<dTriIndex> indices;
};

// n × n cells of `cell` about the origin, heights from `height(x, y)`, two triangles a cell, front up.
Terrain grid(int n, double cell, const std::function<double(double, double)>& height) {
    Terrain t;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = (i - n / 2.0) * cell, y = (j - n / 2.0) * cell;
            t.vertices.insert(t.vertices.end(), {x, y, height(x, y)});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const dTriIndex a = static_cast<dTriIndex>(j * (n + 1) + i), b = a + 1, c = static_cast<dTriIndex>(a + n + 1),
                            d = c + 1;
            t.indices.insert(t.indices.end(), {a, b, d, a, d, c});
        }
    return t;
}

double jitter(double scale) { return scale * (2 * dRandReal() - 1); }

// One world of one contender: the terrain, the bodies, the contacts of one step.
struct World {
    dWorldID world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(nullptr);
    dJointGroupID contacts = dJointGroupCreate(0);
    dTriMeshDataID data = dGeomTriMeshDataCreate();
    Terrain terrain;
    std::vector<dBodyID> bodies;
    std::vector<std::vector<dReal>> hullPoints;  // kept alive for the convex geoms
    bool gdcontact = false;
    double mu = 0.8;

    // `onPlane`: a dPlane at z = 0 instead of the mesh (the reference for a flat mesh: a body on it
    // should do what it does on the plane).
    World(Terrain t, bool useGdcontact, bool onPlane = false) : terrain(std::move(t)), gdcontact(useGdcontact) {
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetQuickStepNumIterations(world, 20);
        dGeomTriMeshDataBuildDouble(data, terrain.vertices.data(), 3 * sizeof(dReal),
                                    static_cast<int>(terrain.vertices.size() / 3), terrain.indices.data(),
                                    static_cast<int>(terrain.indices.size()), 3 * sizeof(dTriIndex));
        // ODE's own convex–trimesh stops with an internal error without the face angles.
        dGeomTriMeshDataPreprocess2(data, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
        if (onPlane) dCreatePlane(space, 0, 0, 1, 0);
        else dCreateTriMesh(space, data, nullptr, nullptr, nullptr);
    }
    ~World() {
        dJointGroupDestroy(contacts);
        dSpaceDestroy(space);  // destroys the geoms
        dGeomTriMeshDataDestroy(data);
        dWorldDestroy(world);
    }
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    dBodyID addBox(double x, double y, double z, double yaw, const double (&size)[3], double density) {
        dBodyID body = dBodyCreate(world);
        dMass mass;
        dMassSetBox(&mass, density, size[0], size[1], size[2]);
        dBodySetMass(body, &mass);
        dGeomSetBody(dCreateBox(space, size[0], size[1], size[2]), body);
        place(body, x, y, z, yaw);
        return body;
    }
    // A rock: a hull of 10 points on an ellipsoid of radii 0.15 × 0.12 × 0.09 m (dRand's) and the
    // ellipsoid's six vertices at 0.8 of its radii, so that the body's origin is inside (ODE's
    // convex geom needs it).
    dBodyID addRock(double x, double y, double z) {
        std::vector<dReal> points;
        for (int axis = 0; axis < 6; ++axis) {
            double p[3] = {0, 0, 0};
            const double radii[3] = {0.15, 0.12, 0.09};
            p[axis / 2] = (axis % 2 ? -0.8 : 0.8) * radii[axis / 2];
            points.insert(points.end(), {p[0], p[1], p[2]});
        }
        for (int i = 0; i < 10; ++i) {
            const double u = 2 * M_PI * dRandReal(), v = std::acos(2 * dRandReal() - 1);
            points.insert(points.end(), {0.15 * std::sin(v) * std::cos(u), 0.12 * std::sin(v) * std::sin(u), 0.09 * std::cos(v)});
        }
        hullPoints.push_back(points);
        dGeomID geom = gdc::ode::createConvex(space, hullPoints.back().data(), 16);
        dBodyID body = dBodyCreate(world);
        dMass mass;
        dMassSetSphereTotal(&mass, 3.0, 0.12);
        dBodySetMass(body, &mass);
        dGeomSetBody(geom, body);
        place(body, x, y, z, 2 * M_PI * dRandReal());
        return body;
    }
    void place(dBodyID body, double x, double y, double z, double yaw) {
        dMatrix3 r;
        dRFromAxisAndAngle(r, 0, 0, 1, yaw);
        dBodySetRotation(body, r);
        dBodySetPosition(body, x, y, z);
        bodies.push_back(body);
    }

    static void nearCallback(void* self, dGeomID g1, dGeomID g2) {
        World& w = *static_cast<World*>(self);
        dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
        if (!b1 && !b2) return;
        dContactGeom geoms[16];
        const int count = w.gdcontact ? gdc::ode::collide(g1, g2, 16, geoms, sizeof(dContactGeom))
                                      : dCollide(g1, g2, 16, geoms, sizeof(dContactGeom));
        for (int i = 0; i < count; ++i) {
            dContact contact{};
            contact.surface.mode = dContactApprox1;
            contact.surface.mu = w.mu;
            contact.geom = geoms[i];
            dJointAttach(dJointCreateContact(w.world, w.contacts, &contact), b1, b2);
        }
    }
    void step(bool quick) {
        dSpaceCollide(space, this, &nearCallback);
        quick ? dWorldQuickStep(world, kDt) : dWorldStep(world, kDt);
        dJointGroupEmpty(contacts);
    }
    void run(bool quick, double seconds) {
        for (int i = 0, n = static_cast<int>(std::lround(seconds / kDt)); i < n; ++i) step(quick);
    }
};

struct Verdict {
    bool fine = false, gross = false;
    double value = 0;  // the scene's measure (creep or vertical speed), for the medians
};

Verdict moved(World& w, bool quick, double settle, double watch, double fineLimit, double grossLimit, double floorZ) {
    w.run(quick, settle);
    std::vector<std::array<double, 3>> start;
    for (dBodyID b : w.bodies) {
        const dReal* p = dBodyGetPosition(b);
        start.push_back({p[0], p[1], p[2]});
    }
    w.run(quick, watch);
    Verdict v;
    double fastest = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const dReal* p = dBodyGetPosition(w.bodies[i]);
        const double d = std::hypot(p[0] - start[i][0], p[1] - start[i][1], p[2] - start[i][2]);
        v.value = std::max(v.value, d);
        if (p[2] < floorZ) v.gross = true;
        const dReal* s = dBodyGetLinearVel(w.bodies[i]);
        fastest = std::max(fastest, std::hypot(s[0], s[1], s[2]));
    }
    v.fine = v.value > fineLimit || fastest > 5e-3;
    v.gross = v.gross || v.value > grossLimit;
    return v;
}

// The contenders: gdcontact on the mesh, ODE's own colliders on the mesh, gdcontact on a dPlane.
enum Contender { GdcMesh, OdeMesh, GdcPlane };

Verdict rest(Contender contender, bool quick) {
    World w(grid(16, 0.25, [](double, double) { return 0.0; }), contender != OdeMesh, contender == GdcPlane);
    for (int i = 0; i < 6; ++i) w.addRock(-1.2 + 0.8 * (i % 3) + jitter(0.05), -0.6 + 1.2 * (i / 3) + jitter(0.05), 0.16);
    const double size[3] = {0.3, 0.2, 0.15};
    for (int i = 0; i < 4; ++i)
        w.addBox(-0.9 + 0.6 * i + jitter(0.05), jitter(0.05), 0.075 + 0.01, 2 * M_PI * dRandReal(), size, 500);
    return moved(w, quick, 2.0, 3.0, 1e-3, 0.05, -0.05);
}

Verdict slide(Contender contender, bool quick) {
    // 8 m wide: the box never reaches the rim.
    World w(grid(32, 0.25, [](double, double) { return 0.0; }), contender != OdeMesh, contender == GdcPlane);
    w.mu = 0;
    const double size[3] = {0.6, 0.4, 0.3};
    const double heading = 2 * M_PI * dRandReal(), speed = 1 + dRandReal();
    dBodyID box = w.addBox(-std::cos(heading) + jitter(0.1), -std::sin(heading) + jitter(0.1), 0.15, heading, size, 500);
    dBodySetLinearVel(box, speed * std::cos(heading), speed * std::sin(heading), 0);
    w.run(quick, 0.2);
    const dReal* q0 = dBodyGetRotation(box);
    const double yaw0 = std::atan2(q0[4], q0[0]);
    Verdict v;
    double turn = 0, hop = 0;
    for (int i = 0; i < 180; ++i) {
        w.step(quick);
        v.value = std::max(v.value, std::abs(static_cast<double>(dBodyGetLinearVel(box)[2])));
        const dReal* r = dBodyGetRotation(box);
        turn = std::max(turn, std::abs(std::remainder(std::atan2(r[4], r[0]) - yaw0, 2 * M_PI)));
        hop = std::max(hop, dBodyGetPosition(box)[2] - 0.15);
    }
    const double degree = M_PI / 180;
    v.fine = v.value > 0.01 || turn > degree;
    v.gross = turn > 10 * degree || hop > 0.01;
    return v;
}

// Bumps of 10 cm in a shallow bowl (a metre high at 5 m out): no rock leaves the terrain, so a
// gross fail is a rock still moving or through the mesh, not one that rolled off the rim.
double bumps(double x, double y) { return 0.1 * std::sin(2.1 * x) * std::cos(1.7 * y) + 0.04 * (x * x + y * y); }

Verdict pile(Contender contender, bool quick) {
    World w(grid(40, 0.25, bumps), contender != OdeMesh);
    for (int i = 0; i < 16; ++i) w.addRock(jitter(0.3), jitter(0.3), 0.35 + 0.25 * i);
    Verdict v = moved(w, quick, 4.0, 2.0, 5e-3, 0.1, -1.0);
    for (dBodyID b : w.bodies) {  // below the terrain: through it
        const dReal* p = dBodyGetPosition(b);
        if (p[2] < bumps(p[0], p[1]) - 0.1) v.gross = true;
    }
    return v;
}

// Two-sided sign test: the probability of a split at least as uneven as (b, c) under fair coins.
double signTest(int b, int c) {
    const int n = b + c, k = std::min(b, c);
    if (n == 0) return 1.0;
    double sum = 0, term = std::pow(0.5, n);  // C(n, 0) / 2^n
    for (int i = 0; i <= k; ++i) {
        sum += term;
        term = term * (n - i) / (i + 1);
    }
    return std::min(1.0, 2 * sum);
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    int seeds = 50;
    for (int i = 1; i + 1 < argc; ++i)
        if (std::string(argv[i]) == "--seeds") seeds = std::stoi(argv[i + 1]);
    struct Scenario {
        const char* name;
        Verdict (*run)(Contender, bool);
        bool flat;  // a plane is its reference
        const char* measure;
    };
    const Scenario scenarios[] = {{"rest", rest, true, "most motion 2–5 s, m"},
                                  {"slide", slide, true, "largest vertical speed, m/s"},
                                  {"pile", pile, false, "most motion 4–6 s, m"}};
    std::printf("| scene | stepper | seeds | fine fails gdcontact / ODE (plane: gdcontact) | gross fails gdcontact / "
                "ODE (plane) | sign test p gdcontact–ODE (fine, gross) | median measure gdcontact / ODE (plane) |\n");
    std::printf("|---|---|---:|---|---|---|---|\n");
    for (const Scenario& scenario : scenarios)
        for (const bool quick : {true, false}) {
            const int contenders = scenario.flat ? 3 : 2;
            int fine[3] = {0, 0, 0}, gross[3] = {0, 0, 0}, onlyFine[2] = {0, 0}, onlyGross[2] = {0, 0};
            std::vector<double> values[3];
            for (int seed = 0; seed < seeds; ++seed) {
                Verdict verdicts[3];
                for (int c = 0; c < contenders; ++c) {
                    // A fresh ODE session for each run: install() overrides ODE's colliders until
                    // dCloseODE, after which ODE's own table is back (ODE's colliders are set up
                    // again at the next session's first collision).
                    dInitODE2(0);
                    if (c != OdeMesh) gdc::ode::install();
                    dRandSetSeed(static_cast<unsigned long>(seed) + 1);
                    verdicts[c] = scenario.run(static_cast<Contender>(c), quick);
                    dCloseODE();
                    fine[c] += verdicts[c].fine;
                    gross[c] += verdicts[c].gross;
                    values[c].push_back(verdicts[c].value);
                }
                for (int c = 0; c < 2; ++c) {
                    onlyFine[c] += verdicts[c].fine && !verdicts[1 - c].fine;
                    onlyGross[c] += verdicts[c].gross && !verdicts[1 - c].gross;
                }
            }
            auto plane = [&](double x, const char* format) {
                char text[32] = "n/a";
                if (scenario.flat) std::snprintf(text, sizeof text, format, x);
                return std::string(text);
            };
            std::printf("| %s | %s | %d | %d / %d (%s) | %d / %d (%s) | %.3g, %.3g | %.3g / %.3g (%s) (%s) |\n",
                        scenario.name, quick ? "quick20" : "world", seeds, fine[0], fine[1], plane(fine[2], "%.0f").c_str(),
                        gross[0], gross[1], plane(gross[2], "%.0f").c_str(), signTest(onlyFine[0], onlyFine[1]),
                        signTest(onlyGross[0], onlyGross[1]), median(values[0]), median(values[1]),
                        plane(scenario.flat ? median(values[2]) : 0, "%.3g").c_str(), scenario.measure);
            std::fflush(stdout);
        }
    return 0;
}
