// The embeddable engine: open a database, run SMQL statements, get rows.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "model/types.hpp"
#include "model/result.hpp"
#include "storage/check.hpp"

namespace smql {

namespace storage { class Database; }

class Engine {
public:
    // Opens (creating if needed) the database in `directory`. Throws smql::Error.
    static std::unique_ptr<Engine> open(const std::string& directory, bool readOnly = false);
    // Verifies the database in `directory` without writing to it (storage::checkDatabase says what
    // is checked); a database that cannot be opened is a problem in the report, not an exception.
    static storage::CheckReport check(const std::string& directory);
    ~Engine();

    // Runs every `;`-separated statement of `text`; returns one ResultSet per
    // statement. Throws smql::Error on the first failing statement; statements
    // before it have run (each is atomic on its own).
    std::vector<ResultSet> execute(std::string_view text);
    // The same, handing each statement's result over as soon as it is ready,
    // so a caller can print the statements before a failing one.
    void execute(std::string_view text, const std::function<void(ResultSet&&)>& onResult);

    // Stores an imported scene in one write transaction, after giving its
    // objects their parents (support, else the nearest upright anchor).
    // Returns the new scene's id; the scene becomes the current one.
    model::NodeId importScene(model::SceneData scene);
    // A stored scene in the import/export form (local ids renumbered 1..n).
    model::SceneData exportScene(const std::string& name);
    // A stored scene as it is, with its database ids (the most recent when `name` is empty).
    model::SceneData readScene(const std::string& name);
    // Rewrites stored nodes' attributes, text, confidence or box in one transaction
    // (storage::WriteTransaction::updateNodes says what may change).
    void updateNodes(const std::vector<model::Node>& nodes);
    // The evidence a node carries (the crops an ingest kept), by database id, in name order.
    // Throws Error(Binding) when the database has no such node.
    std::vector<model::Blob> evidence(model::NodeId node);

    // Stops the statement running in another thread (Error(Interrupted)); safe from any thread and
    // from a signal handler. Without a running statement it does nothing.
    void interrupt();

    // Which objects of a new capture of a place are objects already stored
    // for it: pairs of (stored node id, observed node id).
    using ObjectMatcher = std::function<std::vector<std::pair<model::NodeId, model::NodeId>>(
        const model::SceneData& stored, const model::SceneData& observed)>;
    struct SceneRefresh {
        std::size_t seenAgain = 0;      // stored objects the capture saw again (and that were updated)
        std::size_t storedObjects = 0;  // visible objects of the stored scene
    };
    // Merges a new capture of the place into the stored scene `name` (the
    // most recent when empty): each stored object `match` pairs with an
    // observed one gets `captures` = stored + 1 (1 when unset) and
    // `last_seen_at` = observed.info.captureTime; nothing else changes. The
    // read and the write are one write transaction, so refreshes of one scene
    // from several processes at once never lose one another's counts.
    SceneRefresh refreshScene(const std::string& name, const model::SceneData& observed, const ObjectMatcher& match);

    // The scene that queries run against (SHOW SCENES lists them; USE SCENE sets it).
    std::string currentScene() const;
    std::vector<std::string> knownCategories() const;

    storage::Database& database();

    struct State;

private:
    explicit Engine(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace smql
