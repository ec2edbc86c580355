#include "storage/check.hpp"

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "model/error.hpp"
#include "storage/database.hpp"

namespace smql::storage {

namespace {

namespace fs = std::filesystem;
using model::Node;
using model::NodeId;

struct FileId {
    dev_t device;
    ino_t inode;
};

// The processes (other than this one) that map `data`, and for each the
// lock files it maps, from /proc/*/maps: LMDB maps both data.mdb and
// lock.mdb, so a process that maps this data.mdb but not the current
// lock.mdb has the database open under a lock file that was removed or
// replaced. Processes of other users are invisible without privileges.
std::map<pid_t, std::vector<std::string>> lockFilesOfProcessesMapping(const FileId& data,
                                                                      const std::optional<FileId>& lock,
                                                                      bool& mapsCurrentLock) {
    std::map<pid_t, std::vector<std::string>> out;
    mapsCurrentLock = false;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator("/proc", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
        const pid_t pid = static_cast<pid_t>(std::stol(name));
        if (pid == ::getpid()) continue;
        std::ifstream maps(entry.path() / "maps");
        bool mapsData = false, current = false;
        std::vector<std::string> others;
        for (std::string line; std::getline(maps, line);) {
            std::istringstream fields(line);
            std::string range, perms, offset, device, path;
            unsigned long inode = 0;
            if (!(fields >> range >> perms >> offset >> device >> inode)) continue;
            std::getline(fields >> std::ws, path);
            unsigned major = 0, minor = 0;
            if (std::sscanf(device.c_str(), "%x:%x", &major, &minor) != 2) continue;
            const dev_t dev = makedev(major, minor);
            if (dev == data.device && inode == data.inode) mapsData = true;
            if (path.find("lock.mdb") == std::string::npos) continue;
            if (lock && dev == lock->device && inode == lock->inode)
                current = true;
            else
                others.push_back(path);
        }
        if (!mapsData) continue;
        mapsCurrentLock |= current;
        if (!current) out[pid] = others;
    }
    return out;
}

void checkLockFile(const std::string& directory, CheckReport& report) {
    struct stat data {
    }, lock{};
    if (::stat((fs::path(directory) / "data.mdb").c_str(), &data) != 0) return;  // the open reports it
    std::optional<FileId> lockId;
    if (::stat((fs::path(directory) / "lock.mdb").c_str(), &lock) == 0) lockId = FileId{lock.st_dev, lock.st_ino};
    bool anyCurrent = false;
    auto stale = lockFilesOfProcessesMapping({data.st_dev, data.st_ino}, lockId, anyCurrent);
    for (const auto& [pid, locks] : stale)
        report.problems.push_back(fmt::format(
            "lock.mdb: process {} has the database open under {}, not under the current {}/lock.mdb: its writes are "
            "not serialised with other processes' (the lock file was removed or replaced while it ran); stop it",
            pid, locks.empty() ? std::string("no lock file") : fmt::format("the lock file {}", locks.front()),
            directory));
}

// LMDB 0.9 follows its own page structure without checks: a flipped bit in a branch page, a page
// header or a node pointer sends it outside the page, and the process stops inside LMDB. Before
// LMDB is given the file, its B-trees are walked here with plain reads from the newer meta page,
// and every page they reach is checked: its number, its kind and bounds, each node within it, each
// child and overflow page within the file, and every key in order and within the range its parent
// gives it (a branch key flipped sends searches past what they look for: a blob no longer found,
// silently, while a walk in order still finds it).
class PageWalk {
public:
    PageWalk(std::ifstream& file, std::uint64_t pages, std::size_t pageSize)
        : file_(file), pages_(pages), pageSize_(pageSize) {}

