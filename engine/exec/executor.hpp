// Runs a planned statement over one read transaction. One file per statement
// (exec_<statement>.cpp); node sets, frames and FIND's filter live in
// executor.cpp and exec_find.cpp. An Executor lives for one statement: its
// caches (resolved sets, membership tables) are indexed by the statement's
// NodeSet ids and die with it.
#pragma once

#include <atomic>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/binder/bound.hpp"
#include "engine/catalog/session.hpp"
#include "engine/planner/planner.hpp"
#include "model/result.hpp"

namespace smql::storage {
class Database;
class ReadTransaction;
}  // namespace smql::storage

namespace smql::exec {

// RELATE's sentence for one pair: "lamp#13 is left of window#9; near window#9 (0.4 m)", or that no
// relation holds. CHECK gives it as its evidence.
std::string relationSentence(std::string_view subjectLabel, std::string_view objectLabel, double distance,
                             const std::vector<relations::RelationHit>& hits);
std::string relationSentence(const model::Node& a, const model::Node& b,
                             const std::vector<relations::RelationHit>& hits);

// FIND of a category across all scenes, answered from the label index alone (no snapshot, no plan):
// the rows of the nodes that `keys` (a BoundCatalogFind's) name, `count` of them in all, up to
// `limit`. What the executor runs for a BoundCatalogFind, and what the engine runs for a FIND whose
// category was bound in the same committed transaction (engine.cpp, rememberedFind).
ResultSet catalogFind(const storage::ReadTransaction& txn, const catalog::Session& session, std::string_view category,
                      const std::vector<std::string>& keys, std::optional<std::int64_t> limit, std::uint64_t count);

// Throws Error(Limit) when an answer of `rows` rows is over the session's max_rows.
void checkRowLimit(const catalog::Session& session, std::size_t rows);

struct Hit {
    catalog::Slot slot;
    double distance = 0;    // to the ORDER BY / NEAREST TO reference, when there is one
    double similarity = 0;  // to the SIMILAR TO text, when there is one
};

class Executor {
public:
    // `session` is read for the thresholds and limits, and changed by USE and SET. When `interrupt`
    // turns true (from another thread), the statement stops with Error(Interrupted). `db` is where
    // DROP and RENAME write (in a write transaction of their own); null for read-only callers.
    Executor(const storage::ReadTransaction& txn, catalog::Session& session, const planner::Plan& plan,
             const std::atomic<bool>* interrupt = nullptr, storage::Database* db = nullptr);

    ResultSet run();
    // The nodes a FIND plan (the statement's or a sub-query's) answers, in order.
    std::vector<Hit> find(const planner::FindPlan& plan);

private:
    ResultSet run(const binder::BoundFind& find);
    ResultSet run(const binder::BoundCatalogFind& find);
    ResultSet run(const binder::BoundRelate& relate);
    ResultSet run(const binder::BoundCheck& check);
    ResultSet run(const binder::BoundShowCategories& show);
    ResultSet run(const binder::BoundShowAttributes& show);
    ResultSet run(const binder::BoundDescribe& describe);
    ResultSet run(const binder::BoundShowScenes& show);
    ResultSet run(const binder::BoundShowSettings& show);
    ResultSet run(const binder::BoundShowTree& show);
    ResultSet run(const binder::BoundShowChanges& show);
    ResultSet run(const binder::BoundDropScene& drop);
    ResultSet run(const binder::BoundRenameScene& rename);
    ResultSet run(const binder::BoundShowGraph& show);
    ResultSet run(const binder::BoundGuide& guide);
    ResultSet run(const binder::BoundUse& use);
    ResultSet run(const binder::BoundSet& set);
    ResultSet run(const binder::BoundExplain& explain);
    ResultSet run(const binder::BoundAsk& ask);

