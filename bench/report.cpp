#include "bench/report.hpp"

#include <algorithm>
#include <ctime>
#include <fstream>
#include <thread>

#include <fmt/format.h>
#include <sqlite3.h>

namespace smql::bench {

namespace {

// A target is met when open time on the large data set stays within this
// factor of the small one (timer noise on a few hundred microseconds).
constexpr double kFlatOpenFactor = 2.0;
constexpr double kFindTargetMicros = 20.0;
constexpr double kSpeedupTarget = 10.0;

std::string micros(double us) {
    if (us < 10) return fmt::format("{:.2f}", us);
    if (us < 100) return fmt::format("{:.1f}", us);
    return fmt::format("{:.0f}", us);
}

std::string bytes(std::uint64_t b) {
    if (b < (1u << 20)) return fmt::format("{:.0f} KiB", static_cast<double>(b) / 1024);
    return fmt::format("{:.1f} MiB", static_cast<double>(b) / (1 << 20));
}

std::string rate(double count, double seconds) {
    double r = seconds > 0 ? count / seconds : 0;
    return r >= 100 ? fmt::format("{:.0f}", r) : fmt::format("{:.1f}", r);
}

std::string ratio(double sqlite, double smql) { return smql > 0 ? fmt::format("{:.1f}x", sqlite / smql) : "-"; }

std::string sizeLabel(const DataSet& d) {
    return fmt::format("{} ({} x {})", d.spec.label, d.spec.scenes, d.spec.objectsPerScene);
}

std::string met(bool ok) { return ok ? "met" : "**missed**"; }

}  // namespace

MachineInfo machineInfo() {
    MachineInfo m;
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) == 0) {
            m.cpu = line.substr(line.find(':') + 2);
            break;
        }
    }
    m.cores = std::thread::hardware_concurrency();
    std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    m.date = date;
    m.build = fmt::format("{}, GCC {}.{}", SMQL_BENCH_BUILD_TYPE, __GNUC__, __GNUC_MINOR__);
    m.sqlite = sqlite3_libversion();
    return m;
}

