#include "bench/report.hpp"

#include <algorithm>
#include <ctime>
#include <fstream>
#include <functional>
#include <thread>

#include <fmt/format.h>
#include <sqlite3.h>

namespace smql::bench {

namespace {

// A target is met when open time on the large data set stays within this
// factor of the small one (timer noise on a few hundred microseconds).
constexpr double kFlatOpenFactor = 2.0;
constexpr double kFindTargetMicros = 20.0;
// Prepared smql against each baseline's prepared statements, per baseline (SQLite, PostGIS).
constexpr double kPreparedSpeedupTargets[] = {10.0, 30.0};
// Fresh text (a text the engine never saw verbatim) against the baselines' prepared statements.
constexpr double kFreshSpeedupTarget = 2.0;
constexpr double kColdSceneTargetMicros = 100.0;

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

// A check against a line that the noise cannot flip: met when even the
// round least favourable to smql is on the right side, missed when even the
// most favourable is not, and otherwise "within noise" of the line.
enum class Verdict { Met, WithinNoise, Missed };
Verdict verdict(double worst, double best, const std::function<bool(double)>& ok) {
    if (ok(worst)) return Verdict::Met;
    if (!ok(best)) return Verdict::Missed;
    return Verdict::WithinNoise;
}
Verdict combine(Verdict a, Verdict b) { return std::max(a, b); }
std::string show(Verdict v) {
    switch (v) {
        case Verdict::Met:
            return "met";
        case Verdict::WithinNoise:
            return "within noise of the line";
        case Verdict::Missed:
            return "**missed**";
    }
    return {};
}

// The spread of the round p50s around their median, in percent.
double noisePercent(const Percentiles& p) { return p.p50 > 0 ? 100 * (p.p50High - p.p50Low) / p.p50 : 0; }

// One row of the targets table: smql (`which` of its columns) at least `target` times faster than
// baseline `b` on every query class of the run, judged on the rounds as verdict() says.
std::string speedupTarget(const DataSetRun& run, std::size_t b, double target, std::string_view what,
                          Percentiles ClassResult::*which) {
    std::string measured;
    Verdict v = Verdict::Met;
    for (const auto& c : run.result.classes) {
        const Percentiles& theirs = c.baselines[b];
        const Percentiles& ours = c.*which;
        double worst = ours.p50High > 0 ? theirs.p50Low / ours.p50High : 0;
        double best = ours.p50Low > 0 ? theirs.p50High / ours.p50Low : 0;
        v = combine(v, verdict(worst, best, [target](double x) { return x >= target; }));
        measured += fmt::format("{}{} {} ({:.1f}-{:.1f}x)", measured.empty() ? "" : "; ", c.name,
                                ratio(theirs.p50, ours.p50), worst, best);
    }
    return fmt::format("| {}: at least {:.0f}x faster than tuned {} on every query class, {} | {} | {} |", what, target,
                       run.result.baselineNames[b], run.data.spec.label, measured, show(v));
}

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
    line(
        "smql against tuned SQLite and PostGIS baselines holding the same data, measured side by side in one run of "
        "`bench/smql_bench` (`make bench` writes this file; the tables are generated, the notes at the end are kept).");
    line();
    line(fmt::format("- Machine: {}, {} cores; {}", m.cpu.empty() ? "unknown CPU" : m.cpu, m.cores, m.date));
    line(fmt::format("- Build: {}; SQLite {} with its R*Tree module; {}", m.build, m.sqlite,
                     report.postgis.empty() ? "PostGIS not run" : report.postgis));
    line(fmt::format("- Command: `{}` ({:.0f} s in all)", report.commandLine, report.totalSeconds));
    line();

    line("## Data sets");
    line();
    line(
        "| data set | scenes | objects per scene: asked / stored (mean) | nodes | smql file (data.mdb) | SQLite file | "
        "PostGIS database | SQLite / smql size |");
    line("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (const auto& r : report.runs) {
        const auto& d = r.data;
        line(fmt::format(
            "| {} | {} | {} / {:.0f} | {} | {} | {} | {} | {:.2f} |", d.spec.label, d.spec.scenes,
            d.spec.objectsPerScene, static_cast<double>(d.objects) / d.spec.scenes, d.nodes, bytes(d.smqlBytes),
            bytes(d.sqliteBytes), d.postgisBytes ? bytes(d.postgisBytes) : "-",
            static_cast<double>(d.sqliteBytes) / static_cast<double>(std::max<std::uint64_t>(d.smqlBytes, 1))));
    }
    line();

