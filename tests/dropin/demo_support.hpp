// What the drop-in programs share: a contact audit in the near callback (every contact ODE gets
// must have a unit, finite normal, a finite position and depth ≥ 0), dMessage capture, and
// convex data as ODE users write it (printed with 6 decimals, planes as they come).
#pragma once

#include <ode/ode.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

namespace dropin {

struct Audit {
    long contacts = 0;
    long invalid = 0;
    long steps = 0;
    std::string firstInvalid;

    void check(const dContactGeom& c) {
        ++contacts;
        const double length = std::sqrt(c.normal[0] * c.normal[0] + c.normal[1] * c.normal[1] + c.normal[2] * c.normal[2]);
        const bool ok = std::isfinite(length) && std::abs(length - 1.0) < 1e-6 && std::isfinite(c.pos[0]) &&
                        std::isfinite(c.pos[1]) && std::isfinite(c.pos[2]) && std::isfinite(c.depth) && c.depth >= 0;
        if (!ok && invalid++ == 0) {
            char text[256];
            std::snprintf(text, sizeof text, "classes %d/%d normal (%g %g %g) depth %g", dGeomGetClass(c.g1),
                          dGeomGetClass(c.g2), c.normal[0], c.normal[1], c.normal[2], c.depth);
            firstInvalid = text;
        }
    }
};

/// dMessage text, one line per message (the handler is C: a process-wide string).
inline std::string& messages() {
    static std::string text;
    return text;
}
inline void captureMessage(int, const char* format, va_list arguments) {
    char buffer[4096];
    std::vsnprintf(buffer, sizeof buffer, format, arguments);
    messages() += buffer;
    messages() += '\n';
}
inline int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

/// A convex in dCreateConvex's layout, kept alive as long as the geoms made from it (ODE keeps
/// pointers to the caller's arrays).
struct ConvexData {
    std::vector<dReal> planes;
    std::vector<dReal> points;
    std::vector<unsigned> polygons;
    unsigned planeCount() const { return static_cast<unsigned>(planes.size() / 4); }
    unsigned pointCount() const { return static_cast<unsigned>(points.size() / 3); }
};

/// ODE's demo convex (demo_convex.cpp's layout): a 0.25 cube, written as an ODE user would.
inline ConvexData demoCube() {
    return {{1.0f, 0.0f, 0.0f, 0.25f, 0.0f, 1.0f, 0.0f, 0.25f, 0.0f, 0.0f, 1.0f, 0.25f,
             -1.0f, 0.0f, 0.0f, 0.25f, 0.0f, -1.0f, 0.0f, 0.25f, 0.0f, 0.0f, -1.0f, 0.25f},
            {0.25f, 0.25f, 0.25f, -0.25f, 0.25f, 0.25f, 0.25f, -0.25f, 0.25f, -0.25f, -0.25f, 0.25f,
             0.25f, 0.25f, -0.25f, -0.25f, 0.25f, -0.25f, 0.25f, -0.25f, -0.25f, -0.25f, -0.25f, -0.25f},
            {4, 0, 2, 6, 4, 4, 1, 0, 4, 5, 4, 0, 1, 3, 2, 4, 3, 1, 5, 7, 4, 2, 3, 7, 6, 4, 5, 4, 6, 7}};
}

/// A regular icosahedron of circumradius `radius`, every number printed with 6 decimals, its
/// planes written with the normal pointing inwards (n·x = −d) when `inwards` — data ODE runs.
ConvexData roundedIcosahedron(double radius, bool inwards);

/// A hexagonal prism (radius r, half height h) printed with 6 decimals, the planes listed in
/// another order than the polygons — data ODE runs.
ConvexData roundedPrismShuffled(double r, double h);

}  // namespace dropin
