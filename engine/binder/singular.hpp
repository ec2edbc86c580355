// References that must name one node (RELATE's sides, VIEW FROM, FACING, CHECK): a bare name that
// matches several is an error listing them, never a choice made for the user nor every pair.
#pragma once

#include <vector>

#include "engine/binder/bound.hpp"
#include "engine/catalog/scene_snapshot.hpp"

namespace smql::binder {

// Throws unless `slots`, what `set` names, is exactly one node: none says so, several are listed
// as typed-back names (`window#12`) with where each is, and how to pick one.
void requireOne(const catalog::SceneSnapshot& scene, const binder::NodeSet& set,
                const std::vector<catalog::Slot>& slots);

}  // namespace smql::binder
