// gdc::ode::reduceBodyPair: the ODE side of the per-body-pair contact budget. It reads the bodies
// (centre of mass, the world's gravity) and the contacts' geoms, turns every normal to point into
// b1's side, and lets the core (gdc::reduceBodyPairContacts, src/body_pair_reduction.cpp) choose.
#include <gdcontact/ode.hpp>

#include "body_pair.hpp"

#include <functional>
#include <map>
#include <string>
#include <utility>

namespace gdc::ode {
namespace detail {
namespace {

const dContactGeom& at(const dContactGeom* contacts, int index, int skip) {
    return *reinterpret_cast<const dContactGeom*>(reinterpret_cast<const char*>(contacts) +
                                                  static_cast<std::size_t>(index) * static_cast<std::size_t>(skip));
}

Vec3 vec(const dReal* v) { return Vec3(v[0], v[1], v[2]); }

}  // namespace

bool bothHaveOneGeom(dBodyID b1, dBodyID b2) {
    auto single = [](dBodyID body) {
        const dGeomID first = body ? dBodyGetFirstGeom(body) : nullptr;
        return first && !dBodyGetNextGeom(first);
    };
    return single(b1) && single(b2);
}

int chooseBodyPairContacts(dBodyID b1, dBodyID b2, const dContactGeom* contacts, int count, int skip,
                           const Settings& settings, std::vector<BodyPairContact>& points, std::vector<int>& kept) {
    kept.clear();
    bool severalPairs = false;
    for (int i = 1; i < count && !severalPairs; ++i) {  // count ≥ 2: contacts[0] exists
        const dContactGeom& first = at(contacts, 0, skip);
        const dContactGeom& c = at(contacts, i, skip);
        severalPairs = !((c.g1 == first.g1 && c.g2 == first.g2) || (c.g1 == first.g2 && c.g2 == first.g1));
    }
    if (settings.maxBodyPairContacts == 0 || !severalPairs) {
        for (int i = 0; i < count; ++i) kept.push_back(i);
        return count;
    }
    points.resize(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        const dContactGeom& c = at(contacts, i, skip);
        BodyPairContact& p = points[static_cast<std::size_t>(i)];
        p.position = vec(c.pos);
        p.normal = vec(c.normal);  // from g2 into g1: into b1's side when g1 is on b1
        if (dGeomGetBody(c.g1) != b1) p.normal = -p.normal;
        p.depth = c.depth;
    }
    BodyPairFrame frame;
    if (b1) frame.centreA = vec(dBodyGetPosition(b1)), frame.hasCentreA = true;
    if (b2) frame.centreB = vec(dBodyGetPosition(b2)), frame.hasCentreB = true;
    dVector3 gravity;
    dWorldGetGravity(dBodyGetWorld(b1 ? b1 : b2), gravity);
    frame.gravity = vec(gravity);
    return reduceBodyPairContacts(points.data(), count, frame, settings, kept);
}

}  // namespace detail

int reduceBodyPair(dBodyID b1, dBodyID b2, dContactGeom* contacts, int count, int skip, const Settings& settings) {
    validate(settings);
    if (count < 0) throw InvalidInput("gdc::ode::reduceBodyPair: negative count " + std::to_string(count));
    if (count > 0 && !contacts) throw InvalidInput("gdc::ode::reduceBodyPair: null contacts");
    if (skip < static_cast<int>(sizeof(dContactGeom)))
        throw InvalidInput("gdc::ode::reduceBodyPair: skip " + std::to_string(skip) + " is less than sizeof(dContactGeom)");
    if (b1 == b2)
        throw InvalidInput(b1 ? "gdc::ode::reduceBodyPair: b1 and b2 are the same body"
                              : "gdc::ode::reduceBodyPair: b1 and b2 are both the static world (0)");
    for (int i = 0; i < count; ++i) {
        const dContactGeom& c = detail::at(contacts, i, skip);
        const dBodyID first = c.g1 ? dGeomGetBody(c.g1) : nullptr, second = c.g2 ? dGeomGetBody(c.g2) : nullptr;
        if (!c.g1 || !c.g2 || !((first == b1 && second == b2) || (first == b2 && second == b1)))
            throw InvalidInput("gdc::ode::reduceBodyPair: contact " + std::to_string(i) +
                               " is not between a geom of b1 and a geom of b2 (its g1, g2)");
    }
    thread_local std::vector<BodyPairContact> points;
    thread_local std::vector<int> kept;
    const int survivors = detail::chooseBodyPairContacts(b1, b2, contacts, count, skip, settings, points, kept);
    char* base = reinterpret_cast<char*>(contacts);
    for (int k = 0; k < survivors; ++k)
        if (kept[k] != k)
            *reinterpret_cast<dContactGeom*>(base + static_cast<std::size_t>(k) * skip) =
                detail::at(contacts, kept[k], skip);
    return survivors;
}

BodyPairContacts::BodyPairContacts(const Settings& settings) : settings_(settings) { validate(settings_); }

void BodyPairContacts::add(dGeomID o1, dGeomID o2, const dContactGeom* contacts, int count) {
    if (count < 0) throw InvalidInput("gdc::ode::BodyPairContacts::add: negative count " + std::to_string(count));
    if (count > 0 && !contacts) throw InvalidInput("gdc::ode::BodyPairContacts::add: null contacts");
    pairs_.push_back({o1, o2, contacts_.size(), count});
    contacts_.insert(contacts_.end(), contacts, contacts + count);
}

void BodyPairContacts::clear() {
    pairs_.clear();
    contacts_.clear();
}

void BodyPairContacts::deliver(void* data, ContactHandler handler) {
    if (!handler) throw InvalidInput("gdc::ode::BodyPairContacts::deliver: null handler");
    struct Clear {  // cleared whatever happens
        BodyPairContacts& self;
        ~Clear() { self.clear(); }
    } clearAtEnd{*this};
    thread_local std::vector<BodyPairContact> points;
    thread_local std::vector<int> kept;
    // Survivor counts per pair (−1: not reduced, its contacts as added).
    done_.assign(pairs_.size(), -1);
    if (settings_.maxBodyPairContacts > 0) {
        // The pairs of each pair of bodies, in the order added (two single-geom bodies touch
        // through one pair at most: they skip the table).
        std::map<std::pair<dBodyID, dBodyID>, std::vector<std::size_t>> byBodies;
        std::vector<std::pair<dBodyID, dBodyID>> order;
        for (std::size_t i = 0; i < pairs_.size(); ++i) {
            dBodyID b1 = dGeomGetBody(pairs_[i].o1), b2 = dGeomGetBody(pairs_[i].o2);
            if (b1 == b2 || detail::bothHaveOneGeom(b1, b2)) continue;
            if (std::less<dBodyID>()(b2, b1)) std::swap(b1, b2);
            auto [entry, created] = byBodies.try_emplace({b1, b2});
            if (created) order.push_back({b1, b2});
            entry->second.push_back(i);
        }
        for (const auto& key : order) {
            const std::vector<std::size_t>& members = byBodies[key];
            const dBodyID b1 = dGeomGetBody(pairs_[members[0]].o1), b2 = dGeomGetBody(pairs_[members[0]].o2);
            if (members.size() < 2) continue;
            gathered_.clear();
            for (std::size_t j : members) {
                const dContactGeom* first = contacts_.data() + pairs_[j].offset;
                gathered_.insert(gathered_.end(), first, first + pairs_[j].count);
            }
            int survivors;
            try {
                survivors = detail::chooseBodyPairContacts(b1, b2, gathered_.data(), static_cast<int>(gathered_.size()),
                                                           sizeof(dContactGeom), settings_, points, kept);
            } catch (const InvalidInput&) {  // a contact with a zero normal (ODE's convex collider): as added
                continue;
            }
            // Each survivor back into its own pair's contacts, in order.
            std::size_t from = 0;
            for (std::size_t j : members) done_[j] = 0;
            for (std::size_t m = 0, k = 0; m < members.size(); ++m) {
                const std::size_t j = members[m];
                const std::size_t end = from + static_cast<std::size_t>(pairs_[j].count);
                for (; k < static_cast<std::size_t>(survivors) && static_cast<std::size_t>(kept[k]) < end; ++k)
                    contacts_[pairs_[j].offset + static_cast<std::size_t>(done_[j]++)] = gathered_[static_cast<std::size_t>(kept[k])];
                from = end;
            }
        }
    }
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
        const int count = done_[i] >= 0 ? done_[i] : pairs_[i].count;
        if (count > 0) handler(data, pairs_[i].o1, pairs_[i].o2, contacts_.data() + pairs_[i].offset, count);
    }
}

}  // namespace gdc::ode
