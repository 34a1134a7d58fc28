// viewer — interactive (or headless) view of the paper's scenes.
//   viewer [--scene NAME] [--method gdc|tracking|ode] [--size WxH]
//          [--frames N [--screenshot FILE.png [--fit]] [--realtime]] [--no-panel] [--no-contacts] [--scripted]
//          [--obj FILE.obj [--obj-hull] [--obj-scale S]]
#include "viewer.hpp"

#include <ode/ode.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

namespace {

void usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: viewer [options]\n"
                 "  --scene NAME        scene to open (");
    const auto names = gdc::scenes::sceneNames();
    for (std::size_t i = 0; i < names.size(); ++i) std::fprintf(out, "%s%s", i ? ", " : "", names[i].c_str());
    std::fprintf(out,
                 ")\n"
                 "  --method M          contacts by gdc | tracking | ode\n"
                 "  --size WxH          window size in pixels (default 1280x720)\n"
                 "  --frames N          draw N frames and exit (each advances 1/60 s of simulated time)\n"
                 "  --realtime          with --frames: advance by wall-clock time, no vsync; prints the fps\n"
                 "  --screenshot FILE   with --frames: write the last frame as PNG\n"
                 "  --no-panel          hide the control panel\n"
                 "  --no-contacts       hide the contact overlay\n"
                 "  --scripted          let the scene's scripted user act (builder, remover, push)\n"
                 "  --fit               with --screenshot: frame the bodies where they are at the end\n"
                 "  --hidden            do not show the window\n"
                 "  --obj FILE          a shape of your own for d (drop) and t (throw): each object of the\n"
                 "                      OBJ file one convex part (V-HACD/CoACD output), or with --obj-hull\n"
                 "                      the hull of the whole file; --obj-scale S multiplies its coordinates\n"
                 "\n"
                 "mouse: left-drag a body to pull it; ctrl/shift+click removes a brick; left/right-drag\n"
                 "elsewhere orbits, middle-drag pans, wheel zooms. keys: space pause, s step, r reset,\n"
                 "p push, c contacts, f fit view, h hide panel, esc quit;\n"
                 "d drop at the cursor, t throw from the camera (shift+right-drag: throw by flick), 1-4 box /\n"
                 "rock / composite / OBJ, i inspector, w wireframe, b bounding boxes\n");
}

}  // namespace

int main(int argc, char** argv) {
    gdc::viewer::ViewerOptions options;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
                return argv[++i];
            };
            if (arg == "--scene") options.scene = value();
            else if (arg == "--method") {
                const std::string name = value();
                options.method = gdc::scenes::parseMethod(name);
                if (!options.method) throw std::invalid_argument("unknown method '" + name + "' (gdc, tracking, ode)");
            } else if (arg == "--size") {
                const std::string size = value();
                if (std::sscanf(size.c_str(), "%dx%d", &options.width, &options.height) != 2)
                    throw std::invalid_argument("--size wants WxH, got '" + size + "'");
            } else if (arg == "--frames") {
                const std::string n = value();
                char* end = nullptr;
                options.frames = int(std::strtol(n.c_str(), &end, 10));
                if (*end != '\0' || options.frames <= 0) throw std::invalid_argument("--frames wants a positive count, got '" + n + "'");
            } else if (arg == "--screenshot") options.screenshot = value();
            else if (arg == "--realtime") options.realtime = true;
            else if (arg == "--no-panel") options.panel = false;
            else if (arg == "--no-contacts") options.contacts = false;
            else if (arg == "--scripted") options.scripted = true;
            else if (arg == "--hidden") options.visible = false;
            else if (arg == "--fit") options.fit = true;
            else if (arg == "--obj") options.obj = value();
            else if (arg == "--obj-hull") options.objHull = true;
            else if (arg == "--obj-scale") {
                const std::string text = value();
                char* end = nullptr;
                options.objScale = std::strtod(text.c_str(), &end);
                if (*end != '\0' || !(options.objScale > 0.0) || !std::isfinite(options.objScale))
                    throw std::invalid_argument("--obj-scale wants a positive number, got '" + text + "'");
            }
            else if (arg == "--help" || arg == "-h") {
                usage(stdout);
                return 0;
            } else throw std::invalid_argument("unknown option '" + arg + "'");
        }
        if (!options.screenshot.empty() && options.frames <= 0)
            throw std::invalid_argument("--screenshot needs --frames N");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "viewer: %s\n", e.what());
        usage(stderr);
        return 2;
    }

    dInitODE2(0);
    int status = 0;
    try {
        gdc::viewer::Viewer viewer(options);
        status = viewer.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "viewer: %s\n", e.what());
        status = 1;
    }
    dCloseODE();
    return status;
}
