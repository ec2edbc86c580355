// The embeddable engine: open a database, run SMQL statements, get rows.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/binder/parameters.hpp"
#include "engine/binder/shape_cache.hpp"
#include "engine/guide/route_graph.hpp"
#include "model/result.hpp"
#include "model/types.hpp"
#include "storage/check.hpp"

namespace smql {

namespace storage {
class Database;
}
namespace ask {
class Translator;
}

class Engine;

// A statement parsed once and run many times with different values for its placeholders
// (`FIND ? WHERE near(?, ?)`; docs/language.md, "Parameters"), as sqlite3_stmt. Running it
// binds, plans and executes the parsed statement: the parser never sees it again, and a bound
// value is data, never SMQL text. Made by Engine::prepare; the Engine must outlive it. Not for
// use by two threads at once (the Engine is).
class PreparedStatement {
public:
    // Placeholders are numbered 1..parameterCount(): `?` in the order written, `$n` by n.
    std::size_t parameterCount() const;
    // Binds placeholder `index` (1-based). Text for a name or a string; std::int64_t, double or
    // Length (metres) for a number, a distance or LIMIT; std::vector<float> for SIMILAR TO's query
    // in the space of the nodes' stored embeddings (docs/similarity.md); std::monostate for NULL.
    // Throws Error(Usage) for an index out of range or a value its place cannot take (text for LIMIT).
    void bind(std::size_t index, ParameterValue value);
    // Every placeholder unbound again; running then fails naming the first.
    void clearBindings();
    // Runs the statement with the values bound now. Throws smql::Error as Engine::execute does,
    // and Error(Usage) naming a placeholder without a value.
    ResultSet execute();
    // The statement's text, for error messages.
    const std::string& text() const;

private:
    friend class Engine;
    PreparedStatement(Engine& engine, std::shared_ptr<const ast::Statement> statement);

    Engine* engine_;
    std::shared_ptr<const ast::Statement> statement_;
    std::vector<binder::ParameterSlot> slots_;
    std::vector<std::optional<ParameterValue>> values_;
};

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

    // Parses one statement, placeholders allowed, to run later with values. Throws smql::Error
    // for a syntax error, and Error(Usage) when `text` holds more than one statement.
    PreparedStatement prepare(std::string_view text);

    // How the cache of statement shapes has done: a text that differs from one run before only in
    // its literals skips the parser (docs/language.md, "Statement shapes"; SET shape_cache).
    binder::ShapeCacheStats shapeCacheStats() const;

    // Stores an imported scene in one write transaction, after giving its
    // objects their parents (support, else the nearest upright anchor).
    // Returns the new scene's id; the scene becomes the current one.
    model::NodeId importScene(model::SceneData scene);
    // Before a long ingest: throws what importScene (a scene named `name` exists) or updateScene
    // (no scene `update`) would throw after it, so that minutes of work are not lost to a name.
    void checkIngestTarget(const std::string& name, const std::string& update);
    // A stored scene in the import/export form (local ids renumbered 1..n).
    model::SceneData exportScene(const std::string& name);
    // A stored scene as it is, with its database ids (the most recent when `name` is empty).
    model::SceneData readScene(const std::string& name);
    // Rewrites stored nodes' attributes, text, confidence or box in one transaction
    // (storage::WriteTransaction::updateNodes says what may change).
    void updateNodes(const std::vector<model::Node>& nodes);
    // The capture's points of a stored scene (the most recent when `name` is empty) as the PLY file
    // `smql export ply --points` writes (model/points.hpp). Throws Error(Input) when the scene has
    // none (imported layouts) or they are damaged.
    std::string scenePoints(const std::string& name);
    // The evidence a node carries (the crops an ingest kept), by database id, in name order.
    // Throws Error(Binding) when the database has no such node.
    std::vector<model::Blob> evidence(model::NodeId node);

    // Stops the statement running in another thread (Error(Interrupted)); safe from any thread and
    // from a signal handler. Without a running statement it does nothing.
    void interrupt();

    // What an update found: counts of each kind of object, and the changes one by one
    // (`before`: ids of the superseded version, kept in its history; `after`: ids of the new one).
    struct SceneUpdateReport {
        std::string scene;
        std::string time;           // the capture time the new version carries
        std::uint64_t version = 0;  // the number the superseded version has in the history
        std::size_t unchanged = 0, moved = 0, added = 0, missing = 0, unseen = 0;
        std::vector<model::ObjectChange> changes;
        // "updated scene 'den' as of ...: 17 objects seen again where they were, 1 moved, ..."
        std::string summary() const;
        // When no stored object was seen again in place and most captured ones are new (three or more stored and
        // new): the capture may be of another place, or started from another origin.
        std::optional<std::string> warning() const;
    };
    // Merges a new capture of a place into its stored scene `name` (the current one when empty):
    // objects are matched to the stored ones (docs/history.md), the scene becomes the next
    // version (seen-again, moved and new objects; missing ones left out) and the superseded
    // version goes to the scene's history with the changes, so SHOW CHANGES and AS OF can read
    // it. The capture's time is observed.info.captureTime (now, when it has none), and must not
    // be before the stored version's. One write transaction: concurrent updates of a scene
    // serialise and neither is lost.
    SceneUpdateReport updateScene(const std::string& name, const model::SceneData& observed);

    // What a top-down map of a scene shows: its nodes, with database ids, and the decision-point
    // graph guidance routes on (docs/guidance.md).
    struct SceneMap {
        model::SceneData scene;
        guide::RouteGraph graph;
        guide::FreeSpace space;  // the free floor the graph lies on, and what blocks the rest
    };
    // The scene `name` (the current one when empty).
    SceneMap sceneMap(const std::string& name);

    // The translator ASK uses from now on: null restores the built-in rule-based one. Plug in a
    // client of a language model's endpoint here (docs/ask.md); the SMQL it returns is parsed,
    // bound, planned and run like any statement.
    void setAskTranslator(std::shared_ptr<const ask::Translator> translator);
    // What ASK translates with: the endpoint's URL of a plugged-in model translator (SET translator,
    // smql_set_translator), or "built-in".
    std::string askTranslatorName() const;

    // The scene that queries run against (SHOW SCENES lists them; USE SCENE sets it).
    std::string currentScene() const;
    // The categories of things in every scene: camera frames and descriptions left out.
    std::vector<std::string> knownCategories() const;

    storage::Database& database();

    struct State;

private:
    friend class PreparedStatement;
    explicit Engine(std::unique_ptr<State> state);
    ResultSet executePrepared(const std::shared_ptr<const ast::Statement>& statement,
                              const std::vector<std::optional<ParameterValue>>& values);
    std::unique_ptr<State> state_;
};

// The language as a front end needs it without the parser (the shell, smql_complete): whether a
// text ends with a complete statement (a closing `;` outside strings and parentheses), as
// sqlite3_complete says; the keywords and the sides of references, for completion.
bool statementComplete(std::string_view text);
const std::vector<std::string>& languageKeywords();
const std::vector<std::string>& referenceSides();

}  // namespace smql
