// SHOW SCENES | SETTINGS | TREE [x] | CHANGES [SINCE t] | GRAPH.
#include "engine/binder/binder.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "model/error.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::ShowStmt& show, BoundStatement& out) {
    switch (show.what) {
        case ast::ShowStmt::What::Scenes:
            out.body = BoundShowScenes{};
            return;
        case ast::ShowStmt::What::Settings:
            out.body = BoundShowSettings{};
            return;
        case ast::ShowStmt::What::Categories:
            if (!ctx_.session.allScenes) scene();
            out.body = BoundShowCategories{ctx_.session.allScenes};
            return;
        case ast::ShowStmt::What::Attributes:
            // The stored attributes are the current scene's; across all scenes only the built-in ones.
            if (!ctx_.session.allScenes) scene();
            out.body = BoundShowAttributes{};
            return;
        case ast::ShowStmt::What::Changes:
            if (ctx_.session.allScenes)
                throw Error(ErrorKind::Binding, "SHOW CHANGES lists the changes of one scene", std::nullopt,
                            "USE SCENE 'name' first");
            out.body = BoundShowChanges{scene().info().name, show.since};
            return;
        case ast::ShowStmt::What::Graph:
            if (ctx_.session.allScenes)
                throw Error(ErrorKind::Binding, "SHOW GRAPH shows one scene's graph", std::nullopt,
                            "USE SCENE 'name' first");
            scene();
            out.body = BoundShowGraph{};
            return;
        case ast::ShowStmt::What::Tree: {
            BoundShowTree tree;
            if (show.root)
                tree.root = bindSingle(*show.root, "SHOW TREE");
            else
                scene();  // the whole tree of the current scene
            out.body = std::move(tree);
            return;
        }
    }
}

}  // namespace smql::binder
