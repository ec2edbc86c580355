#include "engine/binder/singular.hpp"

#include <fmt/format.h>

#include "model/error.hpp"
#include "model/presentation.hpp"

namespace smql::binder {

namespace {

constexpr std::size_t kListed = 10;

// "window#12 (by wall#3 at 1.2, 0.4, 1.5 m)", "mug#4 (on desk#2 at ...)": enough to tell the candidates apart. A
// thing is by the anchor it hangs below in the tree, on the thing it rests on.
std::string candidate(const catalog::SceneSnapshot& scene, catalog::Slot slot) {
    const model::Node& n = scene.node(slot);
    std::string where;
    if (auto parent = scene.slotOf(n.parent); parent && scene.node(*parent).kind != model::NodeKind::Scene) {
        const model::Node& p = scene.node(*parent);
        where = (p.kind == model::NodeKind::Anchor ? "by " : "on ") + catalog::SceneSnapshot::label(p);
    }
    if (n.geometry != model::GeometryKind::None)
        where += fmt::format("{}at {:.1f}, {:.1f}, {:.1f} m", where.empty() ? "" : " ", n.box.center.x, n.box.center.y,
                             n.box.center.z);
    return where.empty() ? catalog::SceneSnapshot::label(n)
                         : fmt::format("{} ({})", catalog::SceneSnapshot::label(n), where);
}

}  // namespace

void requireOne(const catalog::SceneSnapshot& scene, const binder::NodeSet& set,
                const std::vector<catalog::Slot>& slots) {
    if (slots.size() == 1) return;
    // "window (3 nodes)" -> window: the count is said below.
    const std::string named = set.description.substr(0, set.description.find(" ("));
    if (slots.empty())
        throw Error(ErrorKind::Binding, fmt::format("{} names no node; {} needs one", named, set.singleFor), set.where,
                    "SHOW CATEGORIES lists what this scene holds");
    std::string category = scene.node(slots.front()).category;
    std::vector<std::string> candidates;
    for (auto slot : slots) candidates.push_back(candidate(scene, slot));
    const std::string listed = model::listFirst(candidates, kListed);
    const std::string example = catalog::SceneSnapshot::label(scene.node(slots.front()));
    const std::string landmark = category == "door" ? "window" : "door";
    throw Error(ErrorKind::Binding,
                fmt::format("{} is ambiguous: {} needs one node and it names {}: {}", named, set.singleFor,
                            slots.size(), listed),
                set.where,
                fmt::format("name one, as in {}, or pick one by place, as in (FIND {} NEAREST TO {} LIMIT 1)", example,
                            category, landmark));
}

}  // namespace smql::binder
