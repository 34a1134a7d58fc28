// One headless program per scene (the scene's name is compiled in as GDC_SCENE_NAME):
//   box_drop --method gdc|tracking|ode [--steps N] [--dt S] [--stepper world|quick] [--iterations N]
//            [--erp X] [--cfm X] [--mu X] [--contacts N] [--surface-layer M] [--convex] [--no-script]
//            [--csv FILE] [--summary FILE] [--bodies N (big_world)] [--threads N (big_world)]
//            [--body-pair-contacts N (gdc)]
// Prints one line: the quality measures after rest (max/mean), timings, and the scene's verdict.
#include "scene.hpp"

#include <gdcontact/ode.hpp>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef GDC_SCENE_NAME
#error "GDC_SCENE_NAME must name the scene"
#endif

namespace {

using gdc::scenes::SolverSettings;

void usage(std::ostream& out) {
    out << "usage: " << GDC_SCENE_NAME
        << " [--method gdc|tracking|ode] [--steps N] [--dt S] [--stepper world|quick] [--iterations N]\n"
           "       [--erp X] [--cfm X] [--mu X] [--contacts N] [--surface-layer M] [--convex] [--no-script]\n"
           "       [--csv FILE] [--summary FILE] [--bodies N] [--threads N] [--body-pair-contacts N]\n"
           "  --method     contact generation: gdc (gdcontact), tracking (persistent manifold), ode (ODE's own)\n"
           "  --steps      number of steps (default: the scene's full duration)\n"
           "  --convex     box-shaped bodies as dConvex instead of dBox\n"
           "  --no-script  no scripted user (no builder, remover or push)\n"
           "  --bodies     big_world: number of bodies (default 2000)\n"
           "  --threads    big_world: gdc::ode::setThreadCount (default 0, one per hardware thread)\n"
           "  --body-pair-contacts  gdc: Settings::maxBodyPairContacts (0: off; default 4)\n"
           "  --csv        per-step measures; --summary: the summary as JSON\n"
           "ODE's messages (dMessage, e.g. \"LCP internal error\") are printed to stderr and counted.\n";
}

double parseNumber(const std::string& option, const char* text) {
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    if (end == text || *end != '\0') throw std::invalid_argument(option + " needs a number, got '" + text + "'");
    return value;
}

std::string jsonString(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

}  // namespace

int main(int argc, char** argv) {
    gdc::scenes::SceneOptions options;
    // Solver options change the scene's own settings one field at a time, after it is made.
    std::vector<std::function<void(SolverSettings&)>> solverChanges;
    std::string csvPath, summaryPath;
    long steps = -1;
    int threads = 0;
    int bodyPairContacts = -1;  // -1: the scene's own settings
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string option = argv[i];
            auto value = [&]() -> const char* {
                if (i + 1 >= argc) throw std::invalid_argument(option + " needs a value");
                return argv[++i];
            };
            if (option == "--help" || option == "-h") {
                usage(std::cout);
                return 0;
            } else if (option == "--method") {
                const std::string name = value();
                const auto method = gdc::scenes::parseMethod(name);
                if (!method) throw std::invalid_argument("unknown method '" + name + "' (gdc, tracking, ode)");
                options.method = *method;
            } else if (option == "--steps") {
                steps = static_cast<long>(parseNumber(option, value()));
                if (steps < 1) throw std::invalid_argument("--steps must be at least 1");
            } else if (option == "--dt") {
                const double dt = parseNumber(option, value());
                solverChanges.push_back([dt](SolverSettings& solver) { solver.dt = dt; });
            } else if (option == "--stepper") {
                const std::string name = value();
                SolverSettings::Stepper stepper;
                if (name == "world") stepper = SolverSettings::Stepper::World;
                else if (name == "quick") stepper = SolverSettings::Stepper::Quick;
                else throw std::invalid_argument("unknown stepper '" + name + "' (world, quick)");
                solverChanges.push_back([stepper](SolverSettings& solver) { solver.stepper = stepper; });
            } else if (option == "--iterations") {
                const int n = static_cast<int>(parseNumber(option, value()));
                solverChanges.push_back([n](SolverSettings& solver) { solver.iterations = n; });
            } else if (option == "--erp") {
                const double x = parseNumber(option, value());
                solverChanges.push_back([x](SolverSettings& solver) { solver.erp = x; });
            } else if (option == "--cfm") {
                const double x = parseNumber(option, value());
                solverChanges.push_back([x](SolverSettings& solver) { solver.cfm = x; });
            } else if (option == "--mu") {
                const double x = parseNumber(option, value());
                solverChanges.push_back([x](SolverSettings& solver) { solver.mu = x; });
            } else if (option == "--contacts") {
                const int n = static_cast<int>(parseNumber(option, value()));
                solverChanges.push_back([n](SolverSettings& solver) { solver.maxContactsPerPair = n; });
            } else if (option == "--surface-layer") {
                const double x = parseNumber(option, value());
                solverChanges.push_back([x](SolverSettings& solver) { solver.surfaceLayer = x; });
            } else if (option == "--bodies") {
                const double n = parseNumber(option, value());
                if (!(n >= 1 && n <= 1e6)) throw std::invalid_argument("--bodies must be in 1..1000000");
                options.bodies = static_cast<int>(n);
            } else if (option == "--threads") {
                const double n = parseNumber(option, value());
                if (!(n >= 0 && n <= 256)) throw std::invalid_argument("--threads must be in 0..256");
                threads = static_cast<int>(n);
            } else if (option == "--body-pair-contacts") {
                const double n = parseNumber(option, value());
                if (!(n >= 0 && n <= 16)) throw std::invalid_argument("--body-pair-contacts must be in 0..16");
                bodyPairContacts = static_cast<int>(n);
            } else if (option == "--convex") {
                options.convexBoxes = true;
            } else if (option == "--no-script") {
                options.scripted = false;
            } else if (option == "--csv") {
                csvPath = value();
            } else if (option == "--summary") {
                summaryPath = value();
            } else {
                throw std::invalid_argument("unknown option '" + option + "'");
            }
        }
    } catch (const std::exception& error) {
        std::cerr << GDC_SCENE_NAME << ": " << error.what() << "\n";
        usage(std::cerr);
        return 2;
    }

    dInitODE2(0);
    // ODE's messages (its Dantzig LCP's "LCP internal error" among them) still reach stderr, and are
    // counted for the summary.
    static int odeMessages = 0;
    dSetMessageHandler([](int number, const char* message, va_list arguments) {
        ++odeMessages;
        std::fprintf(stderr, "ODE Message %d: ", number);
        std::vfprintf(stderr, message, arguments);
        std::fprintf(stderr, "\n");
    });
    int status = 0;
    try {
        gdc::ode::setThreadCount(threads);
        auto scene = gdc::scenes::makeScene(GDC_SCENE_NAME, options);
        SolverSettings settings = scene->solver();
        for (const auto& change : solverChanges) change(settings);
        scene->setSolver(settings);  // throws for out-of-range values
        if (bodyPairContacts >= 0) {
            gdc::Settings contactSettings = scene->contactSettings();
            contactSettings.maxBodyPairContacts = bodyPairContacts;
            scene->setContactSettings(contactSettings);
            // big_world's whole-step collision (spaceCollide) uses install()'s settings; installing
            // is harmless for the gdc method (it calls gdcontact directly) and would reroute the others.
            if (options.method == gdc::scenes::Method::Gdcontact) gdc::ode::install(contactSettings);
        }
        const SolverSettings& used = scene->solver();
        if (steps < 0) steps = static_cast<long>(scene->duration() / used.dt + 0.5);
        for (long i = 0; i < steps && !scene->exploded(); ++i) scene->step();

        const gdc::scenes::Summary s = scene->summary();
        double contactsPerStep = 0.0;
        for (const gdc::scenes::Measures& m : scene->history()) contactsPerStep += m.contacts;
        if (!scene->history().empty()) contactsPerStep /= static_cast<double>(scene->history().size());
        const gdc::scenes::Outcome outcome = scene->outcome();
        const char* method = gdc::scenes::methodName(scene->method());
        const char* shapes = options.convexBoxes ? "convex" : "box";
        std::printf("%s method=%s boxes=%s stepper=%s iterations=%d dt=%g steps=%ld | after rest (%d steps): "
                    "penetration max %.3g mean %.3g m, contact depth max %.3g m, alignment max %.3g mean %.3g rad, "
                    "drift %.3g m, twist %.3g rad, sag %.3g m, oscillation %.3g m/s | collision %.3g ms, "
                    "solver %.3g ms per step, %.1f contacts per step, %d ODE messages | %s: %s\n",
                    scene->name().c_str(), method, shapes, gdc::scenes::stepperName(used.stepper), used.iterations,
                    used.dt, static_cast<long>(scene->stepCount()), s.samples, s.maxPenetration, s.meanPenetration,
                    s.maxContactPenetration, s.maxAlignment, s.meanAlignment, s.maxDrift, s.maxTwist, s.maxSag,
                    s.oscillation, 1e3 * s.meanCollisionSeconds, 1e3 * s.meanSolverSeconds, contactsPerStep,
                    odeMessages, outcome.success ? "PASS" : "FAIL", outcome.text.c_str());
        if (!csvPath.empty()) scene->writeCsv(csvPath);
        if (!summaryPath.empty()) {
            std::ofstream json(summaryPath);
            if (!json) throw std::runtime_error("cannot write " + summaryPath);
            json.precision(9);
            json << "{\"scene\": " << jsonString(scene->name()) << ", \"method\": " << jsonString(method)
                 << ", \"boxes\": " << jsonString(shapes) << ", \"stepper\": "
                 << jsonString(gdc::scenes::stepperName(used.stepper)) << ", \"iterations\": " << used.iterations
                 << ", \"dt\": " << used.dt << ", \"steps\": " << scene->stepCount()
                 << ", \"exploded\": " << (scene->exploded() ? "true" : "false") << ", \"samples\": " << s.samples
                 << ", \"max_penetration\": " << s.maxPenetration << ", \"mean_penetration\": " << s.meanPenetration
                 << ", \"max_contact_penetration\": " << s.maxContactPenetration
                 << ", \"max_alignment\": " << s.maxAlignment << ", \"mean_alignment\": " << s.meanAlignment
                 << ", \"max_drift\": " << s.maxDrift << ", \"max_twist\": " << s.maxTwist
                 << ", \"max_sag\": " << s.maxSag << ", \"oscillation\": " << s.oscillation
                 << ", \"collision_ms\": " << 1e3 * s.meanCollisionSeconds
                 << ", \"solver_ms\": " << 1e3 * s.meanSolverSeconds
                 << ", \"contacts_per_step\": " << contactsPerStep << ", \"ode_messages\": " << odeMessages
                 << ", \"success\": " << (outcome.success ? "true" : "false")
                 << ", \"outcome\": " << jsonString(outcome.text) << ", \"values\": {";
            for (std::size_t i = 0; i < outcome.values.size(); ++i)
                json << (i ? ", " : "") << jsonString(outcome.values[i].first) << ": " << outcome.values[i].second;
            json << "}}\n";
        }
    } catch (const std::exception& error) {
        std::cerr << GDC_SCENE_NAME << ": " << error.what() << "\n";
        status = 1;
    }
    dCloseODE();
    return status;
}