    // The meta page of the newer transaction: the roots of the free list and of the tables. A file
    // shorter than its last page is left to the open, which says it was cut short.
    void fromMeta() {
        constexpr std::size_t kMeta = 16, kFreeRoot = kMeta + 24 + 40, kMainRoot = kFreeRoot + 48,
                              kLastPage = kMainRoot + 8, kTxnId = kLastPage + 8;
        const std::string first = page(0), second = page(1);
        const std::string& meta = u64(second, kTxnId) > u64(first, kTxnId) ? second : first;
        if (u64(meta, kLastPage) >= pages_) return;
        tree(u64(meta, kFreeRoot), 0, Range{std::nullopt, std::nullopt, true});
        tree(u64(meta, kMainRoot), 0, {});
    }
    std::vector<std::string> problems;

private:
    // The keys a subtree may hold: from `lower` (inclusive) to `upper` (exclusive), either open.
    // The free list's keys are transaction ids (MDB_INTEGERKEY); every table of smql's, and the
    // duplicates of its DUPSORT tables, compare their bytes as LMDB's default does.
    struct Range {
        std::optional<std::string> lower, upper;
        bool integerKeys = false;
    };
    static bool less(std::string_view a, std::string_view b, bool integerKeys) {
        if (integerKeys && a.size() == 8 && b.size() == 8) return u64(a, 0) < u64(b, 0);
        return a < b;  // memcmp over the shorter, then the shorter first: mdb_cmp_memn
    }
    static bool within(std::string_view key, const Range& range) {
        return (!range.lower || !less(key, *range.lower, range.integerKeys)) &&
               (!range.upper || less(key, *range.upper, range.integerKeys));
    }

    static std::uint64_t u64(std::string_view b, std::size_t at) {
        std::uint64_t v = 0;
        for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
        return v;
    }
    static unsigned u16(const std::string& b, std::size_t at) {
        return static_cast<unsigned char>(b[at]) | static_cast<unsigned>(static_cast<unsigned char>(b[at + 1])) << 8;
    }
    std::string page(std::uint64_t number) {
        std::string out(pageSize_, '\0');
        file_.clear();
        file_.seekg(static_cast<std::streamoff>(number * pageSize_));
        file_.read(out.data(), static_cast<std::streamsize>(pageSize_));
        return out;
    }
    void damaged(std::uint64_t page, const std::string& what) {
        if (problems.size() < kShown)
            problems.push_back(fmt::format("data.mdb: page {} (LMDB's own structure) is damaged: {}", page, what));
    }

    // Each key of a page in order and within its range; false (and said) when one is not.
    bool ordered(std::uint64_t number, const std::vector<std::string_view>& keys, std::size_t first,
                 const Range& range) {
        for (std::size_t i = first; i < keys.size(); ++i) {
            std::string fault;
            if (!within(keys[i], range))
                fault = fmt::format("key {} lies outside the range its parent page gives it", i);
            else if (i > first && !less(keys[i - 1], keys[i], range.integerKeys))
                fault = fmt::format("key {} is out of order", i);
            if (fault.empty()) continue;
            damaged(number, fault);
            return false;
        }
        return true;
    }

