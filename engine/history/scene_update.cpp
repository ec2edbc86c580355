#include "engine/history/scene_update.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <unordered_map>

#include "model/geometry.hpp"

namespace smql::history {

namespace {

using model::Node;
using model::NodeId;
using model::NodeKind;

// The objects that take part in matching: visible objects with a box.
bool matchable(const Node& n) {
    return n.kind == NodeKind::Object && !n.hidden && n.geometry != model::GeometryKind::None;
}

double centreDistance(const model::Box& a, const model::Box& b) {
    return std::hypot(a.center.x - b.center.x, a.center.y - b.center.y, a.center.z - b.center.z);
}

double largestHorizontalExtent(const model::Box& b) { return std::max(b.size.x, b.size.y); }

// Sizes compared without regard to which horizontal axis is which (a turned chair is the same chair).
bool sameSize(const model::Box& a, const model::Box& b, double ratio) {
    std::array<double, 3> x{a.size.x, a.size.y, a.size.z}, y{b.size.x, b.size.y, b.size.z};
    std::sort(x.begin(), x.begin() + 2);
    std::sort(y.begin(), y.begin() + 2);
    for (std::size_t i = 0; i < 3; ++i) {
        if (!(x[i] > 0) || !(y[i] > 0)) continue;  // an extent not measured says nothing
        double r = x[i] > y[i] ? x[i] / y[i] : y[i] / x[i];
        if (r > ratio) return false;
    }
    return true;
}

// A colour both captures recorded must agree; one that only one recorded is no evidence either way.
bool sameColour(const Node& a, const Node& b) {
    const std::string* x = a.attribute("color");
    const std::string* y = b.attribute("color");
    return !x || !y || *x == *y;
}

struct Candidate {
    double distance;
    std::size_t stored, observed;
};

// Pairs in order of distance, each object at most once: the closest plausible pairs first.
template <class Accept>
void pairGreedily(const std::vector<const Node*>& stored, const std::vector<const Node*>& observed,
                  std::vector<std::optional<std::size_t>>& storedMatch, std::vector<bool>& observedTaken,
                  Accept&& accept) {
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < stored.size(); ++i) {
        if (storedMatch[i]) continue;
        for (std::size_t j = 0; j < observed.size(); ++j) {
            if (observedTaken[j] || stored[i]->category != observed[j]->category) continue;
            if (accept(*stored[i], *observed[j]))
                candidates.push_back({centreDistance(stored[i]->box, observed[j]->box), i, j});
        }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
    for (const auto& c : candidates) {
        if (storedMatch[c.stored] || observedTaken[c.observed]) continue;
        storedMatch[c.stored] = c.observed;
        observedTaken[c.observed] = true;
    }
}

// The floor rectangle of what a capture observed: anchors and objects with a box.
struct Coverage {
    double minX = std::numeric_limits<double>::infinity(), minY = minX;
    double maxX = -std::numeric_limits<double>::infinity(), maxY = maxX;
    bool contains(const model::Vec3& p, double margin) const {
        return p.x >= minX - margin && p.x <= maxX + margin && p.y >= minY - margin && p.y <= maxY + margin;
    }
};

Coverage coverageOf(const model::SceneData& observed) {
    Coverage c;
    for (const Node& n : observed.nodes) {
        if (n.geometry == model::GeometryKind::None || (n.kind != NodeKind::Anchor && n.kind != NodeKind::Object))
            continue;
        model::Aabb box = model::worldAabb(n.box);
        c.minX = std::min(c.minX, box.min.x);
        c.minY = std::min(c.minY, box.min.y);
        c.maxX = std::max(c.maxX, box.max.x);
        c.maxY = std::max(c.maxY, box.max.y);
    }
    return c;
}

void setAttribute(Node& node, const std::string& name, const std::string& value) {
    auto it = std::find_if(node.attributes.begin(), node.attributes.end(),
                           [&](const model::Attribute& a) { return a.name == name; });
    if (it == node.attributes.end())
        node.attributes.push_back({name, value});
    else
        it->value = value;
}

void sortAttributes(Node& node) {
    std::sort(node.attributes.begin(), node.attributes.end(),
              [](const model::Attribute& a, const model::Attribute& b) { return a.name < b.name; });
}

// Seen once more at `time`: the count of captures that saw it, and when the last one did.
void seenAgain(Node& node, const std::string& time) {
    const std::string* captures = node.attribute("captures");
    int count = 1;
    if (captures) {
        try {
            count = std::stoi(*captures);
        } catch (const std::exception&) {
            count = 1;  // a value some importer wrote that is not a count: start counting here
        }
    }
    setAttribute(node, "captures", std::to_string(count + 1));
    setAttribute(node, "last_seen_at", time);
}

}  // namespace

void stampSeen(model::SceneData& scene, const std::string& now) {
    if (scene.info.captureTime.empty()) scene.info.captureTime = now;
    for (auto& node : scene.nodes) {
        if (node.kind != model::NodeKind::Object) continue;
        auto has = [&](std::string_view name) {
            return std::any_of(node.attributes.begin(), node.attributes.end(),
                               [&](const model::Attribute& a) { return a.name == name; });
        };
        if (!has("first_seen_at")) node.attributes.push_back({"first_seen_at", scene.info.captureTime});
        if (!has("last_seen_at")) node.attributes.push_back({"last_seen_at", scene.info.captureTime});
        sortAttributes(node);
    }
}

Matching matchObjects(const model::SceneData& stored, const model::SceneData& observed, const MatchRules& rules) {
    std::vector<const Node*> before, after;
    for (const Node& n : stored.nodes)
        if (matchable(n)) before.push_back(&n);
    for (const Node& n : observed.nodes)
        if (matchable(n)) after.push_back(&n);

    std::vector<std::optional<std::size_t>> match(before.size());
    std::vector<bool> taken(after.size(), false);
    std::vector<bool> moved(before.size(), false);
    // Seen again where it was.
    pairGreedily(before, after, match, taken, [&](const Node& s, const Node& o) {
        return centreDistance(s.box, o.box) <= std::max(rules.inPlace, largestHorizontalExtent(s.box) / 2);
    });
    std::vector<bool> inPlace(before.size());
    for (std::size_t i = 0; i < before.size(); ++i) inPlace[i] = match[i].has_value();
    // Moved: the same kind of thing, the same size and colour, somewhere else.
    pairGreedily(before, after, match, taken, [&](const Node& s, const Node& o) {
        return sameSize(s.box, o.box, rules.sizeRatio) && sameColour(s, o);
    });

    const Coverage looked = coverageOf(observed);
    Matching out;
    for (std::size_t i = 0; i < before.size(); ++i) {
        ObjectFate fate{before[i]->id, model::kNoNode, Fate::Unchanged};
        if (match[i]) {
            fate.observed = after[*match[i]]->id;
            fate.fate = inPlace[i] ? Fate::Unchanged : Fate::Moved;
        } else {
            fate.fate = looked.contains(before[i]->box.center, rules.coverageMargin) ? Fate::Missing : Fate::Unseen;
        }
        out.stored.push_back(fate);
    }
    for (std::size_t j = 0; j < after.size(); ++j)
        if (!taken[j]) out.added.push_back(after[j]->id);
    return out;
}

namespace {

// The next version, built phase by phase: which stored nodes stay, what each kept object's fate
// does to it, the new objects, then the relations. Local ids are given in that order.
class UpdatePlanner {
public:
    UpdatePlanner(const model::SceneData& stored, const model::SceneData& observed, const std::string& time,
                  const Matching& matching)
        : stored_(stored), observed_(observed), time_(time), matching_(matching) {
        for (const auto& f : matching.stored) fateOf_.emplace(f.stored, &f);
        for (const Node& n : observed.nodes) observedById_.emplace(n.id, &n);
        for (const Node& n : stored.nodes) storedById_.emplace(n.id, &n);
        auto& info = update_.next.info;
        info = stored.info;
        info.captureTime = time;
        if (!observed.info.source.empty()) info.source = observed.info.source;
    }

