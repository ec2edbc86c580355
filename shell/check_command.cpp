// `smql check DB`: what is wrong with a database, if anything (Engine::check).
#include <iostream>

#include <fmt/format.h>

#include "engine/engine.hpp"
#include "shell/commands.hpp"

namespace smql::shell {

int checkCommand(const std::string& dbDir) {
    auto report = Engine::check(dbDir);
    for (const auto& problem : report.problems) std::cout << "problem: " << problem << "\n";
    if (!report.ok()) {
        std::cout << fmt::format("{}: {} problem{} found\n", dbDir, report.problems.size(),
                                 report.problems.size() == 1 ? "" : "s");
        return 1;
    }
    std::cout << fmt::format(
        "{}: ok ({} scenes, {} nodes, {} relations, {} blobs; every record's checksum, the "
        "trees, the indexes and the lock file checked)\n",
        dbDir, report.scenes, report.nodes, report.relations, report.blobs);
    return 0;
}

}  // namespace smql::shell
