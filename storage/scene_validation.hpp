// Internal to storage/: the checks an incoming scene passes before anything of it is written, so a
// refused import or rename leaves the write transaction as it was and usable. (check.hpp is the
// other kind of check: of what a database already holds.)
#pragma once

#include <cstddef>
#include <string_view>
#include <unordered_map>

#include "model/types.hpp"
#include "storage/lmdb_env.hpp"

namespace smql::storage {

// Throws smql::Error(Input) for a name that cannot key the name index and the history table: empty,
// too long, or holding a NUL.
void checkSceneName(const Environment& env, std::string_view name);

// Throws smql::Error(Input) for a node whose box holds a NaN or an infinite number: no spatial
// query could place it, and every predicate would read it as false. `where()` names the node, and
// is asked only then.
bool finiteBox(const model::Box& box);
[[noreturn]] void refuseBox(const model::Box& box, std::string_view where);
template <class Where>
void checkBox(const model::Node& node, const Where& where) {
    if (!finiteBox(node.box)) refuseBox(node.box, where());
}

// Checks a scene's name, local ids and boxes (throwing smql::Error(Input)), and returns the position of each
// local id in data.nodes (its database id is sceneId + 1 + position).
std::unordered_map<model::NodeId, std::size_t> validateScene(const Environment& env, const model::SceneData& data);

}  // namespace smql::storage
