// USE SCENE 'name' | '*': the scene a session's statements run in.
#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "storage/database.hpp"

namespace smql::binder {

namespace {
// "*" or "all": FIND and COUNT by category and attributes across every scene.
bool isAllScenes(std::string_view name) { return name == "*" || name == "all"; }
}  // namespace

void Binder::bindStatement(const ast::UseStmt& use, BoundStatement& out) {
    if (isAllScenes(use.scene)) {
        out.body = BoundUse{{}, true};
        return;
    }
    if (!ctx_.txn.sceneByName(use.scene)) {
        std::vector<std::string> names;
        for (const auto& s : ctx_.txn.scenes()) names.push_back(s.name);
        auto close = model::nearestNames(use.scene, names);
        throw Error(
            ErrorKind::Binding, fmt::format("no scene named '{}'", use.scene), use.where,
            close.empty() ? "SHOW SCENES lists the scenes" : "did you mean " + model::joinAlternatives(close) + "?");
    }
    out.body = BoundUse{use.scene, false};
}

}  // namespace smql::binder
