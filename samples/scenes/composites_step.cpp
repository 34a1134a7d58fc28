// The composites scene's whole step (collision + dWorldStep) on identical states, per contender:
//   composites_step [--every N] [--repeats N] [--cfm X]
// A reference run of the scene (gdcontact) is sampled every N steps once every body is released
// (t ≥ 4.1 s, until the end at 9.8 s); each contender's own copy of the scene is given that state
// (every body's pose and velocities) before each timed step, so that every contender steps the
// same bodies in the same places. Contenders: gdcontact with the body-pair budget
// (Settings::maxBodyPairContacts 4), gdcontact without it (0), ODE's own colliders with the parts
// as dBox (dBoxBox, libccd for the gears' convex parts) and with every part a dConvex (libccd).
// Each sample is stepped --repeats times per contender, interleaved; the median is taken per
// sample, the mean over samples printed: contacts, collision ms, dWorldStep ms, whole step ms, its
// ratio to the cheaper ODE option, and ODE's messages ("LCP internal error") during the timed steps.
#include "scene.hpp"

#include <gdcontact/ode.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace gdc::scenes;
using Clock = std::chrono::steady_clock;

int odeMessages = 0;

struct BodyState {
    dReal position[3], quaternion[4], linear[3], angular[3];
};

std::vector<BodyState> stateOf(const Scene& scene) {
    std::vector<BodyState> states;
    for (const Body& body : scene.bodies()) {
        BodyState s;
        const dReal* p = dBodyGetPosition(body.body);
        const dReal* q = dBodyGetQuaternion(body.body);
        const dReal* v = dBodyGetLinearVel(body.body);
        const dReal* w = dBodyGetAngularVel(body.body);
        std::copy(p, p + 3, s.position);
        std::copy(q, q + 4, s.quaternion);
        std::copy(v, v + 3, s.linear);
        std::copy(w, w + 3, s.angular);
        states.push_back(s);
    }
    return states;
}

void setState(const Scene& scene, const std::vector<BodyState>& states) {
    for (std::size_t i = 0; i < states.size(); ++i) {
        dBodyID body = scene.bodies()[i].body;
        const BodyState& s = states[i];
        dBodySetPosition(body, s.position[0], s.position[1], s.position[2]);
        dBodySetQuaternion(body, s.quaternion);
        dBodySetLinearVel(body, s.linear[0], s.linear[1], s.linear[2]);
        dBodySetAngularVel(body, s.angular[0], s.angular[1], s.angular[2]);
    }
}

struct Contender {
    std::string name;
    std::unique_ptr<Scene> scene;
    bool gdcontact;
    gdc::Settings settings;
    dJointGroupID joints = nullptr;
    // per sample: medians
    std::vector<double> collision, step, reduction;
    double contacts = 0;
    int messages = 0;
};

struct Pass {
    Contender* contender;
    std::vector<std::pair<dGeomID, dGeomID>> pairs;
};

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (b1 == b2) return;
    auto dynamic = [](dBodyID b) { return b && !dBodyIsKinematic(b); };
    if (!dynamic(b1) && !dynamic(b2)) return;
    static_cast<Pass*>(data)->pairs.push_back({o1, o2});
}