    const catalog::SceneSnapshot& scene() const { return *plan_.statement->scene; }
    // Called once per unit of work (a candidate, a pair): throws once the statement is interrupted.
    void poll() {
        if (interrupt_ && (++work_ & 1023) == 0 && interrupt_->load(std::memory_order_relaxed)) interrupted();
    }
    [[noreturn]] static void interrupted();
    void checkRows(std::size_t rows) const;
    // The one visible node with a box a set holds; an error that lists the candidates (and how to
    // pick one) when it holds several, and says so when it holds none. `role` names the end.
    catalog::Slot single(const binder::NodeSet& set, std::string_view role);
    // The nodes of a set: as bound, or resolved now (a side in `frame`, a sub-query's answer).
    const std::vector<catalog::Slot>& slots(const binder::NodeSet& set, const relations::Frame& frame);
    const std::vector<catalog::Slot>& resolveSide(const binder::NodeSet& set, const relations::Frame& frame);
    // Which slots a large set holds, for R-tree lookups of references.
    const std::vector<char>& membership(const binder::NodeSet& set, const relations::Frame& frame);
    // A set's nodes by the low x of their world bounds, made once per statement: the references whose
    // bounds meet a predicate's region lie from the region's low x less the widest one's width to
    // its high x, so each candidate tests those few rather than every reference (a hall's 130 chairs).
    struct ReferenceSweep {
        std::vector<model::Aabb> bounds;   // by bounds.min.x; nodes with NaN x bounds (which meet nothing) left out
        std::vector<catalog::Slot> slots;  // in the same order
        double widest = 0;                 // the largest width along x
    };
    const ReferenceSweep& sweepOf(const binder::NodeSet& set, const relations::Frame& frame);
    relations::Frame frame(const binder::BoundView& view);
    relations::Frame defaultFrame() const;

    // The one way the executor decides a predicate over two (or three) of the scene's nodes: FIND's
    // filter, its index probes and sub-queries, COUNT, CHECK and RELATE all ask here, with the scene
    // as what stands between and the statement's thresholds.
    double score(relations::Predicate p, const model::Node& a, const model::Node& b, const relations::Frame& frame,
                 const model::Node* c = nullptr, std::optional<double> writtenDistance = std::nullopt) const;
    std::vector<relations::RelationHit> relate(const model::Node& a, const model::Node& b,
                                               const relations::Frame& frame) const;

    bool matches(const binder::BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame);
    bool holdsForSome(const binder::BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame);
    // A predicate one of whose arguments is HERE: related to a person standing where the viewer stands
    // (relations::viewerAt).
    bool holdsForHere(const binder::BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame);
    bool compare(const binder::BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame);
    // distance(x) of a node: to the nearest node of `refs` other than itself; infinite when there is none.
    double distanceToOthers(catalog::Slot slot, const std::vector<catalog::Slot>& refs) const;
    // distance(x) of a node with a box: to x's nodes other than itself, or for HERE along the floor from where the
    // viewer stands to its footprint (the viewer's height does not count: how far a person must walk).
    double distanceTo(catalog::Slot slot, const binder::NodeSet& to, const relations::Frame& frame);
    // The world bounds a distance is measured from: a node's, or for HERE the vertical line where the viewer stands.
    static model::Aabb standingLine(const relations::Frame& frame);
    bool inTarget(const binder::Target& target, catalog::Slot slot, const relations::Frame& frame);
    std::vector<Hit> nearestFirst(const planner::FindPlan& plan, const relations::Frame& frame);
    struct SimilaritySpace {
        const similar::EmbeddingIndex& index;
        similar::Vector text;           // the embedded text, in the built-in embedder's space
        std::span<const float> vector;  // the bound vector (the bound statement keeps it), else empty
        std::span<const float> query() const { return vector.empty() ? std::span<const float>(text) : vector; }
    };
    SimilaritySpace similaritySpace(const binder::BoundSimilarTo& similarTo) const;
    std::vector<Hit> similarFirst(const planner::FindPlan& plan, const relations::Frame& frame);
    void rankBySimilarity(const planner::FindPlan& plan, std::vector<Hit>& hits) const;
    std::vector<Hit> filtered(const planner::FindPlan& plan, const relations::Frame& frame);
    // Where the candidates of an R-tree probe around one reference's bounds lie (a superset).
    model::Aabb probeRegion(const binder::BoundExpr& term, const model::Aabb& around) const;
    void orderByAttribute(const planner::FindPlan& plan, std::vector<Hit>& hits) const;
    ResultSet returned(const binder::BoundFind& find, const std::vector<Hit>& hits) const;

    const storage::ReadTransaction& txn_;
    catalog::Session& session_;
    const planner::Plan& plan_;
    const std::atomic<bool>* interrupt_;
    storage::Database* db_;
    std::uint64_t work_ = 0;
    const relations::Thresholds thresholds_;                           // as the statement started
    std::vector<std::optional<std::vector<catalog::Slot>>> resolved_;  // by NodeSet id
    std::vector<std::vector<char>> membership_;                        // by NodeSet id; empty until needed
    std::vector<std::optional<ReferenceSweep>> sweeps_;                // by NodeSet id
};

}  // namespace smql::exec
