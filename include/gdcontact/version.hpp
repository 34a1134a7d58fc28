// The version of gdcontact these headers belong to. The same numbers as CMake's project(VERSION)
// (the build checks that they agree), the installed gdcontact.pc and the Debian package.
// Plain macros, usable from C too.
#pragma once

#define GDCONTACT_VERSION_MAJOR 0
#define GDCONTACT_VERSION_MINOR 1
#define GDCONTACT_VERSION_PATCH 0
#define GDCONTACT_VERSION_STRING "0.1.0"
/// One number for comparisons: major·10000 + minor·100 + patch (0.1.0 → 100).
#define GDCONTACT_VERSION (GDCONTACT_VERSION_MAJOR * 10000 + GDCONTACT_VERSION_MINOR * 100 + GDCONTACT_VERSION_PATCH)