std::string renderMarkdown(const Report& report) {
    const auto& m = report.machine;
    std::string out;
    auto line = [&](std::string text = {}) { out += text + "\n"; };

    line("# Benchmarks");
    line();
    line("smql against a SQLite baseline holding the same data, measured side by side in one run of "
         "`bench/smql_bench` (`make bench` writes this file; the tables are generated, the notes at the end are kept).");
    line();
    line(fmt::format("- Machine: {}, {} cores; {}", m.cpu.empty() ? "unknown CPU" : m.cpu, m.cores, m.date));
    line(fmt::format("- Build: {}; SQLite {} with its R*Tree module", m.build, m.sqlite));
    line(fmt::format("- Command: `{}` ({:.0f} s in all)", report.commandLine, report.totalSeconds));
    line();

    line("## Data sets");
    line();
    line("| data set | scenes | objects per scene: asked / stored (mean) | nodes | smql file (data.mdb) | SQLite file | "
         "SQLite / smql size |");
    line("|---|---:|---:|---:|---:|---:|---:|");
    for (const auto& r : report.runs) {
        const auto& d = r.data;
        line(fmt::format("| {} | {} | {} / {:.0f} | {} | {} | {} | {:.2f} |", d.spec.label, d.spec.scenes,
                         d.spec.objectsPerScene, static_cast<double>(d.objects) / d.spec.scenes, d.nodes,
                         bytes(d.smqlBytes), bytes(d.sqliteBytes),
                         static_cast<double>(d.sqliteBytes) / static_cast<double>(std::max<std::uint64_t>(d.smqlBytes, 1))));
    }
    line();

    line("## Query latency (microseconds)");
    line();
    line(fmt::format("Warm: the scene has been queried before. Each class runs {} times per system, split into {} "
                     "rounds; p50 and p99 are the medians over the rounds of each round's percentile. The ratio is "
                     "SQLite p50 over smql p50 (above 1: smql is faster).",
                     report.options.queries, report.options.rounds));
    line();
    line("| data set | query | smql p50 | smql p99 | SQLite p50 | SQLite p99 | SQLite / smql | answers checked | mean rows |");
    line("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for (const auto& r : report.runs) {
        for (const auto& c : r.result.classes)
            line(fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {:.1f} |", sizeLabel(r.data), c.name,
                             micros(c.smql.p50), micros(c.smql.p99), micros(c.sqlite.p50), micros(c.sqlite.p99),
                             ratio(c.sqlite.p50, c.smql.p50), c.verified, c.meanAnswer));
        const auto& s = r.result;
        line(fmt::format("| {} | first FIND after USE SCENE (cold scene) | {} | {} | {} | {} | {} | - | - |",
                         sizeLabel(r.data), micros(s.smqlSceneSwitch.p50), micros(s.smqlSceneSwitch.max),
                         micros(s.sqliteSceneSwitch.p50), micros(s.sqliteSceneSwitch.max),
                         ratio(s.sqliteSceneSwitch.p50, s.smqlSceneSwitch.p50)));
    }
    line();
    line("The cold-scene row has one sample per scene visited, so its p99 column is the maximum.");
    line();

    line("## Import");
    line();
    line("| data set | smql scenes/s | smql objects/s | SQLite scenes/s | SQLite objects/s | smql time in tree derivation |");
    line("|---|---:|---:|---:|---:|---:|");
    for (const auto& r : report.runs) {
        const auto& d = r.data;
        const auto& i = d.import;
        auto objects = static_cast<double>(d.objects);
        line(fmt::format("| {} | {} | {} | {} | {} | {:.0f}% |", sizeLabel(d), rate(d.spec.scenes, i.smqlSeconds),
                         rate(objects, i.smqlSeconds), rate(d.spec.scenes, i.sqliteSeconds),
                         rate(objects, i.sqliteSeconds),
                         i.treeScenesImportSeconds > 0 ? 100 * i.treeSeconds / i.treeScenesImportSeconds : 0.0));
    }
    line();

    line("## Open (microseconds, median)");
    line();
    line("| data set | smql open | smql open + first query | SQLite open | SQLite open + first query |");
    line("|---|---:|---:|---:|---:|");
    for (const auto& r : report.runs) {
        const auto& o = r.result.open;
        line(fmt::format("| {} | {} | {} | {} | {} |", sizeLabel(r.data), micros(o.smqlOpen), micros(o.smqlFirstQuery),
                         micros(o.sqliteOpen), micros(o.sqliteFirstQuery)));
    }
    line();

    line("## Targets");
    line();
    line("| target | measured | |");
    line("|---|---|---|");
    for (const auto& r : report.runs) {
        std::string measured;
        bool ok = true;
        for (const auto& c : r.result.classes) {
            if (!c.twoPredicateFind) continue;
            ok = ok && c.smql.p50 < kFindTargetMicros;
            measured += fmt::format("{}{} {} us", measured.empty() ? "" : "; ", c.name, micros(c.smql.p50));
        }
        line(fmt::format("| single-scene FIND p50 under {:.0f} us, {} | {} | {} |", kFindTargetMicros, r.data.spec.label,
                         measured, met(ok)));
    }
    for (const auto& r : report.runs) {
        std::string measured;
        bool ok = true;
        for (const auto& c : r.result.classes) {
            double x = c.smql.p50 > 0 ? c.sqlite.p50 / c.smql.p50 : 0;
            ok = ok && x >= kSpeedupTarget;
            measured += fmt::format("{}{} {:.1f}x", measured.empty() ? "" : "; ", c.name, x);
        }
        line(fmt::format("| at least {:.0f}x faster than SQLite on every query class, {} | {} | {} |", kSpeedupTarget,
                         r.data.spec.label, measured, met(ok)));
    }
    if (report.runs.size() >= 2) {
        const auto& small = report.runs.front();
        const auto& large = report.runs.back();
        double a = small.result.open.smqlOpen, b = large.result.open.smqlOpen;
        line(fmt::format("| open time does not grow with database size (large within {:.0f}x of small) | "
                         "{} us at {} -> {} us at {} ({:.2f}x) | {} |",
                         kFlatOpenFactor, micros(a), bytes(small.data.smqlBytes), micros(b), bytes(large.data.smqlBytes),
                         a > 0 ? b / a : 0, met(a > 0 && b <= kFlatOpenFactor * a)));
    }
    line();

    line("## Method");
    line();
    line(fmt::format(
        "- Data: `generateRoom({{seed = scene index, objectCount, name = room_<index>}})` (ingest/generate): walls, a door, "
        "windows, furniture groups on a grid of 2.6 m cells and small coloured things resting on the furniture; the floor "
        "grows with the object count (a 2,000-object room is a hall of 28 x 21 cells, 73 m x 55 m). The data set table gives the objects asked for and stored. Each scene is imported with "
        "`Engine::importScene` (one write transaction, tree derivation included), then read back and inserted into "
        "SQLite with the same ids, parents and boxes in one transaction per scene. Both systems sync each commit "
        "(LMDB's default; SQLite WAL with `synchronous=FULL`)."));
    line("- SQLite schema: `scenes`, `nodes(id, scene, parent, kind, category, geometry, cx, cy, cz, sx, sy, sz, yaw, "
         "hidden, confidence, source_id, text)`, `attributes(node, name, value)`, indexes on `(scene, category)`, "
         "`(category)` and `(parent)`, and an R*Tree `node_boxes(id, scene, x, y, z)` over each box's world bounds "
         "with the scene (its id +-0.5) as its first dimension. Statements are prepared once; `mmap_size` and a 64 MiB page cache are "
         "set, as a tuned application would.");
    line("- Answers: SQL finds the candidates (indexes, R*Tree), then the exact geometry runs in C++ with the "
         "engine's own `relations::evaluate` / `relate` / `model::distance`, so both systems answer with the same "
         "formulas. Before timing, every distinct query is run on both and the answers (ids in order, relation names "
         "in order, counts) must be equal, or the run fails.");
    line("- FIND with two metric predicates: `FIND object WHERE on(table) AND near(window, 1.5 m)` (few "
         "windows, so few answers) and `FIND object WHERE on(table) AND near(chair, 1 m)` (many references "
         "on both sides: a large room has about 45 tables and 130 chairs); a scene without tables uses desk, counter "
         "or sofa. SQLite: the references of both terms by `(scene, category)`, an R*Tree probe around each reference "
         "of the smaller set (the region where the predicate can hold, as smql's planner computes it), the exact test "
         "of that term, then of the other term against the references whose region the candidate's bounds meet.");
    line(fmt::format("- RELATE: `RELATE #a TO #b` for {} pairs per scene (half of them a small thing and what it rests "
                     "on, half random), from the scene's default viewpoint. SQLite: both rows by primary key in one "
                     "statement, then `relations::relate`.",
                     kRelatePairsPerScene));
    line(fmt::format("- NEAREST TO: `FIND object NEAREST TO door LIMIT {}`. SQLite: R*Tree probes around the door "
                     "with a radius growing 1 m, 4 m, 16 m ... until {} objects lie within it (box distance is never "
                     "below the bounds' distance, so those are the nearest).",
                     kNearestLimit, kNearestLimit));
    line(fmt::format("- Category search across all scenes: `USE SCENE '*'` then `FIND <c> LIMIT {}` and `COUNT <c>` "
                     "for c in mug, book, lamp, plant, laptop, bottle, bowl, vase, clock, cushion. SQLite: the "
                     "`(category)` index, `ORDER BY id LIMIT {}` and `count(*)`.",
                     kCategoryLimit, kCategoryLimit));
    line(fmt::format("- Timing: `steady_clock` around each `Engine::execute(text)` (statement text is parsed once and "
                     "cached, as SQLite's statements are prepared once) and around each SQLite call, result rows "
                     "included. Single-scene classes run in {} scene(s) spread over the data set: `USE SCENE`, the "
                     "first FIND (timed apart, above: it loads the scene into smql's memory) and the checks; then "
                     "the timed runs, in rounds that each visit every scene, SQLite right after smql on the same "
                     "queries; all in one process on a warm OS page cache. Open times are medians of {} opens of "
                     "the closed database (smql: `Engine::open`; SQLite: `sqlite3_open_v2`, pragmas and preparing "
                     "the statements); \"+ first query\" adds `USE SCENE 'room_0'` and its FIND.",
                     report.options.sampledScenes, report.options.openRepeats));
    line();
    line(kNotesMarker);
    return out;
}

}  // namespace smql::bench
