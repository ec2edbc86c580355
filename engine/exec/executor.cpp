#include "engine/exec/executor.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/error.hpp"
#include "engine/model/geometry.hpp"

namespace smql::exec {

using binder::BoundExpr;
using model::Node;

namespace {

std::string lower(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// SQL LIKE: % any run, _ any one character; case-insensitive.
bool like(std::string_view text, std::string_view pattern) {
    if (pattern.empty()) return text.empty();
    if (pattern[0] == '%') {
        for (std::size_t i = 0; i <= text.size(); ++i)
            if (like(text.substr(i), pattern.substr(1))) return true;
        return false;
    }
    if (text.empty()) return false;
    bool same = pattern[0] == '_' || std::tolower(static_cast<unsigned char>(pattern[0])) ==
                                         std::tolower(static_cast<unsigned char>(text[0]));
    return same && like(text.substr(1), pattern.substr(1));
}

// A node's field as a comparison sees it: built-in fields first, then stored attributes.
std::optional<std::variant<double, std::string>> field(const Node& n, const std::string& name) {
    const auto& s = n.box.size;
    if (name == "category") return n.category;
    if (name == "kind") return std::string(model::toString(n.kind));
    if (name == "text") return n.text;
    if (name == "id") return static_cast<double>(n.id);
    if (name == "source_id") {
        if (!n.sourceId) return std::nullopt;
        return static_cast<double>(*n.sourceId);
    }
    if (name == "confidence") return static_cast<double>(n.confidence);
    if (n.geometry != model::GeometryKind::None) {
        if (name == "height") return s.z;
        if (name == "width") return std::max(s.x, s.y);
        if (name == "depth") return std::min(s.x, s.y);
        if (name == "volume") return model::volume(n.box);
        if (name == "x") return n.box.center.x;
        if (name == "y") return n.box.center.y;
        if (name == "z") return n.box.center.z;
    }
    if (const std::string* v = n.attribute(name)) return *v;
    return std::nullopt;
}

template <typename T>
bool ordered(ast::CompareOp op, const T& a, const T& b) {
    switch (op) {
        case ast::CompareOp::Eq: return a == b;
        case ast::CompareOp::Ne: return a != b;
        case ast::CompareOp::Lt: return a < b;
        case ast::CompareOp::Le: return a <= b;
        case ast::CompareOp::Gt: return a > b;
        case ast::CompareOp::Ge: return a >= b;
        case ast::CompareOp::Like: return false;
    }
    return false;
}

double distanceToSet(const Node& a, const binder::NodeSet& set, const SceneSnapshot& scene, bool skipSelf) {
    double best = std::numeric_limits<double>::infinity();
    for (Slot s : set.slots) {
        const Node& b = scene.node(s);
        if (skipSelf && b.id == a.id) continue;
        best = std::min(best, model::distance(a.box, b.box));
    }
    return best;
}

Value boxValue(const Node& n) {
    if (n.geometry == model::GeometryKind::None) return std::monostate{};
    return n.box;
}

Value sourceValue(const Node& n) {
    if (!n.sourceId) return std::monostate{};
    return *n.sourceId;
}

}  // namespace

bool Executor::compare(const BoundExpr& expr, const Node& node) const {
    auto value = field(node, expr.attribute);
    if (!value) return false;  // a node without the field never matches, as NULL in SQL
    if (auto* text = std::get_if<std::string>(&expr.literal)) {
        std::string have = std::holds_alternative<std::string>(*value)
                               ? std::get<std::string>(*value)
                               : fmt::format("{}", std::get<double>(*value));
        if (expr.op == ast::CompareOp::Like) return like(have, *text);
        return ordered(expr.op, lower(have), lower(*text));
    }
    double want = std::holds_alternative<double>(expr.literal) ? std::get<double>(expr.literal)
                                                               : static_cast<double>(std::get<std::int64_t>(expr.literal));
    double have;
    if (auto* d = std::get_if<double>(&*value)) {
        have = *d;
    } else {
        const auto& s = std::get<std::string>(*value);
        char* end = nullptr;
        have = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0') return false;
    }
    if (expr.op == ast::CompareOp::Like) return false;
    return ordered(expr.op, have, want);
}

bool Executor::matches(const BoundExpr& expr, Slot slot, const relations::Frame& frame) const {
    switch (expr.kind) {
        case BoundExpr::Kind::And:
            return std::all_of(expr.children.begin(), expr.children.end(),
                               [&](const BoundExpr& c) { return matches(c, slot, frame); });
        case BoundExpr::Kind::Or:
            return std::any_of(expr.children.begin(), expr.children.end(),
                               [&](const BoundExpr& c) { return matches(c, slot, frame); });
        case BoundExpr::Kind::Not:
            return !matches(expr.children.front(), slot, frame);
        case BoundExpr::Kind::Compare:
            return compare(expr, scene_.node(slot));
        case BoundExpr::Kind::Predicate:
            return holdsForSome(expr, slot, frame);
    }
    return false;
}

const std::vector<char>& Executor::membership(const binder::NodeSet& set) const {
    auto [it, inserted] = membership_.try_emplace(&set);
    if (inserted) {
        it->second.assign(scene_.nodes().size(), 0);
        for (Slot s : set.slots) it->second[s] = 1;
    }
    return it->second;
}

bool Executor::holdsForSome(const BoundExpr& expr, Slot slot, const relations::Frame& frame) const {
    const Node& a = scene_.node(slot);
    if (expr.args.size() == 2) {
        for (Slot b : expr.args[0].slots)
            for (Slot c : expr.args[1].slots)
                if (b != slot && c != slot && c != b &&
                    relations::evaluate(expr.predicate, a, scene_.node(b), thresholds_, frame, &scene_.node(c)) > 0)
                    return true;
        return false;
    }
    double nearDistance = expr.nearDistance.value_or(thresholds_.nearDistance);
    // Where a reference must be for the predicate to hold: a cheap bounds test before the exact one.
    auto region = relations::referenceRegion(expr.predicate, scene_.bounds(slot), nearDistance, thresholds_);
    auto holds = [&](Slot b) {
        if (b == slot || (region && !relations::intersects(scene_.bounds(b), *region))) return false;
        return relations::evaluate(expr.predicate, a, scene_.node(b), thresholds_, frame, nullptr, expr.nearDistance) > 0;
    };
    const auto& refs = expr.args[0].slots;
    constexpr std::size_t kIndexedReferences = 32;
    if (region && refs.size() > kIndexedReferences) {
        // Many references: the R-tree names the few close enough, the set keeps its own.
        const auto& member = membership(expr.args[0]);
        std::vector<Slot> close;
        scene_.spatialIndex().intersecting(*region, close);
        return std::any_of(close.begin(), close.end(), [&](Slot b) { return member[b] && holds(b); });
    }
    return std::any_of(refs.begin(), refs.end(), holds);
}

bool Executor::inTarget(const binder::Target& target, Slot slot) const {
    const Node& n = scene_.node(slot);
    switch (target.kind) {
        case binder::Target::Kind::Category: return n.category == target.category;
        case binder::Target::Kind::NodeKind: return n.kind == target.nodeKind && !n.hidden;
        case binder::Target::Kind::AnyNode: return n.kind != model::NodeKind::Scene && !n.hidden;
        case binder::Target::Kind::Nodes:
            return std::binary_search(target.nodes.slots.begin(), target.nodes.slots.end(), slot);
    }
    return false;
}

std::optional<std::vector<Hit>> Executor::nearestFirst(const planner::FindPlan& plan) const {
    const auto& f = *plan.find;
    if (!f.distanceTo || f.distanceTo->slots.size() != 1 || !f.limit || f.descending || plan.probe) return std::nullopt;
    const Slot ref = f.distanceTo->slots.front();
    const auto want = static_cast<std::size_t>(*f.limit);
    const model::Aabb& around = scene_.bounds(ref);
    auto boundsGap = [&](const model::Aabb& b) {
        double dx = std::max({0.0, b.min.x - around.max.x, around.min.x - b.max.x});
        double dy = std::max({0.0, b.min.y - around.max.y, around.min.y - b.max.y});
        double dz = std::max({0.0, b.min.z - around.max.z, around.min.z - b.max.z});
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    const auto& index = scene_.spatialIndex();
    for (std::size_t k = std::max<std::size_t>(4 * want, 32);; k *= 4) {
        std::vector<Slot> near;
        index.nearest(around, k, near);
        std::vector<Hit> hits;
        for (Slot s : near) {
            if ((f.nearest && s == ref) || !inTarget(f.target, s) || (f.where && !matches(*f.where, s, f.frame))) continue;
            hits.push_back({s, model::distance(scene_.node(s).box, scene_.node(ref).box)});
        }
        std::sort(hits.begin(), hits.end(), [&](const Hit& a, const Hit& b) {
            return a.distance != b.distance ? a.distance < b.distance : scene_.node(a.slot).id < scene_.node(b.slot).id;
        });
        // A box is never nearer than its bounds, so boxes beyond the last returned bounds cannot beat
        // an answer strictly nearer than those bounds.
        bool wholeIndex = near.size() < k || k >= index.size();
        if (wholeIndex || (hits.size() >= want && hits[want - 1].distance < boundsGap(scene_.bounds(near.back())))) {
            if (hits.size() > want) hits.resize(want);
            return hits;
        }
    }
}

std::vector<Hit> Executor::find(const planner::FindPlan& plan) const {
    const auto& f = *plan.find;
    if (auto hits = nearestFirst(plan)) return *hits;
    std::vector<Slot> candidates;
    if (plan.probe) {
        for (const auto& region : plan.probe->regions) scene_.spatialIndex().intersecting(region, candidates);
        std::sort(candidates.begin(), candidates.end());
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        std::erase_if(candidates, [&](Slot s) { return !inTarget(f.target, s); });
    } else {
        candidates = f.target.nodes.slots;
    }

    std::vector<Hit> hits;
    hits.reserve(candidates.size());
    for (Slot s : candidates) {
        if (f.where && !matches(*f.where, s, f.frame)) continue;
        hits.push_back({s, 0});
    }
    if (f.distanceTo) {
        // Nodes without a place have no distance to order by.
        std::erase_if(hits, [&](const Hit& h) { return scene_.node(h.slot).geometry == model::GeometryKind::None; });
        for (auto& h : hits) h.distance = distanceToSet(scene_.node(h.slot), *f.distanceTo, scene_, f.nearest);
        if (f.nearest) {
            // NEAREST TO x: x itself is not an answer.
            std::erase_if(hits, [&](const Hit& h) {
                return std::find(f.distanceTo->slots.begin(), f.distanceTo->slots.end(), h.slot) !=
                       f.distanceTo->slots.end();
            });
        }
        std::stable_sort(hits.begin(), hits.end(), [&](const Hit& a, const Hit& b) {
            if (a.distance != b.distance) return f.descending ? a.distance > b.distance : a.distance < b.distance;
            return scene_.node(a.slot).id < scene_.node(b.slot).id;
        });
    }
    if (f.limit && hits.size() > static_cast<std::size_t>(*f.limit)) hits.resize(static_cast<std::size_t>(*f.limit));
    return hits;
}

ResultSet Executor::findRows(const planner::FindPlan& plan) const {
    const auto& f = *plan.find;
    auto hits = find(plan);
    ResultSet rs;
    if (f.countOnly) {
        rs.columns = {{"count", ValueType::Integer}};
        rs.rows.push_back({static_cast<std::int64_t>(hits.size())});
        return rs;
    }
    rs.columns = {{"id", ValueType::Integer},
                  {"category", ValueType::Text},
                  {"source_id", ValueType::Integer},
                  {"box", ValueType::Box}};
    if (f.distanceTo) rs.columns.push_back({"distance", ValueType::Real});
    if (f.path) rs.columns.push_back({"path", ValueType::Text});
    rs.rows.reserve(hits.size());
    for (const auto& h : hits) {
        const Node& n = scene_.node(h.slot);
        std::vector<Value> row{static_cast<std::int64_t>(n.id), n.category, sourceValue(n), boxValue(n)};
        if (f.distanceTo) row.emplace_back(h.distance);
        if (f.path) row.emplace_back(scene_.path(h.slot));
        rs.rows.push_back(std::move(row));
    }
    return rs;
}

ResultSet Executor::relate(const binder::BoundRelate& r) const {
    ResultSet rs;
    rs.columns = {{"subject", ValueType::Text}, {"relation", ValueType::Text}, {"object", ValueType::Text},
                  {"score", ValueType::Real},   {"distance", ValueType::Real}};
    std::vector<std::string> sentences;
    for (Slot a : r.subject.slots) {
        for (Slot b : r.object.slots) {
            if (a == b) continue;
            const Node& na = scene_.node(a);
            const Node& nb = scene_.node(b);
            auto hits = relations::relate(na, nb, thresholds_, r.frame);
            double gap = model::distance(na.box, nb.box);
            std::string la = SceneSnapshot::label(na), lb = SceneSnapshot::label(nb);
            std::string sentence;
            for (const auto& hit : hits) {
                rs.rows.push_back({la, std::string(relations::toString(hit.predicate)), lb, hit.score, gap});
                std::string words(relations::toString(hit.predicate));
                std::replace(words.begin(), words.end(), '_', ' ');  // "left of", "in front of"
                std::string phrase = fmt::format("{} {}", words, lb);
                if (hit.predicate == relations::Predicate::Near) phrase += fmt::format(" ({:.1f} m)", gap);
                sentence += (sentence.empty() ? la + " is " : "; ") + phrase;
            }
            if (hits.empty()) sentence = fmt::format("no relation holds from {} to {} ({:.1f} m apart)", la, lb, gap);
            sentences.push_back(sentence);
        }
    }
    for (std::size_t i = 0; i < sentences.size() && i < 20; ++i) rs.message += (i ? "\n" : "") + sentences[i];
    if (sentences.size() > 20) rs.message += fmt::format("\n... {} more pairs in the rows", sentences.size() - 20);
    return rs;
}

ResultSet Executor::describe(const binder::NodeSet& nodes) const {
    ResultSet rs;
    rs.columns = {{"id", ValueType::Integer}, {"field", ValueType::Text}, {"value", ValueType::Text}};
    for (Slot s : nodes.slots) {
        const Node& n = scene_.node(s);
        auto id = static_cast<std::int64_t>(n.id);
        auto add = [&](std::string_view name, std::string value) { rs.rows.push_back({id, std::string(name), std::move(value)}); };
        add("kind", std::string(model::toString(n.kind)));
        add("category", n.category);
        add("path", scene_.path(s));
        if (n.sourceId) add("source_id", std::to_string(*n.sourceId));
        if (n.geometry != model::GeometryKind::None) {
            const auto& b = n.box;
            add("center", fmt::format("({:.3f}, {:.3f}, {:.3f}) m", b.center.x, b.center.y, b.center.z));
            add("dimensions", fmt::format("{:.3f} x {:.3f} x {:.3f} m", b.size.x, b.size.y, b.size.z));
            add("yaw", fmt::format("{:.1f} deg", b.yaw * 180.0 / M_PI));
            add("geometry", n.geometry == model::GeometryKind::Plane ? "plane segment" : "box");
        }
        add("confidence", fmt::format("{:.2f}", n.confidence));
        for (const auto& a : n.attributes) add(a.name, a.value);
        if (!n.text.empty()) add("text", n.text);
        if (n.hidden) add("hidden", "yes (left out of queries unless named)");
        std::string kids;
        for (Slot c : scene_.children(s)) {
            const Node& child = scene_.node(c);
            if (child.kind == model::NodeKind::Description) add("description", child.text);
            else kids += (kids.empty() ? "" : ", ") + SceneSnapshot::label(child);
        }
        if (!kids.empty()) add("children", kids);
    }
    return rs;
}

ResultSet Executor::tree(std::optional<Slot> root) const {
    ResultSet rs;
    rs.columns = {{"id", ValueType::Integer}, {"depth", ValueType::Integer}, {"node", ValueType::Text}};
    std::size_t hidden = 0, descriptions = 0, frames = 0;
    // Depth-first, children in id order, so the listing reads like the path of each node.
    std::vector<std::pair<Slot, std::int64_t>> stack;
    Slot start = root.value_or(*scene_.slotOf(scene_.info().id));
    stack.push_back({start, 0});
    while (!stack.empty()) {
        auto [slot, depth] = stack.back();
        stack.pop_back();
        const Node& n = scene_.node(slot);
        if (n.hidden) {
            ++hidden;
            continue;
        }
        // Descriptions are text about their parent (DESCRIBE shows them) and frames are where the
        // camera stood (FIND frame lists them): neither is a place in the tree.
        if (n.kind == model::NodeKind::Description || n.kind == model::NodeKind::Frame) {
            ++(n.kind == model::NodeKind::Frame ? frames : descriptions);
            continue;
        }
        rs.rows.push_back({static_cast<std::int64_t>(n.id), depth,
                           std::string(2 * depth, ' ') + SceneSnapshot::label(n)});
        const auto& kids = scene_.children(slot);
        for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back({*it, depth + 1});
    }
    if (hidden) rs.message = fmt::format("{} hidden node{} not shown (e.g. unlabelled parts)", hidden, hidden == 1 ? "" : "s");
    if (descriptions)
        rs.message += fmt::format("{}{} description{} not shown (DESCRIBE #id lists an object's)", rs.message.empty() ? "" : "; ",
                                  descriptions, descriptions == 1 ? "" : "s");
    if (frames)
        rs.message += fmt::format("{}{} frame{} not shown (FIND frame lists them)", rs.message.empty() ? "" : "; ", frames,
                                  frames == 1 ? "" : "s");
    return rs;
}

}  // namespace smql::exec
