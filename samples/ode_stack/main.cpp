// The 10-high cube stack with and without gdcontact: drift and twist after 20 s, one line per
// collider and solver. Usage: ode_stack [seconds]
#include "stack_scene.hpp"

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    using namespace gdc::ode::scenes;
    StackOptions options;
    if (argc > 1) options.seconds = std::atof(argv[1]);
    struct Row { StackCollider collider; const char* name; };
    const Row rows[] = {{StackCollider::OdeBoxes, "dBox + ODE dBoxBox"},
                        {StackCollider::OdeConvex, "createConvex + ODE convex (libccd)"},
                        {StackCollider::Gdcontact, "createConvex + gdcontact"}};
    std::printf("%d-high stack of unit cubes, %.0f s at dt %.2f s, ERP 0.2, CFM 1e-5, mu 0.8, %d contacts per pair; drift, twist, sag since t = %.0f s\n",
                options.height, options.seconds, options.timeStep, options.contactsPerPair, options.settleSeconds);
    for (Solver solver : {Solver::Step, Solver::QuickStep})
        for (const Row& row : rows) {
            const StackResult result = runStack(row.collider, solver, options);
            std::printf("%-36s %-22s drift %10.3g mm  twist %8.3g deg  sag %8.3g mm  %s\n", row.name,
                        solver == Solver::Step ? "dWorldStep" : "dWorldQuickStep(20 it)", result.driftMm,
                        result.twistDeg, result.sagMm, result.standing ? "standing" : "FELL");
            std::fflush(stdout);
        }
    return 0;
}