    line("## Query latency (microseconds)");
    line();
    line(fmt::format(
        "Warm: the scene has been queried before. Each class runs {} times per system, split into {} rounds; p50 and "
        "p99 are the medians over the rounds of each round's percentile. smql runs every query three ways: as fresh "
        "text (a text the engine never saw verbatim), as repeated text (the engine's cache of parsed texts skips the "
        "parse) and as a prepared statement (`Engine::prepare` once, then bind and execute); the baselines run "
        "prepared statements. Ratios are the baseline's p50 over smql's prepared p50 (prepared against prepared), "
        "then over smql's fresh-text p50 (above 1: smql is faster). Noise is the widest spread of the round p50s, "
        "over the systems, as a share of the median.",
        report.options.queries, report.options.rounds));
    line();
    line(
        "| data set | query | smql p50 fresh | smql p50 repeated | smql p50 prepared | smql p99 prepared | SQLite p50 "
        "| "
        "SQLite p99 | PostGIS p50 | PostGIS p99 | SQLite / smql prepared | PostGIS / smql prepared | SQLite / smql "
        "fresh | PostGIS / smql fresh | noise | answers checked | mean rows |");
    line("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (const auto& r : report.runs) {
        for (const auto& c : r.result.classes) {
            double noise =
                std::max({noisePercent(c.smqlFresh), noisePercent(c.smqlRepeated), noisePercent(c.smqlPrepared)});
            for (const auto& b : c.baselines) noise = std::max(noise, noisePercent(b));
            auto p50 = [&](std::size_t i) { return i < c.baselines.size() ? micros(c.baselines[i].p50) : "-"; };
            auto p99 = [&](std::size_t i) { return i < c.baselines.size() ? micros(c.baselines[i].p99) : "-"; };
            auto x = [&](std::size_t i, const Percentiles& smql) {
                return i < c.baselines.size() ? ratio(c.baselines[i].p50, smql.p50) : "-";
            };
            line(fmt::format(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.0f}% | {} | {:.1f} |",
                sizeLabel(r.data), c.name, micros(c.smqlFresh.p50), micros(c.smqlRepeated.p50),
                micros(c.smqlPrepared.p50), micros(c.smqlPrepared.p99), p50(0), p99(0), p50(1), p99(1),
                x(0, c.smqlPrepared), x(1, c.smqlPrepared), x(0, c.smqlFresh), x(1, c.smqlFresh), noise, c.verified,
                c.meanAnswer));
        }
        const auto& s = r.result;
        auto cold = [&](std::size_t i, bool p50) {
            if (i >= s.baselineSceneSwitch.size()) return std::string("-");
            return micros(p50 ? s.baselineSceneSwitch[i].p50 : s.baselineSceneSwitch[i].max);
        };
        auto coldRatio = [&](std::size_t i) {
            return i < s.baselineSceneSwitch.size() ? ratio(s.baselineSceneSwitch[i].p50, s.smqlSceneSwitch.p50)
                                                    : std::string("-");
        };
        line(
            fmt::format("| {} | first FIND after USE SCENE (cold scene) | {} | - | - | {} | {} | {} | {} | {} | - | - "
                        "| {} | {} | - | - | - |",
                        sizeLabel(r.data), micros(s.smqlSceneSwitch.p50), micros(s.smqlSceneSwitch.max), cold(0, true),
                        cold(0, false), cold(1, true), cold(1, false), coldRatio(0), coldRatio(1)));
    }
    line();
    line(
        "The cold-scene row times the first FIND after `USE SCENE` with the scene not yet loaded, as fresh text: "
        "for smql in rounds that each open the database anew and visit every sampled scene once (its p50 the "
        "median of the rounds' medians, its p99 column the slowest scene of any round), for the baselines once "
        "per scene (their p99 columns the slowest); its ratios are fresh-text ones.");
    line();