    void tree(std::uint64_t root, int depth, const Range& range) {
        constexpr std::uint64_t kNoPage = ~std::uint64_t{0};
        constexpr unsigned kBranch = 0x01, kLeaf = 0x02, kLeaf2 = 0x20, kBig = 0x01, kSub = 0x02, kDup = 0x04;
        if (root == kNoPage || problems.size() >= kShown) return;
        if (root < 2 || root >= pages_) return damaged(root, "a tree points to it, past the end of the file");
        if (depth > kDeepest || !seen_.insert(root).second) return damaged(root, "a tree reaches it twice");
        const std::string p = page(root);
        if (u64(p, 0) != root) return damaged(root, fmt::format("it says it is page {}", u64(p, 0)));
        const unsigned flags = u16(p, 10), lower = u16(p, 12), upper = u16(p, 14);
        if (!(flags & (kBranch | kLeaf)) || lower < 16 || lower > upper || upper > pageSize_)
            return damaged(root, fmt::format("flags {:#x}, lower {}, upper {}", flags, lower, upper));
        const unsigned count = (lower - 16) / 2;
        std::vector<std::string_view> keys;
        if (flags & kLeaf2) {
            const std::size_t size = u16(p, 8);
            if (16 + std::size_t{count} * size > pageSize_) return damaged(root, "its fixed-size keys overrun it");
            for (unsigned i = 0; i < count; ++i) keys.push_back(std::string_view(p).substr(16 + i * size, size));
            ordered(root, keys, 0, range);
            return;
        }
        struct Child {
            std::uint64_t page;
            Range range;
        };
        std::vector<Child> children;
        for (unsigned i = 0; i < count; ++i) {
            const std::size_t node = u16(p, 16 + 2 * i);
            if (node < upper || node + 8 > pageSize_) return damaged(root, fmt::format("node {} lies outside it", i));
            const unsigned lo = u16(p, node), hi = u16(p, node + 2), nodeFlags = u16(p, node + 4);
            const std::size_t value = node + 8 + u16(p, node + 6);
            if (value > pageSize_) return damaged(root, fmt::format("node {}'s key overruns it", i));
            keys.push_back(std::string_view(p).substr(node + 8, value - node - 8));
            if (flags & kBranch) {
                children.push_back({lo | std::uint64_t{hi} << 16 | std::uint64_t{nodeFlags} << 32, {}});
                continue;
            }
            const std::size_t size = lo | std::size_t{hi} << 16;
            if (nodeFlags & kBig) {
                if (value + 8 > pageSize_) return damaged(root, fmt::format("node {} overruns it", i));
                const std::uint64_t first = u64(p, value), spans = (size + 16 + pageSize_ - 1) / pageSize_;
                if (first < 2 || first + spans > pages_)
                    damaged(root, fmt::format("node {}'s value lies past the end of the file", i));
                continue;
            }
            if (value + size > pageSize_) return damaged(root, fmt::format("node {}'s value overruns it", i));
            if (nodeFlags & kSub) {
                if (size < 48) return damaged(root, fmt::format("node {} holds no table", i));
                children.push_back({u64(p, value + 40), {}});  // the table's MDB_db: its md_root
            } else if (nodeFlags & kDup) {
                const unsigned subLower = u16(p, value + 12), subUpper = u16(p, value + 14);
                if (size < 16 || subLower < 16 || subLower > subUpper || subUpper > size)
                    damaged(root, fmt::format("node {}'s duplicates are damaged", i));
            }
        }
        // A branch's first key is not compared (LMDB keeps it empty): its child starts where the
        // branch's own range does, and each child ends where the next one's key begins.
        if (!ordered(root, keys, flags & kBranch ? 1 : 0, range)) return;
        if (flags & kBranch)
            for (std::size_t i = 0; i < children.size(); ++i) {
                children[i].range = {i == 0 ? range.lower : std::string(keys[i]),
                                     i + 1 < keys.size() ? std::string(keys[i + 1]) : range.upper, range.integerKeys};
            }
        for (const Child& child : children) tree(child.page, depth + 1, child.range);
    }

