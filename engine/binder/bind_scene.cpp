// DROP SCENE, RENAME SCENE, and AS OF (which scene version a statement reads).
#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "storage/database.hpp"

namespace smql::binder {

namespace {

[[noreturn]] void noSuchScene(const storage::ReadTransaction& txn, const std::string& name,
                              const SourceLocation& where) {
    std::vector<std::string> names;
    for (const auto& s : txn.scenes()) names.push_back(s.name);
    auto close = model::nearestNames(name, names);
    throw Error(
        ErrorKind::Binding, fmt::format("no scene named '{}'", name), where,
        close.empty() ? "SHOW SCENES lists the scenes" : "did you mean " + model::joinAlternatives(close) + "?");
}

}  // namespace

void Binder::bindStatement(const ast::DropSceneStmt& drop, BoundStatement& out) {
    if (!ctx_.txn.sceneByName(drop.scene)) noSuchScene(ctx_.txn, drop.scene, drop.where);
    out.body = BoundDropScene{drop.scene};
}

void Binder::bindStatement(const ast::RenameSceneStmt& rename, BoundStatement& out) {
    if (!ctx_.txn.sceneByName(rename.scene)) noSuchScene(ctx_.txn, rename.scene, rename.where);
    if (rename.newName != rename.scene && ctx_.txn.sceneByName(rename.newName))
        throw Error(ErrorKind::Binding, fmt::format("a scene named '{}' already exists", rename.newName), rename.where,
                    "choose another name, or DROP SCENE that one first");
    out.body = BoundRenameScene{rename.scene, rename.newName};
}

void Binder::useVersion(const ast::AsOf& asOf) {
    if (ctx_.session.allScenes)
        throw Error(ErrorKind::Binding, "AS OF reads one scene's past", asOf.where, "USE SCENE 'name' first");
    scene_ = ctx_.sceneAsOf(asOf.instant);
}

}  // namespace smql::binder
