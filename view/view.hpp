// `smql view DB`: the memory in a browser (docs/view.md). A small HTTP server (cpp-httplib) on
// 127.0.0.1 serves one page (view/page, with three.js built into the program at build time, never
// fetched) and a JSON API over a read-only engine: the scenes, one scene's nodes with their paths,
// and statements (SMQL or ASK) run under a time limit. `smql export html` writes the same page as
// one file, the scene inside it.
#pragma once

#include <functional>
#include <string>

namespace smql {
class Engine;
}

namespace smql::view {

struct ViewOptions {
    std::string database;
    std::string host = "127.0.0.1";
    int port = 8080;                   // 0: any free port
    int statementMilliseconds = 5000;  // a statement running longer is interrupted
    std::string scene;                 // the scene the page opens on (default: the current one)
    std::string token;                 // the API's token (default: a new random one); in the address printed
};

// Serves until the process is stopped. `listening` is called with the page's address once the server
// is bound (the shell prints it): http://127.0.0.1:PORT/?token=TOKEN. The API answers only requests
// whose Host is this machine's and that carry the token (docs/view.md, "Who can use it"). Throws smql::Error(Usage)
// when the address cannot be bound.
void serve(const ViewOptions& options, const std::function<void(const std::string& url)>& listening);

// The page as one self-contained HTML file showing `scene` (the current one when empty): the
// scripts and the scene are inside it; without a server, the query box is off.
std::string standalonePage(Engine& engine, const std::string& scene);

}  // namespace smql::view
