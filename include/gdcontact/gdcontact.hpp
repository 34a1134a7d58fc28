// Umbrella header of the gdcontact core (no ODE). For the ODE drop-in, include <gdcontact/ode.hpp>.
#pragma once

#include <gdcontact/collide.hpp>
#include <gdcontact/manifold.hpp>
#include <gdcontact/polytope.hpp>
#include <gdcontact/settings.hpp>
#include <gdcontact/shapes.hpp>
#include <gdcontact/triangle_mesh.hpp>
#include <gdcontact/types.hpp>
#include <gdcontact/version.hpp>