    line("### New text");
    line();
    line(
        "What a text the engine never saw verbatim costs before the binder (p50 over 1,000 runs of each class's "
        "first query, a new comment each time): ANTLR's parse into the AST (SLL prediction first, the full LL only "
        "when it fails), and the hand-written scan that finds the text's statement shape. A text whose shape the "
        "engine keeps pays the scan and the binding of its literals instead of the parse: fresh minus repeated text "
        "in the latency table.");
    line();
    line("| data set | query | ANTLR parse | shape scan | fresh - repeated |");
    line("|---|---|---:|---:|---:|");
    for (const auto& r : report.runs)
        for (const auto& c : r.result.classes)
            line(fmt::format("| {} | {} | {} | {} | {} |", sizeLabel(r.data), c.name, micros(c.parseMicros),
                             micros(c.shapeScanMicros), micros(c.smqlFresh.p50 - c.smqlRepeated.p50)));
    line();
    for (const auto& r : report.runs) {
        const auto& s = r.result.shapes;
        line(
            fmt::format("- {}: {} statements answered from a cached shape; {} shapes learned, {} refused (always "
                        "parsed), {} evicted.",
                        sizeLabel(r.data), s.hits, s.learned, s.refused, s.evicted));
    }
    line();

    line("## Import");
    line();
    line(
        "| data set | smql scenes/s | smql objects/s | SQLite scenes/s | SQLite objects/s | PostGIS load (COPY, "
        "indexes, VACUUM ANALYZE) | smql time in tree derivation |");
    line("|---|---:|---:|---:|---:|---:|---:|");
    for (const auto& r : report.runs) {
        const auto& d = r.data;
        const auto& i = d.import;
        auto objects = static_cast<double>(d.objects);
        line(fmt::format("| {} | {} | {} | {} | {} | {} | {:.0f}% |", sizeLabel(d), rate(d.spec.scenes, i.smqlSeconds),
                         rate(objects, i.smqlSeconds), rate(d.spec.scenes, i.sqliteSeconds),
                         rate(objects, i.sqliteSeconds),
                         d.postgisBytes ? fmt::format("{:.1f} s", i.postgisSeconds) : std::string("-"),
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
        Verdict v = Verdict::Met;
        for (const auto& c : r.result.classes) {
            if (!c.twoPredicateFind) continue;
            v = combine(
                v, verdict(c.smqlFresh.p50High, c.smqlFresh.p50Low, [](double us) { return us < kFindTargetMicros; }));
            measured += fmt::format("{}{} {} us ({}-{})", measured.empty() ? "" : "; ", c.name, micros(c.smqlFresh.p50),
                                    micros(c.smqlFresh.p50Low), micros(c.smqlFresh.p50High));
        }
        line(fmt::format("| single-scene FIND p50 (fresh text) under {:.0f} us, {} | {} | {} |", kFindTargetMicros,
                         r.data.spec.label, measured, show(v)));
    }
    for (const auto& r : report.runs) {
        for (std::size_t b = 0; b < r.result.baselineNames.size(); ++b) {
            const double target = kPreparedSpeedupTargets[std::min<std::size_t>(b, 1)];
            line(speedupTarget(r, b, target, "prepared smql", &ClassResult::smqlPrepared));
        }
    }
    for (const auto& r : report.runs)
        if (!r.result.baselineNames.empty())
            line(speedupTarget(r, 0, kFreshSpeedupTarget, "fresh text", &ClassResult::smqlFresh));
    for (const auto& r : report.runs) {
        if (r.data.spec.objectsPerScene < 2000) continue;
        const Percentiles& cold = r.result.smqlSceneSwitch;
        Verdict v = verdict(cold.p50High, cold.p50Low, [](double us) { return us <= kColdSceneTargetMicros; });
        line(fmt::format(
            "| first FIND after USE SCENE at most {:.0f} us on a {}-object scene, {} | {} us ({}-{}) | {} |",
            kColdSceneTargetMicros, r.data.spec.objectsPerScene, r.data.spec.label, micros(cold.p50),
            micros(cold.p50Low), micros(cold.p50High), show(v)));
    }
    if (report.runs.size() >= 2) {
        const auto& small = report.runs.front();
        const auto& large = report.runs.back();
        double a = small.result.open.smqlOpen, b = large.result.open.smqlOpen;
        line(
            fmt::format("| open time does not grow with database size (large within {:.0f}x of small) | "
                        "{} us at {} -> {} us at {} ({:.2f}x) | {} |",
                        kFlatOpenFactor, micros(a), bytes(small.data.smqlBytes), micros(b), bytes(large.data.smqlBytes),
                        a > 0 ? b / a : 0, met(a > 0 && b <= kFlatOpenFactor * a)));
    }
    line();
    line(
        "A target is met when the round least favourable to smql meets it (for ratios: the baseline's fastest round "
        "over smql's slowest), missed when even the most favourable round misses it, and otherwise within noise of "
        "the line; the ranges in brackets are those rounds, so a verdict does not flip with the machine's load.");
    line();

    line("## Method");
    line();
    line(fmt::format(
        "- Data: `generateRoom({{seed = scene index, objectCount, name = room_<index>}})` (ingest/generate): walls, a "
        "door, "
        "windows, furniture groups on a grid of 2.6 m cells and small coloured things resting on the furniture; the "
        "floor "
        "grows with the object count (a 2,000-object room is a hall of 28 x 21 cells, 73 m x 55 m). The data set table "
        "gives the objects asked for and stored. Each scene is imported with "
        "`Engine::importScene` (one write transaction, tree derivation included), then read back and inserted into "
        "SQLite with the same ids, parents and boxes in one transaction per scene, and streamed into PostGIS by COPY "
        "(one COPY for all scenes in one transaction, the indexes built after it, then `VACUUM ANALYZE`). All systems "
        "sync each commit (LMDB's default; SQLite WAL with `synchronous=FULL`; PostgreSQL's default "
        "`synchronous_commit`)."));
    line(
        "- SQLite schema (tuned): `scenes`, `nodes(id, scene, parent, kind, category, geometry, cx, cy, cz, sx, sy, "
        "sz, yaw, hidden, confidence, source_id, text)`, `attributes(node, name, value)`; covering indexes "
        "`(scene, category, kind, geometry, box..., hidden)` and `(category, id, scene, source_id, box...)`, an index "
        "on `(parent)`; `category_counts(category, count)` kept by insert, delete and update triggers; an R*Tree "
        "`node_boxes(id, scene, x, y, z)` over each box's world bounds with the scene (its id +-0.5) as its first "
        "dimension, joined to `nodes` by primary key (the node columns as R*Tree auxiliary columns, which spare the "
        "join, measured 2-4.6x slower on FIND and NEAREST). Statements are prepared once and bound with parameters; "
        "`mmap_size` and a "
        "64 MiB page cache are set, as a tuned application would.");
    line(
        "- PostGIS: a private PostgreSQL cluster the bench creates (initdb into a new temporary directory, the server "
        "on a unix socket inside it and no TCP port, run as `nobody` when the bench runs as root; stopped and removed "
        "at the end, also when the run fails; left out with a printed note when the server or PostGIS is not "
        "installed, or with `--no-postgis`). Settings: `shared_buffers=1GB`, `jit=off`, "
        "`plan_cache_mode=force_generic_plan`, autovacuum off (the data does not change while timed). Schema: the "
        "same tables, plus `min_z`, `max_z` and `footprint geometry(Polygon)` (the box's world bounds seen from "
        "above) per node; a GiST index on `(scene, footprint)` (btree_gist), covering B-trees on `(scene, category)` "
        "and `(category, id)`, `category_counts` kept by statement triggers over transition tables (so COPY counts "
        "at once). Every query is a prepared statement (PQprepare / PQexecPrepared).");
    line(
        "- Answers: SQL finds the candidates (indexes, R*Tree), then the exact geometry runs in C++ with the "
        "engine's own `relations::evaluate` / `relate` / `model::distance`, so both systems answer with the same "
        "formulas. Before timing, every distinct query is run on every system, and during timing every answer of "
        "each baseline is compared with smql's answer to the same fresh text: the answers (ids in order, relation "
        "names in order, counts) must be equal, or the run fails with both answers printed.");
    line(
        "- FIND with two metric predicates: `FIND object WHERE on(table) AND near(window, 1.5 m)` (few "
        "windows, so few answers) and `FIND object WHERE on(table) AND near(chair, 1 m)` (many references "
        "on both sides: a large room has about 45 tables and 130 chairs); a scene without tables uses desk, counter "
        "or sofa. SQLite: the references of both terms by `(scene, category)`, an R*Tree probe around each reference "
        "of the smaller set (the region where the predicate can hold, as smql's planner computes it), the exact test "
        "of that term, then of the other term against the references whose region the candidate's bounds meet. "
        "PostGIS: the same, with the probe as one join per FIND (`n.footprint && ST_Expand(r.footprint, margin)` and "
        "the z range, over the references of the smaller set), so it costs three round trips.");
    line(fmt::format(
        "- RELATE: `RELATE #a TO #b` for {} pairs per scene (half of them a small thing and what it rests "
        "on, half random), from the scene's default viewpoint. SQLite: both rows by primary key in one "
        "statement (both baselines), the objects around the pair (an R*Tree probe; PostGIS: a GiST one), which "
        "may crowd it out of near, then `relations::relate`.",
        kRelatePairsPerScene));
    line(
        fmt::format("- NEAREST TO: `FIND object NEAREST TO door LIMIT {}`. SQLite: R*Tree probes around the door "
                    "with a radius growing 1 m, 4 m, 16 m ... until {} objects lie within it (box distance is never "
                    "below the bounds' distance, so those are the nearest). PostGIS: a GiST k-nearest-neighbour scan "
                    "`ORDER BY footprint <-> ST_Collect(door footprints) LIMIT w`, the exact box distance per row, "
                    "stopping at the first row whose footprint distance (a lower bound) exceeds the {}th exact "
                    "distance; w starts at {} rows and grows 4x when that row is not reached.",
                    kNearestLimit, kNearestLimit, kNearestLimit, 4 * kNearestLimit));
    line(
        fmt::format("- Category search across all scenes: `USE SCENE '*'` then `FIND <c> LIMIT {}` and `COUNT <c>` "
                    "for c in mug, book, lamp, plant, laptop, bottle, bowl, vase, clock, cushion. Both "
                    "baselines: the covering `(category, id, ...)` index, `ORDER BY id LIMIT {}`, and the count from "
                    "`category_counts`.",
                    kCategoryLimit, kCategoryLimit));
    line(
        fmt::format("- Timing: `steady_clock` around each `Engine::execute(text)`, each bind-and-execute of a "
                    "prepared statement and each baseline call, result rows included. smql runs each query three "
                    "ways: as fresh text (the query with a new numbered comment, `-- fresh text N`, so the engine "
                    "never saw the text verbatim and its cache of parsed texts cannot answer; its cache of statement "
                    "shapes can, from the second text of a shape on, as for an application that writes new literals "
                    "into its texts), as repeated text (the parsed-text cache skips the parse) and as a prepared "
                    "statement (`Engine::prepare` once per statement before "
                    "the timing, then `bind` of each value and `execute`: `FIND object WHERE on(?) AND near(?, ?)`, "
                    "`FIND object NEAREST TO ? LIMIT ?`, `FIND ? LIMIT ?`, `COUNT ?`; a node id cannot be a "
                    "placeholder, so each RELATE pair is a prepared statement of its own, as in an application). "
                    "The baselines' statements are prepared and bound the same way, so the prepared column is the "
                    "like-for-like comparison. Every prepared answer is compared with the fresh text's. Single-scene "
                    "classes run in {} scene(s) spread over the data set: `USE SCENE`, the "
                    "first FIND (the baselines' timed here, smql's it loads the scene into memory) and the checks; "
                    "then the timed runs, in rounds that each visit every scene, the baselines right after smql on "
                    "the same queries; all in one process on a warm OS page cache. With the systems closed, smql's "
                    "first FIND is timed again in as many rounds, after one not counted (as the other classes' "
                    "queries run once before their timing), each opening the database anew and visiting the "
                    "scenes in the same order, the nodes of each read and freed and the FIND parsed before its "
                    "`USE SCENE`, as at the first visit. Open times are medians of {} opens of "
                    "the closed database (smql: `Engine::open`; SQLite: `sqlite3_open_v2`, pragmas and preparing "
                    "the statements); \"+ first query\" adds `USE SCENE 'room_0'` and its FIND.",
                    report.options.sampledScenes, report.options.openRepeats));
    line();
    line(kNotesMarker);
    return out;
}

}  // namespace smql::bench