// One collision pass as the scene makes it (4 contacts per pair of parts, mu 0.6), the joints made;
// returns the contacts; `reductionMs` the part of it spent in the body-pair reduction.
int collide(Contender& c, double& reductionMs) {
    Pass pass{&c, {}};
    dSpaceCollide(c.scene->space(), &pass, &nearCallback);
    const SolverSettings& solver = c.scene->solver();
    const int wanted = solver.maxContactsPerPair;
    std::vector<dContactGeom> contacts;
    std::vector<int> counts;
    for (const auto& [o1, o2] : pass.pairs) {
        dContactGeom out[16];
        const int n = c.gdcontact ? gdc::ode::collide(o1, o2, wanted, out, sizeof(dContactGeom), c.settings)
                                  : dCollide(o1, o2, wanted, out, sizeof(dContactGeom));
        contacts.insert(contacts.end(), out, out + n);
        counts.push_back(n);
    }
    std::vector<dContactGeom> made;
    const auto reductionStart = Clock::now();
    if (c.gdcontact && c.settings.maxBodyPairContacts > 0) {
        // Per body pair, the contacts of all its pairs of parts reduced together.
        std::map<std::pair<dBodyID, dBodyID>, std::vector<dContactGeom>> perBodyPair;
        std::vector<std::pair<dBodyID, dBodyID>> order;
        for (const dContactGeom& contact : contacts) {
            dBodyID a = dGeomGetBody(contact.g1), b = dGeomGetBody(contact.g2);
            if (std::less<dBodyID>()(b, a)) std::swap(a, b);
            auto [entry, created] = perBodyPair.try_emplace({a, b});
            if (created) order.push_back({a, b});
            entry->second.push_back(contact);
        }
        for (const auto& key : order) {
            std::vector<dContactGeom>& group = perBodyPair[key];
            const int kept = gdc::ode::reduceBodyPair(dGeomGetBody(group[0].g1), dGeomGetBody(group[0].g2), group.data(),
                                                      static_cast<int>(group.size()), sizeof(dContactGeom), c.settings);
            made.insert(made.end(), group.begin(), group.begin() + kept);
        }
    } else {
        made = contacts;
    }
    reductionMs = std::chrono::duration<double, std::milli>(Clock::now() - reductionStart).count();
    int joints = 0;
    for (const dContactGeom& g : made) {
        // As the scene: ODE's convex collider returns a zero normal for exactly touching shapes
        // (ODE would abort on it); such a contact carries no direction and is dropped.
        const double length = std::sqrt(g.normal[0] * g.normal[0] + g.normal[1] * g.normal[1] + g.normal[2] * g.normal[2]);
        if (!(std::abs(length - 1.0) <= 1e-6) || !std::isfinite(g.depth)) continue;
        ++joints;
        dContact contact{};
        contact.surface.mode = dContactApprox1;
        contact.surface.mu = solver.mu;
        contact.geom = g;
        dJointID joint = dJointCreateContact(c.scene->world(), c.joints, &contact);
        dJointAttach(joint, dGeomGetBody(g.g1), dGeomGetBody(g.g2));
    }
    return joints;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    int every = 10, repeats = 15;
    double cfm = -1;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string option = argv[i];
        if (option == "--every") every = std::atoi(argv[i + 1]);
        else if (option == "--repeats") repeats = std::atoi(argv[i + 1]);
        else if (option == "--cfm") cfm = std::atof(argv[i + 1]);
        else {
            std::fprintf(stderr, "usage: composites_step [--every N] [--repeats N] [--cfm X]\n");
            return 2;
        }
    }
    if (every < 1 || repeats < 1) return 2;
    dInitODE2(0);
    dSetMessageHandler([](int, const char*, va_list) { ++odeMessages; });

    auto make = [&](Method method, bool convex) {
        SceneOptions options;
        options.method = method;
        options.convexBoxes = convex;
        auto scene = makeScene("composites", options);
        if (cfm >= 0) {
            SolverSettings solver = scene->solver();
            solver.cfm = cfm;
            scene->setSolver(solver);
        }
        return scene;
    };
    std::vector<Contender> contenders;
    gdc::Settings budget, none;
    budget.maxContacts = none.maxContacts = 4;
    none.maxBodyPairContacts = 0;
    auto add = [&](const char* name, Method method, bool convex, const gdc::Settings& settings) {
        Contender c;
        c.name = name;
        c.scene = make(method, convex);
        c.gdcontact = method == Method::Gdcontact;
        c.settings = settings;
        contenders.push_back(std::move(c));
    };
    add("gdcontact, no body-pair budget", Method::Gdcontact, false, none);
    add("gdcontact, body-pair budget 4", Method::Gdcontact, false, budget);
    add("ODE, parts as dBox", Method::Ode, false, {});
    add("ODE, parts as dConvex", Method::Ode, true, {});
    auto reference = make(Method::Gdcontact, false);

    constexpr double kAllReleased = 4.1;
    for (Contender& c : contenders) {
        c.scene->runUntil(kAllReleased);  // every body released (dynamic, its geoms enabled)
        c.joints = dJointGroupCreate(0);
    }
    reference->runUntil(kAllReleased);
    std::vector<std::vector<BodyState>> states;
    while (reference->time() < reference->duration() - 1e-9 && !reference->exploded()) {
        reference->step();
        if (reference->stepCount() % every == 0) states.push_back(stateOf(*reference));
    }
    const int samples = static_cast<int>(states.size());
    // Two rounds: the contenders of comparable cost interleaved, then the one without the budget
    // alone (its LCP's megabytes, interleaved, would evict the others' data from the caches and
    // slow down whichever contender comes next).
    for (bool expensiveRound : {false, true})
        for (const std::vector<BodyState>& state : states) {
            std::vector<std::vector<double>> collision(contenders.size()), step(contenders.size()),
                reduction(contenders.size());
            for (int r = 0; r < repeats; ++r)
                for (std::size_t k = 0; k < contenders.size(); ++k) {
                    Contender& c = contenders[k];
                    const bool expensive = c.gdcontact && c.settings.maxBodyPairContacts == 0;
                    if (expensive != expensiveRound) continue;
                    setState(*c.scene, state);
                    const int before = odeMessages;
                    const auto t0 = Clock::now();
                    double reductionMs = 0;
                    const int contacts = collide(c, reductionMs);
                    const auto t1 = Clock::now();
                    dWorldStep(c.scene->world(), c.scene->solver().dt);
                    const auto t2 = Clock::now();
                    dJointGroupEmpty(c.joints);
                    collision[k].push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
                    step[k].push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
                    reduction[k].push_back(reductionMs);
                    if (r == 0) c.contacts += contacts, c.messages += odeMessages - before;
                }
            for (std::size_t k = 0; k < contenders.size(); ++k) {
                if (collision[k].empty()) continue;
                contenders[k].collision.push_back(median(collision[k]));
                contenders[k].step.push_back(median(step[k]));
                contenders[k].reduction.push_back(median(reduction[k]));
            }
        }
    auto mean = [](const std::vector<double>& v) {
        double sum = 0;
        for (double x : v) sum += x;
        return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
    };
    double cheapestOde = 1e300;
    for (const Contender& c : contenders)
        if (!c.gdcontact) cheapestOde = std::min(cheapestOde, mean(c.collision) + mean(c.step));
    std::printf("composites, identical states: %d samples (every %d steps from t = %.1f s), median of %d repeats each, "
                "CFM %g\n",
                samples, every, kAllReleased, repeats, contenders[0].scene->solver().cfm);
    std::printf("%-32s %10s %14s %14s %14s %14s %14s %13s\n", "contender", "contacts", "collision ms", "(reduction)",
                "dWorldStep ms", "whole ms", "x cheaper ODE", "ODE messages");
    for (const Contender& c : contenders) {
        const double whole = mean(c.collision) + mean(c.step);
        std::printf("%-32s %10.1f %14.4f %14.4f %14.4f %14.4f %14.2f %13d\n", c.name.c_str(), c.contacts / samples,
                    mean(c.collision), mean(c.reduction), mean(c.step), whole, whole / cheapestOde, c.messages);
    }
    for (Contender& c : contenders) dJointGroupDestroy(c.joints);
    contenders.clear();
    reference.reset();
    dCloseODE();
    return 0;
}
