// The cost of a body resting on a triangle mesh against the mesh's size (issue 34): a box and an
// 8-vertex hull on flat grids of 2·N² triangles, at cycled jittered poses, ODE's own box–trimesh and
// convex–trimesh (dCollide, no install() in this process), gdcontact through the ODE adapter
// (gdc::ode::collide on the same geoms: the mesh cache's lookup and check, the contacts written as
// ODE's) and gdcontact's core query interleaved pose by pose; the median of each contender's time
// per call over repeated rounds, and the ratios to ODE's. With --csv FILE the rows are also written
// there (`python3 -m gdcreport mesh-cost FILE` plots them: cost against the triangle count).
//   bench_mesh_cost [--csv FILE] [ROUNDS]
#include <gdcontact/gdcontact.hpp>
#include <gdcontact/ode.hpp>
#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Grid {
    std::vector<gdc::Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;
};

// N × N cells of `cell` metres about the origin at z = 0, two triangles each, front up.
Grid grid(int n, double cell) {
    Grid g;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) g.vertices.push_back({(i - n / 2.0) * cell, (j - n / 2.0) * cell, 0});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            g.triangles.push_back({a, b, d});
            g.triangles.push_back({a, d, c});
        }
    return g;
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    int rounds = 15;
    std::FILE* csv = nullptr;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
            csv = std::fopen(argv[++i], "w");
            if (!csv) return std::perror(argv[i]), 2;
        } else {
            rounds = std::stoi(argv[i]);
        }
    }
    if (csv) std::fprintf(csv, "triangles,body,ode_ns,adapter_ns,core_ns,ode_contacts,adapter_contacts,core_contacts\n");
    dInitODE2(0);
    const double cell = 0.5;  // a unit body spans about three cells: 10–20 triangles under it
    const gdc::Vec3 half(0.5, 0.5, 0.5);
    const gdc::Polytope box = gdc::Polytope::box(half);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::vector<gdc::Vec3> hullPoints;
    for (int i = 0; i < 8; ++i) hullPoints.push_back({0.5 * unit(rng), 0.5 * unit(rng), 0.5 * unit(rng)});
    const gdc::Polytope hull = gdc::Polytope::fromPoints(hullPoints);
    std::printf("| triangles | body | ODE (ns/call) | gdcontact adapter (ns/call) | core (ns/call) | ratio to ODE: "
                "adapter / core | contacts ODE / adapter (core) |\n");
    std::printf("|---:|---|---:|---:|---:|---|---|\n");
    for (int n : {4, 8, 16, 32, 64, 128, 256}) {
        const Grid g = grid(n, cell);
        const gdc::TriangleMesh mesh(g.vertices, g.triangles);
        dTriMeshDataID data = dGeomTriMeshDataCreate();
        std::vector<dReal> odeVertices;
        for (const gdc::Vec3& v : g.vertices) odeVertices.insert(odeVertices.end(), {v.x(), v.y(), v.z(), 0});
        std::vector<dTriIndex> odeIndices;
        for (const auto& t : g.triangles) odeIndices.insert(odeIndices.end(), {dTriIndex(t[0]), dTriIndex(t[1]), dTriIndex(t[2])});
        dGeomTriMeshDataBuildDouble(data, odeVertices.data(), 4 * sizeof(dReal), static_cast<int>(g.vertices.size()),
                                    odeIndices.data(), static_cast<int>(odeIndices.size()), 3 * sizeof(dTriIndex));
        // ODE's convex–trimesh needs the face angles (it stops with an internal error without them).
        dGeomTriMeshDataPreprocess2(data, 1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES, nullptr);
        dGeomID floor = dCreateTriMesh(nullptr, data, nullptr, nullptr, nullptr);
        for (int kind = 0; kind < 2; ++kind) {
            const gdc::Polytope& body = kind == 0 ? box : hull;
            dGeomID odeBody = nullptr;
            std::vector<dReal> hullVertices;
            if (kind == 0) {
                odeBody = dCreateBox(nullptr, 1, 1, 1);
            } else {  // a convex geom both ODE and the adapter know (gdc::ode::createConvex)
                for (const gdc::Vec3& v : body.vertices()) hullVertices.insert(hullVertices.end(), {v.x(), v.y(), v.z()});
                odeBody = gdc::ode::createConvex(nullptr, hullVertices.data(), static_cast<unsigned>(body.vertices().size()));
            }
            // 64 cycled poses resting 1–5 mm into the floor, turned about z and tilted a little,
            // within the middle of the grid.
            std::vector<gdc::Pose> poses;
            for (int p = 0; p < 64; ++p) {
                gdc::Pose pose;
                pose.rotation = (Eigen::AngleAxisd(3.14 * unit(rng), gdc::Vec3::UnitZ()) *
                                 Eigen::AngleAxisd(0.02 * unit(rng), gdc::Vec3::UnitX()))
                                    .toRotationMatrix();
                pose.position = {0.8 * unit(rng), 0.8 * unit(rng), 0};
                double lowest = 1e9;
                for (const gdc::Vec3& v : body.vertices()) lowest = std::min(lowest, pose.apply(v).z());
                pose.position.z() = -lowest - 0.003 + 0.002 * unit(rng);
                poses.push_back(pose);
            }
            std::vector<double> odeTimes, adapterTimes, coreTimes;
            std::vector<gdc::MeshContact> contacts;
            dContactGeom odeContacts[64], adapterContacts[64];
            int odeCount = 0, adapterCount = 0, coreCount = 0;
            const gdc::Settings settings;
            for (int round = 0; round < rounds; ++round) {
                double odeTotal = 0, adapterTotal = 0, coreTotal = 0;
                for (const gdc::Pose& pose : poses) {
                    dMatrix3 r;
                    for (int i = 0; i < 3; ++i)
                        for (int j = 0; j < 3; ++j) r[4 * i + j] = pose.rotation(i, j);
                    r[3] = r[7] = r[11] = 0;
                    dGeomSetRotation(odeBody, r);
                    dGeomSetPosition(odeBody, pose.position.x(), pose.position.y(), pose.position.z());
                    const Clock::time_point t0 = Clock::now();
                    odeCount = dCollide(odeBody, floor, 64, odeContacts, sizeof(dContactGeom));
                    const Clock::time_point t1 = Clock::now();
                    adapterCount = gdc::ode::collide(odeBody, floor, 64, adapterContacts, sizeof(dContactGeom), settings);
                    const Clock::time_point t2 = Clock::now();
                    gdc::collide(body, pose, mesh, gdc::Pose{}, settings, contacts);
                    const Clock::time_point t3 = Clock::now();
                    coreCount = static_cast<int>(contacts.size());
                    odeTotal += std::chrono::duration<double, std::nano>(t1 - t0).count();
                    adapterTotal += std::chrono::duration<double, std::nano>(t2 - t1).count();
                    coreTotal += std::chrono::duration<double, std::nano>(t3 - t2).count();
                }
                odeTimes.push_back(odeTotal / poses.size());
                adapterTimes.push_back(adapterTotal / poses.size());
                coreTimes.push_back(coreTotal / poses.size());
            }
            const double odeNs = median(odeTimes), adapterNs = median(adapterTimes), coreNs = median(coreTimes);
            std::printf("| %d | %s | %.0f | %.0f | %.0f | %.2f / %.2f | %d / %d (core %d) |\n", 2 * n * n,
                        kind == 0 ? "box" : "8-vertex hull", odeNs, adapterNs, coreNs, adapterNs / odeNs, coreNs / odeNs,
                        odeCount, adapterCount, coreCount);
            if (csv)
                std::fprintf(csv, "%d,%s,%.1f,%.1f,%.1f,%d,%d,%d\n", 2 * n * n, kind == 0 ? "box" : "hull8", odeNs,
                             adapterNs, coreNs, odeCount, adapterCount, coreCount);
            dGeomDestroy(odeBody);
        }
        dGeomDestroy(floor);
        dGeomTriMeshDataDestroy(data);
    }
    dCloseODE();
    if (csv) std::fclose(csv);
    return 0;
}
