// `smql check DB`: what is wrong with a database, if anything (Engine::check); `--salvage OUT`
// copies every scene that reads whole into a new database.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "engine/engine.hpp"
#include "shell/commands.hpp"
#include "storage/check.hpp"

namespace smql::shell {

namespace {

// Every scene the check found no problem in and that reads whole (its nodes, relations and blobs)
// goes into `out`, one write transaction each; the rest are named. A scene's earlier versions
// stay behind: only its current one is copied.
int salvage(const std::string& dbDir, const storage::CheckReport& report, const std::string& out) {
    std::error_code ec;
    if (std::filesystem::exists(out, ec) && !std::filesystem::is_empty(out, ec))
        throw Error(ErrorKind::Usage, fmt::format("--salvage {}: the folder is not empty", out), std::nullopt,
                    "salvage into a new folder");
    // Damage to LMDB's own pages names no scene: each scene is then copied as LMDB's searches still
    // read it, and a record they no longer reach (a flipped branch key) is not copied. Said, so a
    // salvage of such a file is never taken for a whole copy.
    if (report.pagesDamaged)
        std::cout << "note: LMDB's own pages are damaged (above): scenes are copied as LMDB still finds their "
                     "records, and a record its searches no longer reach is not copied\n";
    auto from = Engine::open(dbDir, /*readOnly=*/true);
    const auto shown = from->execute("SHOW SCENES");
    auto into = Engine::open(out);
    std::size_t kept = 0, left = 0;
    for (const auto& row : shown.back().rows) {
        const std::string name = std::get<std::string>(row[0]);
        const std::string mark = fmt::format("scene '{}' (#", name);
        const bool damaged = std::any_of(report.problems.begin(), report.problems.end(),
                                         [&](const std::string& p) { return p.rfind(mark, 0) == 0; });
        try {
            if (damaged) throw Error(ErrorKind::Storage, "smql check found it damaged");
            into->importScene(from->exportScene(name));
            std::cout << fmt::format("salvaged: scene '{}'\n", name);
            ++kept;
        } catch (const Error& e) {
            std::cout << fmt::format("left out: scene '{}': {}\n", name, e.message());
            ++left;
        }
    }
    std::cout << fmt::format("{}: {} scene{} salvaged, {} left out (earlier versions of scenes are not copied)\n", out,
                             kept, kept == 1 ? "" : "s", left);
    return left == 0 ? 0 : 1;
}

}  // namespace

int checkCommand(const std::string& dbDir, const std::string& salvageInto) {
    auto report = Engine::check(dbDir);
    for (const auto& problem : report.problems) std::cout << "problem: " << problem << "\n";
    if (!report.ok()) {
        std::cout << fmt::format("{}: {} problem{} found\n", dbDir, report.problems.size(),
                                 report.problems.size() == 1 ? "" : "s");
        if (!salvageInto.empty()) salvage(dbDir, report, salvageInto);
        return 1;
    }
    if (!salvageInto.empty()) return salvage(dbDir, report, salvageInto);
    std::cout << fmt::format(
        "{}: ok ({} scene{}, {} nodes, {} relations, {} blobs; every record's checksum, the "
        "trees, the indexes and the lock file checked)\n",
        dbDir, report.scenes, report.scenes == 1 ? "" : "s", report.nodes, report.relations, report.blobs);
    return 0;
}

}  // namespace smql::shell
