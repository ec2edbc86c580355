// SHOW SCENES | SETTINGS | TREE [x].
#include "engine/binder/binder.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::ShowStmt& show, BoundStatement& out) {
    switch (show.what) {
        case ast::ShowStmt::What::Scenes: out.body = BoundShowScenes{}; return;
        case ast::ShowStmt::What::Settings: out.body = BoundShowSettings{}; return;
        case ast::ShowStmt::What::Tree: {
            BoundShowTree tree;
            if (show.root) tree.root = bindRef(*show.root);
            else scene();  // the whole tree of the current scene
            out.body = std::move(tree);
            return;
        }
    }
}

}  // namespace smql::binder
