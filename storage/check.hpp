// `smql check DB`: verifies a database and says what is wrong with it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace smql::storage {

struct CheckReport {
    // One sentence per problem found, naming the scene, node or file; empty when the database is sound.
    std::vector<std::string> problems;
    std::uint64_t scenes = 0;
    std::uint64_t nodes = 0;  // the scenes' nodes, not counting each scene's own
    std::uint64_t relations = 0;
    std::uint64_t blobs = 0;
    // LMDB's own pages (not smql's records) are damaged: such a problem names no scene.
    bool pagesDamaged = false;
    bool ok() const { return problems.empty(); }
};

// Opens `directory` read-only and checks, in one read transaction: that LMDB
// opens it as an smql database of this schema version; that every record
// decodes with a matching checksum; the tree (each node's scene and parent
// exist in its scene, one scene node per scene, node counts); the indexes
// (scene names, children, labels, source ids, both ends of each relation)
// against the node records; and lock.mdb (present, and not superseded under
// a process that still has the database open). Never writes; a database that
// cannot be opened is one problem, not an exception.
CheckReport checkDatabase(const std::string& directory);

}  // namespace smql::storage
