// DROP SCENE, RENAME SCENE and SHOW CHANGES: a scene as a whole, and its history.
#include <cmath>

#include <fmt/format.h>

#include "engine/exec/executor.hpp"
#include "model/error.hpp"
#include "model/instant.hpp"
#include "storage/database.hpp"

namespace smql::exec {

namespace {

storage::Database& writable(storage::Database* db, std::string_view statement) {
    if (!db)
        throw Error(ErrorKind::Storage, fmt::format("{} needs a database open for writing", statement), std::nullopt,
                    "open the database without --read-only");
    return *db;
}

// The scene as the write transaction sees it: another process may have dropped or renamed it
// since the statement was bound.
model::SceneInfo sceneToChange(storage::WriteTransaction& txn, const std::string& name) {
    auto info = txn.sceneByName(name);
    if (!info)
        throw Error(ErrorKind::Binding, fmt::format("no scene named '{}' (it is gone since the statement began)", name),
                    std::nullopt, "SHOW SCENES lists the scenes");
    return *info;
}

Value boxOrNull(model::ChangeKind kind, bool from, const model::Box& box) {
    bool present = from ? kind != model::ChangeKind::Added : kind != model::ChangeKind::Missing;
    return present ? Value(box) : Value();
}

}  // namespace

ResultSet Executor::run(const binder::BoundDropScene& drop) {
    auto txn = writable(db_, "DROP SCENE").beginWrite();
    model::SceneInfo info = sceneToChange(txn, drop.scene);
    txn.dropScene(info.id);
    txn.commit();
    if (session_.sceneName == drop.scene) session_.sceneName.clear();  // the next statement picks the latest
    ResultSet rs;
    rs.message = fmt::format("dropped scene '{}' ({} nodes) and its history", drop.scene, info.nodeCount);
    return rs;
}

ResultSet Executor::run(const binder::BoundRenameScene& rename) {
    auto txn = writable(db_, "RENAME SCENE").beginWrite();
    model::SceneInfo info = sceneToChange(txn, rename.scene);
    txn.renameScene(info.id, rename.newName);
    txn.commit();
    if (session_.sceneName == rename.scene) session_.sceneName = rename.newName;
    ResultSet rs;
    rs.message = fmt::format("renamed scene '{}' to '{}'", rename.scene, rename.newName);
    return rs;
}

ResultSet Executor::run(const binder::BoundShowChanges& show) {
    ResultSet rs;
    rs.columns = {{"time", ValueType::Text},  {"change", ValueType::Text}, {"category", ValueType::Text},
                  {"id", ValueType::Integer}, {"from", ValueType::Box},    {"to", ValueType::Box},
                  {"moved", ValueType::Real}};
    std::size_t updates = 0;
    for (const auto& version : txn_.history(show.scene)) {
        if (show.since && model::comparableInstant(version.supersededAt) < *show.since) continue;
        ++updates;
        for (const auto& change : version.changes) {
            poll();
            const bool moved = change.kind == model::ChangeKind::Moved;
            const auto& a = change.from.center;
            const auto& b = change.to.center;
            rs.rows.push_back(
                {version.supersededAt, std::string(model::toString(change.kind)), change.category,
                 static_cast<std::int64_t>(change.kind == model::ChangeKind::Missing ? change.before : change.after),
                 boxOrNull(change.kind, true, change.from), boxOrNull(change.kind, false, change.to),
                 moved ? Value(std::hypot(b.x - a.x, b.y - a.y, b.z - a.z)) : Value()});
        }
    }
    checkRows(rs.rows.size());
    rs.message = updates == 0
                     ? fmt::format("scene '{}' has no update{}", show.scene,
                                   show.since ? " since " + *show.since : std::string())
                     : fmt::format("{} change{} in {} update{} of scene '{}'", rs.rows.size(),
                                   rs.rows.size() == 1 ? "" : "s", updates, updates == 1 ? "" : "s", show.scene);
    return rs;
}

}  // namespace smql::exec
