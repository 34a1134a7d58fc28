// viewer — interactive (or headless) view of the paper's scenes.
//   viewer [--scene NAME] [--method gdc|tracking|ode] [--side-by-side [--compare M]] [--convex] [--size WxH]
//          [--frames N [--screenshot FILE.png [--fit]] [--realtime]] [--no-panel] [--no-contacts]
//          [--contacts-through] [--no-labels] [--scripted] [--obj FILE.obj [--obj-hull] [--obj-scale S]]
//          [--frames N --record-every K --record-dir DIR]
#include "recorder.hpp"
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
    const auto names = gdc::scenes::allSceneNames();
    for (std::size_t i = 0; i < names.size(); ++i) std::fprintf(out, "%s%s", i ? ", " : "", names[i].c_str());
    std::fprintf(out,
                 ")\n"
                 "  --method M          contacts by gdc | tracking | ode (the left view side by side)\n"
                 "  --side-by-side      the same scene in a second world beside the first, same actions\n"
                 "  --compare M         the second world's contacts: ode (default) | tracking | gdc\n"
                 "  --convex            box-shaped bodies as dConvex instead of ODE's dBox\n"
                 "  --size WxH          window size in pixels (default 1280x720)\n"
                 "  --frames N          draw N frames and exit (each advances 1/60 s of simulated time)\n"
                 "  --realtime          with --frames: advance by wall-clock time, no vsync; prints the fps\n"
                 "  --screenshot FILE   with --frames: write the last frame as PNG\n"
                 "  --no-panel          hide the control panel\n"
                 "  --no-contacts       hide the contact overlay\n"
                 "  --contacts-through  draw contacts over the bodies in front of them (default: hidden there)\n"
                 "  --no-labels         no method, verdict or contact legend over the picture\n"
                 "  --scripted          let the scene's scripted user act (builder, remover, push)\n"
                 "  --fit               with --screenshot: frame the bodies where they are at the end\n"
                 "  --hidden            do not show the window\n"
                 "  --record-every K    with --frames: write every K-th frame (and the last) as PNG\n"
                 "  --record-dir DIR    with --record-every: the frames' folder (frame_0000.png, ...)\n"
                 "  --obj FILE          a shape of your own for d (drop) and t (throw): each object of the\n"
                 "                      OBJ file one convex part (V-HACD/CoACD output), or with --obj-hull\n"
                 "                      the hull of the whole file; --obj-scale S multiplies its coordinates\n"
                 "\n"
                 "mouse: left-drag a body to pull it; ctrl/shift+click removes a brick or an added body;\n"
                 "shift+right-drag throws by flick; left/right-drag elsewhere orbits, middle-drag pans,\n"
                 "wheel zooms. keys: space pause, s step, r reset, p push, c contacts, x contacts through\n"
                 "bodies, v side by side, g dBox/dConvex, f fit view, h hide panel, esc quit;\n"
                 "d drop at the cursor, t throw from the camera, 1-6 box / rock / composite / OBJ / cylinder /\n"
                 "capsule, i inspector, w wireframe, b bounding boxes (side by side, added bodies go to both\n"
                 "worlds)\n");
}

}  // namespace

int main(int argc, char** argv) {
    gdc::viewer::ViewerOptions options;
    gdc::viewer::RecordOptions recording;
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
            } else if (arg == "--compare") {
                const std::string name = value();
                const auto method = gdc::scenes::parseMethod(name);
                if (!method) throw std::invalid_argument("unknown method '" + name + "' (gdc, tracking, ode)");
                options.compareMethod = *method;
                options.sideBySide = true;
            } else if (arg == "--side-by-side") options.sideBySide = true;
            else if (arg == "--convex") options.convexBoxes = true;
            else if (arg == "--contacts-through") options.contactsThrough = true;
            else if (arg == "--no-labels") options.labels = false;
            else if (arg == "--size") {
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
            else if (arg == "--record-dir") recording.directory = value();
            else if (arg == "--record-every") {
                const std::string n = value();
                char* end = nullptr;
                recording.every = int(std::strtol(n.c_str(), &end, 10));
                if (*end != '\0' || recording.every <= 0) throw std::invalid_argument("--record-every wants a positive count, got '" + n + "'");
            }
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
        if (recording.every > 0 && (options.frames <= 0 || recording.directory.empty() || options.realtime ||
                                    !options.screenshot.empty()))
            throw std::invalid_argument("--record-every needs --frames N and --record-dir DIR, without --realtime or --screenshot");
        if (recording.every == 0 && !recording.directory.empty())
            throw std::invalid_argument("--record-dir needs --record-every K");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "viewer: %s\n", e.what());
        usage(stderr);
        return 2;
    }

    dInitODE2(0);
    int status = 0;
    try {
        gdc::viewer::Viewer viewer(options);
        if (recording.every > 0) {
            const int written = gdc::viewer::record(viewer, options.frames, recording);
            std::printf("scene %s: %d frames recorded in %s\n", options.scene.c_str(), written, recording.directory.c_str());
        } else {
            status = viewer.run();
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "viewer: %s\n", e.what());
        status = 1;
    }
    dCloseODE();
    return status;
}
