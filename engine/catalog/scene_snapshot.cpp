#include "engine/catalog/scene_snapshot.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "model/category.hpp"
#include "model/embedding.hpp"
#include "model/error.hpp"
#include "storage/database.hpp"

namespace smql::catalog {

namespace {

// A scene's first spatial queries scan its block bounds (125 for 2,000 boxes, a fraction of a
// microsecond), and the levels above them are packed once 32 scans have run: packing takes 3 us warm
// but 8-45 where the caches are cold, as in a scene's first query. At 8 scans the first FIND of
// smql_bench paid for it (p50 over 30 scenes 109-125 us against 95-104 at 32).
constexpr std::size_t kScansBeforeLevels = 32;

// Whether the bounds of a block or of a node above the blocks may hold boxes that meet `region`:
// a NaN coordinate among them (a box of a database written before storage refused such boxes) rules
// nothing out, where the boxes' own test
// (relations::intersects) fails every comparison with it and would hide the node's other boxes.
bool mayMeet(const model::Aabb& node, const model::Aabb& region) {
    return !(node.max.x < region.min.x || region.max.x < node.min.x || node.max.y < region.min.y ||
             region.max.y < node.min.y || node.max.z < region.min.z || region.max.z < node.min.z);
}

// mayMeet and relations::intersects on stored bounds and a region rounded outward to floats (what
// meets the region meets the rounded one): blocks and boxes are tested in single precision, as stored.
bool mayMeet(const storage::IndexBounds& node, const storage::IndexBounds& region) {
    return !(node.maxX < region.minX || region.maxX < node.minX || node.maxY < region.minY || region.maxY < node.minY ||
             node.maxZ < region.minZ || region.maxZ < node.minZ);
}

bool meets(const storage::IndexBounds& box, const storage::IndexBounds& region) {
    return box.minX <= region.maxX && region.minX <= box.maxX && box.minY <= region.maxY && region.minY <= box.maxY &&
           box.minZ <= region.maxZ && region.minZ <= box.maxZ;
}

bool hasNaN(const model::Aabb& a) { return std::isnan(a.min.x + a.min.y + a.min.z + a.max.x + a.max.y + a.max.z); }

// Squared gap between a block's bounds and a region, as a bound below its boxes' gaps: an axis with a
// NaN coordinate (mayMeet) counts no gap.
double blockGap(const model::Aabb& block, const model::Aabb& region) {
    auto axis = [](double low, double high, double from, double to) {
        const double d = std::max(low - to, from - high);
        return d > 0 ? d * d : 0.0;
    };
    return axis(block.min.x, block.max.x, region.min.x, region.max.x) +
           axis(block.min.y, block.max.y, region.min.y, region.max.y) +
           axis(block.min.z, block.max.z, region.min.z, region.max.z);
}

// Squared gap between a box and a region (0 when they meet): Boost.Geometry's comparable distance.
// A box with a NaN coordinate (mayMeet) has no place, and comes last in a walk nearest first.
double squaredGap(const model::Aabb& box, const model::Aabb& region) {
    return hasNaN(box) ? std::numeric_limits<double>::infinity() : blockGap(box, region);
}

// A node as the snapshot reads it: its category by the canonical name (the constructor says why).
void canonicalise(model::Node& node) {
    if (node.kind != model::NodeKind::Scene && !model::isCategoryName(node.category))
        node.category = model::categoryName(node.category);
}

}  // namespace

std::shared_ptr<const SceneSnapshot> SceneSnapshot::load(const storage::ReadTransaction& txn,
                                                         const model::SceneInfo& info) {
    if (std::optional<storage::SceneIndex> index = txn.sceneIndex(info)) {
        std::shared_ptr<SceneSnapshot> snap(new SceneSnapshot(info, std::move(*index), /*historical=*/false));
        snap->readThrough(&txn);
        return snap;
    }
    std::vector<model::Node> nodes;
    nodes.reserve(info.nodeCount + 1);
    txn.forEachNodeInScene(info.id, [&](const model::Node& n) { nodes.push_back(n); });
    std::shared_ptr<SceneSnapshot> snap(
        new SceneSnapshot(info, storage::SceneIndex::of(nodes, info.version), /*historical=*/false));
    snap->holdAll(std::move(nodes));
    snap->readThrough(&txn);
    return snap;
}

std::shared_ptr<const SceneSnapshot> SceneSnapshot::fromVersion(const model::SceneVersion& version) {
    std::shared_ptr<SceneSnapshot> snap(
        new SceneSnapshot(version.info, storage::SceneIndex::of(version.nodes, version.info.version), true));
    snap->holdAll(version.nodes);
    snap->relations_ = version.relations;
    return snap;
}

SceneSnapshot::SceneSnapshot(model::SceneInfo info, storage::SceneIndex index, bool historical)
    : info_(std::move(info)), index_(std::move(index)), historical_(historical) {
    const auto count = static_cast<Slot>(index_.entries.size());
    decoded_ = std::make_unique<std::atomic<const Decoded*>[]>(count);
    // A stored scene's slot 0 is its scene node, whose id is the scene's; holdAll checks the ids
    // of a scene decoded whole, which may not be one block.
    firstId_ = info_.id;
    idsInOneBlock_ = true;
    // One pass counts each list, so each is allocated once at its size, and finds the scene node's
    // category; a second fills them.
    constexpr std::size_t kKinds = 6;
    std::vector<std::uint32_t> perCategory(index_.categories.size());
    std::vector<bool> sceneName(index_.categories.size());
    std::array<std::uint32_t, kKinds> shownPerKind{};
    for (const auto& e : index_.entries) {
        ++perCategory[e.category];
        if (e.kind == model::NodeKind::Scene)
            sceneName[e.category] = true;
        else
            shownPerKind[static_cast<std::size_t>(e.kind)] += !e.hidden;
    }
    // Categories are read by their canonical name (model/category.hpp): a scene stored before names
    // were canonical ("trash can", "Chairs") answers as one imported now does. Normalising here, on
    // read, rather than rewriting the stored records, leaves the database as it was written: it
    // opens read-only, older programs still read it, `smql check` still finds its records and keys
    // in agreement, and the fold costs one pass over the scene's few distinct names. The scene
    // node's category is the scene's name and stays as written.
    for (std::size_t c = 0; c < index_.categories.size(); ++c)
        if (!sceneName[c] && !model::isCategoryName(index_.categories[c]))
            index_.categories[c] = model::categoryName(index_.categories[c]);
    std::vector<std::vector<Slot>*> lists(index_.categories.size());
    slotsByCategory_.reserve(lists.size());
    for (std::size_t c = 0; c < lists.size(); ++c) {
        lists[c] = &slotsByCategory_[index_.categories[c]];
        lists[c]->reserve(lists[c]->capacity() + perCategory[c]);  // two stored spellings may fold to one
    }
    shownByKind_.resize(kKinds);
    for (std::size_t k = 0; k < kKinds; ++k) shownByKind_[k].reserve(shownPerKind[k]);
    for (Slot s = 0; s < count; ++s) {
        const auto& e = index_.entries[s];
        lists[e.category]->push_back(s);
        if (e.kind != model::NodeKind::Scene && !e.hidden) shownByKind_[static_cast<std::size_t>(e.kind)].push_back(s);
    }
    walls_ = &withCategory(relations::kWall);
    blocks_.reserve(index_.blockBounds.size());
    for (const storage::IndexBounds& block : index_.blockBounds) blocks_.push_back(block.aabb());
}

void SceneSnapshot::holdAll(std::vector<model::Node> nodes) {
    allNodes_ = std::move(nodes);
    for (model::Node& node : allNodes_) canonicalise(node);
    const auto count = static_cast<Slot>(allNodes_.size());
    firstId_ = count > 0 ? allNodes_.front().id : model::kNoNode;
    for (Slot s = 0; s < count; ++s) idsInOneBlock_ = idsInOneBlock_ && allNodes_[s].id == firstId_ + s;
    if (!idsInOneBlock_) slotById_.reserve(count);
    for (Slot s = 0; s < count; ++s) {
        if (!idsInOneBlock_) slotById_.emplace(allNodes_[s].id, s);
        decoded_[s].store(&decodedLines_.emplace_back(Decoded{&allNodes_[s], model::worldAabb(allNodes_[s].box)}),
                          std::memory_order_release);
    }
    std::call_once(allDecoded_, [] {});  // nodes() has them already
}

void SceneSnapshot::readThrough(const storage::ReadTransaction* txn) const {
    std::lock_guard lock(readMutex_);
    reader_ = txn;
}

const model::Node& SceneSnapshot::decode(Slot slot) const {
    std::lock_guard lock(readMutex_);
    if (const Decoded* decoded = decoded_[slot].load(std::memory_order_relaxed)) return *decoded->node;
    assert(reader_ && "a snapshot's nodes are read while a statement names its transaction (readThrough)");
    const model::NodeId id = firstId_ + slot;
    model::Node node;
    const auto& entry = index_.entries[slot];
    // The index and the record must agree on what the index answered from.
    const bool read = reader_->readNode(id, node);
    model::Aabb exact;
    if (read) {
        // The index's names are canonical already (the constructor folded them), so a record that
        // names its category as the index does needs no fold: most do, and the fold's test of the
        // word was a seventh of a node's decoding.
        if (node.category != category(slot)) canonicalise(node);
        exact = model::worldAabb(node.box);
    }
    // The index's bounds must hold the record's: a search over them ruled out what they rule out.
    const model::Aabb indexed = entry.bounds.aabb();
    const bool held = !(indexed.min.x > exact.min.x || indexed.min.y > exact.min.y || indexed.min.z > exact.min.z ||
                        indexed.max.x < exact.max.x || indexed.max.y < exact.max.y || indexed.max.z < exact.max.z);
    if (!read || node.scene != info_.id || node.kind != entry.kind || node.geometry != entry.geometry ||
        node.hidden != (entry.hidden != 0) || node.category != category(slot) || !held)
        throw Error(ErrorKind::Storage,
                    fmt::format("the scene index of scene '{}' does not match the record of node #{}", info_.name, id),
                    std::nullopt, "smql check DB verifies the database");
    const model::Node& kept = decodedNodes_.emplace_back(std::move(node));
    decoded_[slot].store(&decodedLines_.emplace_back(Decoded{&kept, exact}), std::memory_order_release);
    return kept;
}

const std::vector<model::Node>& SceneSnapshot::nodes() const {
    std::call_once(allDecoded_, [&] {
        std::vector<model::Node> all;
        all.reserve(size());
        for (Slot s = 0; s < size(); ++s) all.push_back(node(s));
        allNodes_ = std::move(all);
    });
    return allNodes_;
}

const std::vector<model::Relation>& SceneSnapshot::storedRelations() const {
    std::lock_guard lock(readMutex_);
    if (!relations_) {
        assert(reader_ && "a snapshot's relations are read while a statement names its transaction (readThrough)");
        std::vector<model::Relation> relations;
        reader_->forEachRelationInScene(info_.id, [&](const model::Relation& r) { relations.push_back(r); });
        relations_ = std::move(relations);
    }
    return *relations_;
}

bool SceneSnapshot::levelsBuilt() const {
    if (levelsBuilt_.load(std::memory_order_acquire)) return true;
    if (scans_.fetch_add(1, std::memory_order_relaxed) < kScansBeforeLevels) return false;
    std::call_once(levelsBuilding_, [&] {
        for (const std::vector<model::Aabb>* below = &blocks_; below->size() > storage::SceneIndex::kBlock;
             below = &levels_.back().bounds) {
            Level level;
            level.order.resize(below->size());
            std::iota(level.order.begin(), level.order.end(), 0U);
            level.bounds = storage::packTiles(*below, level.order);
            levels_.push_back(std::move(level));
        }
        levelsBuilt_.store(true, std::memory_order_release);
    });
    return true;
}

void SceneSnapshot::intersecting(const model::Aabb& region, std::vector<Slot>& out) const {
    // Down from the top level's nodes (or every block, before the levels are made or when the
    // blocks are few) to the blocks that meet the region.
    const storage::IndexBounds rounded = storage::IndexBounds::around(region);
    if (!levelsBuilt() || levels_.empty()) {
        for (std::size_t b = 0; b < index_.blockBounds.size(); ++b)
            if (mayMeet(index_.blockBounds[b], rounded)) collect(0, b, region, rounded, out);
        return;
    }
    const auto& top = levels_.back().bounds;
    for (std::size_t n = 0; n < top.size(); ++n)
        if (mayMeet(top[n], region)) collect(levels_.size(), n, region, rounded, out);
}

void SceneSnapshot::collect(std::size_t level, std::size_t node, const model::Aabb& region,
                            const storage::IndexBounds& rounded, std::vector<Slot>& out) const {
    constexpr std::size_t kRun = storage::SceneIndex::kBlock;
    const auto& order = level == 0 ? index_.spatialOrder : levels_[level - 1].order;
    const std::size_t end = std::min(order.size(), (node + 1) * kRun);
    if (level == 0) {
        for (std::size_t i = node * kRun; i < end; ++i)
            if (meets(index_.entries[order[i]].bounds, rounded)) out.push_back(order[i]);
        return;
    }
    for (std::size_t i = node * kRun; i < end; ++i) {
        const std::uint32_t child = order[i];
        if (mayMeet(level == 1 ? blocks_[child] : levels_[level - 2].bounds[child], region))
            collect(level - 1, child, region, rounded, out);
    }
}

SceneSnapshot::NearestWalk::NearestWalk(const SceneSnapshot& scene, const model::Aabb& region)
    : scene_(scene), region_(region) {
    const auto& blocks = scene.blocks_;
    blocks_.reserve(blocks.size());
    for (std::uint32_t b = 0; b < blocks.size(); ++b) blocks_.emplace_back(blockGap(blocks[b], region), b);
    std::make_heap(blocks_.begin(), blocks_.end(), std::greater<>());
}

std::optional<Slot> SceneSnapshot::NearestWalk::next() {
    const auto& order = scene_.index_.spatialOrder;
    // Take in blocks while the nearest block left is nearer than the nearest box taken in.
    while (!blocks_.empty() && (boxes_.empty() || blocks_.front().first < boxes_.front().first)) {
        std::pop_heap(blocks_.begin(), blocks_.end(), std::greater<>());
        const std::size_t b = blocks_.back().second;
        blocks_.pop_back();
        const std::size_t end = std::min(order.size(), (b + 1) * storage::SceneIndex::kBlock);
        for (std::size_t i = b * storage::SceneIndex::kBlock; i < end; ++i) {
            boxes_.emplace_back(squaredGap(scene_.bounds(order[i]), region_), order[i]);
            std::push_heap(boxes_.begin(), boxes_.end(), std::greater<>());
        }
    }
    if (boxes_.empty()) return std::nullopt;
    std::pop_heap(boxes_.begin(), boxes_.end(), std::greater<>());
    const Slot slot = boxes_.back().second;
    boxes_.pop_back();
    return slot;
}

const SceneSnapshot::Guidance& SceneSnapshot::guidance() const {
    std::call_once(guidanceBuilt_, [&] {
        guide::GraphOptions options;
        guide::FreeSpace space(nodes(), options);
        guide::RouteGraph graph = guide::buildGraph(nodes(), space, options);
        guidance_ = std::make_unique<const Guidance>(Guidance{std::move(space), std::move(graph), options});
    });
    return *guidance_;
}

const SceneSnapshot::Guidance& SceneSnapshot::crowdedGuidance() const {
    std::call_once(crowdedBuilt_, [&] {
        guide::GraphOptions options;
        options.pushAside = true;
        guide::FreeSpace space(nodes(), options);
        guide::RouteGraph graph = guide::buildGraph(nodes(), space, options);
        crowded_ = std::make_unique<const Guidance>(Guidance{std::move(space), std::move(graph), options});
    });
    return *crowded_;
}

const similar::EmbeddingIndex& SceneSnapshot::embeddings() const {
    std::call_once(embeddingsBuilt_, [&] {
        std::vector<similar::Vector> vectors;
        vectors.reserve(size());
        for (const auto& node : nodes()) vectors.push_back(similar::embedNode(node));
        embeddings_ = std::make_unique<const similar::EmbeddingIndex>(std::move(vectors));
    });
    return *embeddings_;
}

const similar::EmbeddingIndex* SceneSnapshot::storedEmbeddings(const storage::ReadTransaction& txn) const {
    std::call_once(storedEmbeddingsRead_, [&] {
        if (historical_) return;
        const std::vector<model::Node>& all = nodes();
        std::vector<float> vectors;
        std::size_t dimensions = 0;
        for (std::size_t s = 0; s < all.size(); ++s) {
            auto blob = txn.blob(all[s].id, model::kEmbeddingBlob);
            if (!blob) continue;
            std::vector<float> vector;
            try {
                vector = model::readEmbedding(*blob);
            } catch (const Error& e) {
                throw Error(ErrorKind::Storage, fmt::format("the embedding of {}: {}", label(all[s]), e.message()),
                            std::nullopt, "smql check DB verifies the database");
            }
            if (dimensions == 0) {
                dimensions = vector.size();
                vectors.resize(all.size() * dimensions);
            }
            // Storage refuses a scene whose embeddings differ in length.
            if (vector.size() != dimensions)
                throw Error(ErrorKind::Storage,
                            fmt::format("the embedding of {} has {} dimensions, others in scene '{}' have {}",
                                        label(all[s]), vector.size(), info_.name, dimensions),
                            std::nullopt, "smql check DB verifies the database");
            const std::vector<float> unit = similar::unitVector(vector);
            std::copy(unit.begin(), unit.end(), vectors.begin() + static_cast<std::ptrdiff_t>(s * dimensions));
        }
        if (dimensions == 0) return;
        // An external model's cosine has no floor that means "unrelated": every node with a vector ranks.
        storedEmbeddings_ =
            std::make_unique<const similar::EmbeddingIndex>(dimensions, vectors, std::numeric_limits<float>::lowest());
    });
    return storedEmbeddings_.get();
}

std::optional<Slot> SceneSnapshot::slotOf(model::NodeId id) const {
    if (idsInOneBlock_) {
        if (id < firstId_ || id - firstId_ >= size()) return std::nullopt;
        return static_cast<Slot>(id - firstId_);
    }
    auto it = slotById_.find(id);
    if (it == slotById_.end()) return std::nullopt;
    return it->second;
}

void SceneSnapshot::buildLinks() const {
    std::call_once(linksBuilt_, [&] {
        const std::vector<model::Node>& all = nodes();
        const auto count = static_cast<Slot>(all.size());
        children_.resize(count);
        slotBySource_.reserve(count);
        for (Slot s = 0; s < count; ++s) {
            if (all[s].sourceId) slotBySource_.emplace(*all[s].sourceId, s);
            if (std::optional<Slot> parent = slotOf(all[s].parent)) children_[*parent].push_back(s);
        }
    });
}

const std::vector<std::string>& SceneSnapshot::attributeNames() const {
    std::call_once(attributeNamesFound_, [&] {
        // A scene has a handful of attribute names over thousands of nodes: each is looked for
        // among those found so far, rather than every node's names sorted.
        for (const auto& n : nodes())
            for (const auto& a : n.attributes)
                if (std::find(attributeNames_.begin(), attributeNames_.end(), a.name) == attributeNames_.end())
                    attributeNames_.push_back(a.name);
        std::sort(attributeNames_.begin(), attributeNames_.end());
    });
    return attributeNames_;
}

std::optional<Slot> SceneSnapshot::slotOfSource(std::int64_t sourceId) const {
    buildLinks();
    auto it = slotBySource_.find(sourceId);
    if (it == slotBySource_.end()) return std::nullopt;
    return it->second;
}

const std::vector<Slot>& SceneSnapshot::withCategory(std::string_view category) const {
    static const std::vector<Slot> none;
    auto it = slotsByCategory_.find(category);
    // However the name is written ("Trash Cans"), it names its canonical category.
    if (it == slotsByCategory_.end() && !model::isCategoryName(category))
        it = slotsByCategory_.find(model::categoryName(category));
    return it == slotsByCategory_.end() ? none : it->second;
}

const std::vector<Slot>& SceneSnapshot::children(Slot slot) const {
    buildLinks();
    return children_[slot];
}

const std::vector<Slot>& SceneSnapshot::shownOfKind(model::NodeKind kind) const {
    return shownByKind_[static_cast<std::size_t>(kind)];
}

const std::vector<Slot>& SceneSnapshot::shownNodes() const {
    std::call_once(shownNodesMade_, [&] {
        std::size_t shown = 0;
        for (const auto& list : shownByKind_) shown += list.size();
        shownNodes_.reserve(shown);
        for (Slot s = 0; s < size(); ++s)
            if (kind(s) != model::NodeKind::Scene && !hidden(s)) shownNodes_.push_back(s);
    });
    return shownNodes_;
}

std::vector<std::string> SceneSnapshot::categories() const {
    std::vector<std::string> out;
    for (const auto& [name, slots] : slotsByCategory_) {
        // Descriptions and frames are about places, not places: they are not categories to ask for.
        bool queryable = std::any_of(slots.begin(), slots.end(), [&](Slot s) {
            auto k = kind(s);
            return !hidden(s) && k != model::NodeKind::Scene && k != model::NodeKind::Description &&
                   k != model::NodeKind::Frame;
        });
        if (queryable) out.emplace_back(name);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::string SceneSnapshot::label(const model::Node& node) {
    if (node.kind == model::NodeKind::Scene) return node.category;
    return node.category + '#' + std::to_string(node.id);
}

std::string SceneSnapshot::path(Slot slot) const {
    std::vector<Slot> chain;
    for (std::optional<Slot> s = slot; s; s = slotOf(node(*s).parent)) {
        chain.push_back(*s);
        if (chain.size() > size()) break;  // a corrupt parent cycle must not hang a query
    }
    std::string out;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        if (!out.empty()) out += " / ";
        out += label(node(*it));
    }
    return out;
}

void SceneObstacles::within(const model::Aabb& region, std::vector<const model::Node*>& out) const {
    std::vector<Slot> slots;
    scene_.intersecting(region, slots);
    // The index's bounds hold each box; its exact bounds decide.
    for (Slot s : slots) {
        if (scene_.hidden(s)) continue;
        const model::Node& node = scene_.node(s);
        if (relations::intersects(bounds(node), region)) out.push_back(&node);
    }
}

void SceneObstacles::wallsWithin(const model::Aabb& region, std::vector<const model::Node*>& out) const {
    for (Slot s : scene_.walls())
        if (!scene_.hidden(s) && scene_.geometry(s) != model::GeometryKind::None &&
            relations::intersects(scene_.bounds(s), region) && relations::intersects(bounds(scene_.node(s)), region))
            out.push_back(&scene_.node(s));
}

model::Aabb SceneObstacles::bounds(const model::Node& node) const {
    // Worked out when the record was decoded: they stand for the record itself only.
    if (const model::Aabb* decoded = scene_.decodedBounds(node)) return *decoded;
    return model::worldAabb(node.box);
}

}  // namespace smql::catalog