    SceneUpdate plan() {
        for (const Node* n : keptNodes()) keep(*n);
        addNewObjects();
        carryRelations();
        update_.next.info.nodeCount = update_.next.nodes.size();
        return std::move(update_);
    }

private:
    const ObjectFate* fate(NodeId storedId) const {
        auto it = fateOf_.find(storedId);
        return it == fateOf_.end() ? nullptr : it->second;
    }
    bool gone(const Node& n) const { return fate(n.id) && fate(n.id)->fate == Fate::Missing; }
    bool moved(NodeId storedId) const { return fate(storedId) && fate(storedId)->fate == Fate::Moved; }

    // The stored nodes the new version keeps, in their order: every node but the missing objects
    // (each a change) and the descriptions of nodes that are gone.
    std::vector<const Node*> keptNodes() {
        std::vector<const Node*> kept;
        for (const Node& n : stored_.nodes) {
            if (n.kind == NodeKind::Scene) continue;
            if (gone(n)) {
                ++update_.missing;
                update_.changes.push_back({model::ChangeKind::Missing, n.category, n.id, model::kNoNode, n.box, {}});
                continue;
            }
            auto parent = storedById_.find(n.parent);
            if (n.kind == NodeKind::Description && parent != storedById_.end() && gone(*parent->second)) continue;
            localOfStored_.emplace(n.id, nextLocal_++);
            kept.push_back(&n);
        }
        return kept;
    }