    static constexpr std::size_t kShown = 10;
    static constexpr int kDeepest = 64;
    std::ifstream& file_;
    std::uint64_t pages_;
    std::size_t pageSize_;
    std::set<std::uint64_t> seen_;
};

// Every tree of data.mdb walked and its pages checked; false when one is damaged.
bool checkPages(const std::string& directory, CheckReport& report) {
    std::error_code ec;
    const fs::path data = fs::path(directory) / "data.mdb";
    const auto bytes = fs::file_size(data, ec);
    const auto pageSize = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    std::ifstream file(data, std::ios::binary);
    if (ec || !file || bytes < 2 * pageSize) return true;  // the open reports it
    PageWalk walk(file, bytes / pageSize, pageSize);
    walk.fromMeta();
    report.pagesDamaged = !walk.problems.empty();
    for (auto& problem : walk.problems) report.problems.push_back(std::move(problem));
    return !report.pagesDamaged;
}

// Everything about one scene: its records, its tree and its index entries.
struct SceneCounts {
    std::uint64_t nodes = 0, children = 0, labels = 0, sourceIds = 0, relationEntries = 0, blobs = 0, indexes = 0;
};

// The scene's stored table of contents, when it has one, against what its records give: a scene
// loads from it, so a difference would be answered.
template <class Problem>
std::uint64_t checkSceneIndex(const ReadTransaction& txn, const model::SceneInfo& info, const std::vector<Node>& nodes,
                              Problem&& problem) {
    std::optional<SceneIndex> stored;
    try {
        stored = txn.sceneIndex(info);
    } catch (const Error& e) {
        problem(e.message());
        return 1;
    }
    if (stored && *stored != SceneIndex::of(nodes, info.version))
        problem("its scene index does not match its node records");
    return stored ? 1 : 0;
}

SceneCounts checkScene(const ReadTransaction& txn, const model::SceneInfo& info, CheckReport& report) {
    SceneCounts counts;
    const std::string scene = fmt::format("scene '{}' (#{})", info.name, info.id);
    // One damaged record can break every node below it: the first problems of a
    // scene say what is wrong, the rest are counted.
    constexpr std::size_t kShownPerScene = 20;
    std::size_t found = 0;
    auto problem = [&](std::string what) {
        if (found++ < kShownPerScene) report.problems.push_back(fmt::format("{}: {}", scene, what));
    };

    std::vector<Node> nodes;
    try {
        txn.forEachNodeInScene(info.id, [&](const Node& n) { nodes.push_back(n); });
    } catch (const Error& e) {
        problem(e.message());
        return counts;
    }
    counts.nodes = nodes.size();
    if (nodes.empty() || nodes.front().id != info.id || nodes.front().kind != model::NodeKind::Scene)
        problem("its scene node is missing");
    else if (nodes.front().category != info.name)
        problem(fmt::format("its scene node is named '{}'", nodes.front().category));
    if (nodes.size() != info.nodeCount + 1)
        problem(fmt::format("the scene record counts {} nodes, the node table holds {}", info.nodeCount,
                            nodes.empty() ? 0 : nodes.size() - 1));
    if (auto byName = txn.sceneByName(info.name); !byName || byName->id != info.id)
        problem("the scene name index does not lead to it");

    std::set<NodeId> ids;
    for (const Node& n : nodes) ids.insert(n.id);
    std::map<NodeId, std::vector<NodeId>> childrenOf;
    std::map<std::string, std::vector<NodeId>> byCategory;
    std::map<std::string, std::vector<storage::CategoryRow>> rowsOf;
    for (const Node& n : nodes) {
        if (n.kind == model::NodeKind::Scene) continue;
        if (n.parent == model::kNoNode || !ids.contains(n.parent))
            problem(fmt::format("node #{} has parent #{}, which is not a node of the scene", n.id, n.parent));
        childrenOf[n.parent].push_back(n.id);
        ++counts.children;
        if (!n.category.empty()) {
            byCategory[n.category].push_back(n.id), ++counts.labels;
            rowsOf[n.category].push_back({n.id, info.id, n.sourceId, n.geometry, n.box});
        }
        if (n.sourceId) {
            ++counts.sourceIds;
            if (txn.nodeBySourceId(info.id, *n.sourceId) != n.id)
                problem(fmt::format("the source id index does not lead from src#{} to node #{}", *n.sourceId, n.id));
        }
    }
    try {
        for (const Node& n : nodes) {
            auto indexed = txn.children(n.id);
            auto expected = childrenOf[n.id];
            if (indexed != expected)
                problem(fmt::format("the children index lists {} children of node #{}, the node records {}",
                                    indexed.size(), n.id, expected.size()));
            for (const auto& blob : txn.blobsOf(n.id)) {
                txn.blob(n.id, blob.name);
                ++counts.blobs;
            }
        }
        for (const auto& [category, expected] : byCategory) {
            if (txn.nodesWithCategory(category, info.id) != expected) {
                problem(fmt::format("the label index for '{}' does not match the {} nodes of that category", category,
                                    expected.size()));
                continue;
            }
            // What the entries carry of each node (schema version 5; none before) is what its record holds.
            auto rows = txn.categoryRowsInScene(category, info.id);
            if (!rows.empty() && rows != rowsOf[category])
                problem(
                    fmt::format("the label index entries for '{}' do not match the records of those {} nodes "
                                "(source id, geometry or box)",
                                category, expected.size()));
        }
        txn.forEachRelationInScene(info.id, [&](const model::Relation& r) {
            ++counts.relationEntries;
            if (!ids.contains(r.subject) || !ids.contains(r.object)) {
                problem(fmt::format("a {} relation joins #{} and #{}, not both nodes of the scene",
                                    model::toString(r.type), r.subject, r.object));
                return;
            }
            auto other = txn.relationsOf(r.object);
            if (std::find(other.begin(), other.end(), r) == other.end())
                problem(fmt::format("the {} relation of #{} to #{} is stored under its subject only",
                                    model::toString(r.type), r.subject, r.object));
        });
    } catch (const Error& e) {
        problem(e.message());
    }
    counts.indexes = checkSceneIndex(txn, info, nodes, problem);
    if (found > kShownPerScene)
        report.problems.push_back(fmt::format("{}: and {} more problems", scene, found - kShownPerScene));
    return counts;
}

}  // namespace

CheckReport checkDatabase(const std::string& directory) {
    CheckReport report;
    checkLockFile(directory, report);
    if (!checkPages(directory, report)) return report;
    std::unique_ptr<Database> db;
    try {
        db = Database::open(directory, {.readOnly = true, .create = false});
    } catch (const Error& e) {
        report.problems.push_back(e.message());
        return report;
    }
    auto txn = db->beginRead();
    std::vector<model::SceneInfo> scenes;
    try {
        scenes = txn.scenes();
    } catch (const Error& e) {
        report.problems.push_back(e.message());
        return report;
    }
    SceneCounts total;
    std::uint64_t versions = 0;
    for (const auto& info : scenes) {
        try {
            versions += txn.history(info.name).size();
        } catch (const Error& e) {
            report.problems.push_back(e.message());
        }
        SceneCounts counts = checkScene(txn, info, report);
        total.nodes += counts.nodes;
        total.children += counts.children;
        total.labels += counts.labels;
        total.sourceIds += counts.sourceIds;
        total.relationEntries += counts.relationEntries;
        total.blobs += counts.blobs;
        total.indexes += counts.indexes;
    }
    report.scenes = scenes.size();
    // Each scene's own node is not counted, as SHOW SCENES and imports count.
    report.nodes = total.nodes - std::min<std::uint64_t>(total.nodes, report.scenes);
    report.relations = total.relationEntries;
    report.blobs = total.blobs;

    // Entries no scene accounts for: what a scene check cannot see from the inside.
    std::map<std::string, std::uint64_t> expected = {{"nodes", total.nodes},
                                                     {"scenes", scenes.size()},
                                                     {"scene_names", scenes.size()},
                                                     {"children", total.children},
                                                     {"labels", total.labels},
                                                     {"source_ids", total.sourceIds},
                                                     {"relations", 2 * total.relationEntries},
                                                     {"blobs", total.blobs},
                                                     {"history", versions},
                                                     {"scene_index", total.indexes}};
    for (const auto& stats : txn.tableStats())
        if (auto it = expected.find(stats.name); it != expected.end() && stats.entries != it->second)
            report.problems.push_back(fmt::format("table {} holds {} entries, the scenes account for {}", stats.name,
                                                  stats.entries, it->second));
    return report;
}

}  // namespace smql::storage
