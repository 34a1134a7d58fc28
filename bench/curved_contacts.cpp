// The contacts of one cycled pose of every curved case (curved_cases.cpp): count, the normals'
// tilt from up and the depths from ODE's own collider, from gdcontact through the ODE adapter and
// from the core, so that an obviously wrong answer shows beside the instruction counts.
//   bench_curved_contacts [POSE-INDEX]
#include "ode_shapes.hpp"
#include "pair_cases.hpp"

#include <iostream>
#include <string>

int main(int argc, char** argv) {
    using namespace gdcbench;
    OdeSession ode;
    printCurvedContacts(std::cout, argc > 1 ? std::stoi(argv[1]) : 0);
    return 0;
}