    // A kept node as the new version has it: seen again, moved (to its new box) or unseen; with its
    // parent, which structure and descriptions keep, and an object keeps unless either of them moved
    // (otherwise the engine finds its parent anew: support, else the nearest upright anchor).
    void keep(const Node& n) {
        Node kept = n;
        kept.id = localOfStored_.at(n.id);
        kept.scene = model::kNoNode;
        if (const ObjectFate* f = fate(n.id)) {
            if (f->fate == Fate::Unchanged) ++update_.unchanged;
            if (f->fate == Fate::Unseen) ++update_.unseen;
            if (f->fate != Fate::Unseen) {
                seenAgain(kept, time_);
                localOfObserved_.emplace(f->observed, kept.id);
            }
            if (f->fate == Fate::Moved) {
                ++update_.moved;
                kept.box = observedById_.at(f->observed)->box;
                setAttribute(kept, "moved_at", time_);
                placedAnew_.insert(kept.id);
                update_.changes.push_back({model::ChangeKind::Moved, n.category, n.id, kept.id, n.box, kept.box});
            }
        }
        auto parent = localOfStored_.find(n.parent);
        bool keepsParent = parent != localOfStored_.end();
        if (n.kind == NodeKind::Object) keepsParent = keepsParent && !moved(n.id) && !moved(n.parent);
        kept.parent = keepsParent ? parent->second : model::kNoNode;
        sortAttributes(kept);
        update_.carried.emplace_back(n.id, kept.id);
        update_.next.nodes.push_back(std::move(kept));
    }

    // The new objects, with the descriptions and the evidence the capture gave them.
    void addNewObjects() {
        auto& next = update_.next;
        std::set<std::int64_t> sourceIds;
        for (const Node& n : next.nodes)
            if (n.sourceId) sourceIds.insert(*n.sourceId);
        std::set<NodeId> added(matching_.added.begin(), matching_.added.end());
        auto place = [&](const Node& n, NodeId parent) {
            Node fresh = n;
            fresh.id = nextLocal_++;
            fresh.scene = model::kNoNode;
            fresh.parent = parent;
            // A source id names a thing in one capture's files; the stored ones keep theirs.
            if (fresh.sourceId && !sourceIds.insert(*fresh.sourceId).second) fresh.sourceId.reset();
            localOfObserved_.emplace(n.id, fresh.id);
            return fresh;
        };
        for (const Node& n : observed_.nodes) {
            if (!added.count(n.id)) continue;
            Node fresh = place(n, model::kNoNode);
            ++update_.added;
            setAttribute(fresh, "first_seen_at", time_);
            setAttribute(fresh, "last_seen_at", time_);
            setAttribute(fresh, "captures", "1");
            sortAttributes(fresh);
            placedAnew_.insert(fresh.id);
            update_.changes.push_back({model::ChangeKind::Added, n.category, model::kNoNode, fresh.id, {}, n.box});
            next.nodes.push_back(std::move(fresh));
        }
        for (const Node& n : observed_.nodes)
            if (n.kind == NodeKind::Description && added.count(n.parent))
                next.nodes.push_back(place(n, localOfObserved_.at(n.parent)));
        for (const model::Blob& blob : observed_.blobs) {
            if (!added.count(blob.node)) continue;
            model::Blob b = blob;
            b.node = localOfObserved_.at(blob.node);
            next.blobs.push_back(std::move(b));
        }
    }

    // Relations: the stored ones among what stayed in place, the capture's among what it placed.
    void carryRelations() {
        auto map = [](const std::unordered_map<NodeId, NodeId>& ids, NodeId id) -> std::optional<NodeId> {
            if (id == model::kNoNode) return model::kNoNode;
            auto it = ids.find(id);
            if (it == ids.end()) return std::nullopt;
            return it->second;
        };
        auto& relations = update_.next.relations;
        for (const model::Relation& r : stored_.relations) {
            auto s = map(localOfStored_, r.subject), o = map(localOfStored_, r.object),
                 f = map(localOfStored_, r.frame);
            if (!s || !o || !f || placedAnew_.count(*s) || placedAnew_.count(*o)) continue;
            relations.push_back({*s, *o, r.type, r.score, r.support, *f});
        }
        for (const model::Relation& r : observed_.relations) {
            auto s = map(localOfObserved_, r.subject), o = map(localOfObserved_, r.object);
            if (!s || !o || (!placedAnew_.count(*s) && !placedAnew_.count(*o))) continue;
            auto f = map(localOfObserved_, r.frame);
            relations.push_back({*s, *o, r.type, r.score, r.support, f.value_or(model::kNoNode)});
        }
    }

    const model::SceneData& stored_;
    const model::SceneData& observed_;
    const std::string& time_;
    const Matching& matching_;
    SceneUpdate update_;
    std::unordered_map<NodeId, const ObjectFate*> fateOf_;
    std::unordered_map<NodeId, const Node*> observedById_, storedById_;
    NodeId nextLocal_ = 1;
    std::unordered_map<NodeId, NodeId> localOfStored_, localOfObserved_;
    std::set<NodeId> placedAnew_;  // local ids of moved and added objects: their parents and relations are new
};

}  // namespace

SceneUpdate planUpdate(const model::SceneData& stored, const model::SceneData& observed, const std::string& time,
                       const MatchRules& rules) {
    const Matching matching = matchObjects(stored, observed, rules);
    return UpdatePlanner(stored, observed, time, matching).plan();
}

}  // namespace smql::history
