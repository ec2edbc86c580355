// A new capture of a stored place, merged into the next version of its scene: which stored
// objects were seen again where they were, which moved, which are missing, which are new.
// Pure functions over model types; Engine::updateScene runs them inside one write transaction
// and storage::WriteTransaction::replaceScene keeps the superseded version. docs/history.md
// states the rules.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "model/types.hpp"

namespace smql::history {

// The thresholds of matching (metres and ratios), each documented in docs/history.md.
struct MatchRules {
    // Seen again in place: centres at most this far apart, or half the stored object's
    // largest horizontal extent when that is more.
    double inPlace = 0.3;
    // A moved object keeps its size: each sorted extent within this ratio of the stored one.
    double sizeRatio = 2.0;
    // A stored object counts as missing only where the capture looked: inside the
    // floor rectangle of what it observed, grown by this margin.
    double coverageMargin = 0.5;
};

enum class Fate : std::uint8_t { Unchanged, Moved, Missing, Unseen };

// What became of each stored object, and which observed object it is now.
struct ObjectFate {
    model::NodeId stored = model::kNoNode;
    model::NodeId observed = model::kNoNode;  // Unchanged, Moved
    Fate fate = Fate::Unchanged;
};

struct Matching {
    std::vector<ObjectFate> stored;    // one per stored object, in the stored order
    std::vector<model::NodeId> added;  // observed objects no stored object matches
};

// The stamps every new scene carries, wherever it comes from (an import, an ingest, the C API):
// its capture time (now, when the source gives none) and on each object `first_seen_at` and
// `last_seen_at` = that time, unless the source already has them (a scene exported and imported
// again keeps its history).
void stampSeen(model::SceneData& scene, const std::string& now);

// `stored` holds database ids (its visible objects are matched), `observed` local ids.
Matching matchObjects(const model::SceneData& stored, const model::SceneData& observed, const MatchRules& rules = {});

struct SceneUpdate {
    model::SceneData next;                     // the new version, local ids 1..n, parents to assign
    std::vector<model::ObjectChange> changes;  // `before`: stored ids; `after`: local ids of `next`
    // (stored database id, local id in `next`) of every stored node the new version keeps, so
    // its evidence moves with it.
    std::vector<std::pair<model::NodeId, model::NodeId>> carried;
    std::size_t unchanged = 0, moved = 0, added = 0, missing = 0, unseen = 0;
};

// The next version: the stored structure and unseen objects as they were; objects seen again
// with `captures` + 1 and `last_seen_at` = `time`; moved ones at their new box with `moved_at`;
// new ones with `first_seen_at`; missing ones left out (the history keeps them). Stored
// relations between nodes that stayed where they were are kept, the capture's relations
// between the nodes it placed are added. Objects that moved or are new get their parents anew.
SceneUpdate planUpdate(const model::SceneData& stored, const model::SceneData& observed, const std::string& time,
                       const MatchRules& rules = {});

}  // namespace smql::history
