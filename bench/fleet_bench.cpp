// smql_bench_fleet: push throughput into a fleet store (docs/fleet.md, "Measured"). It starts a
// private PostgreSQL + PostGIS cluster (fleet/pg/local_cluster.hpp, default server settings: commits
// synchronous), builds local databases of generated rooms, and measures one device's push, four
// devices pushing at once (one thread and one connection each), and a push with nothing to send;
// with --shards N, through a coordinator over N clusters on this machine. Then the latency of SMQL
// statements on the store against the same statements in a device's own database.
// `make bench-fleet` prints the Markdown table docs/fleet.md keeps.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <iostream>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "engine/engine.hpp"
#include "fleet/fleet.hpp"
#include "fleet/pg/local_cluster.hpp"
#include "fleet/query.hpp"
#include "fleet/shards.hpp"
#include "ingest/generate/room_generator.hpp"
#include "storage/database.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Options {
    int scenes = 100;   // per device
    int objects = 200;  // per scene
    int shards = 0;     // 0: one server; else a coordinator over this many clusters (docs/fleet.md, "Shards")
};

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A device's database of generated rooms; every device gets rooms of its own seeds.
std::unique_ptr<smql::storage::Database> buildDevice(const fs::path& dir, int device, const Options& options) {
    {
        auto engine = smql::Engine::open(dir.string());
        for (int i = 0; i < options.scenes; ++i)
            engine->importScene(smql::generate::generateRoom({.seed = static_cast<std::uint64_t>(device * 100000 + i),
                                                              .objectCount = options.objects,
                                                              .name = fmt::format("room_{}", i)}));
    }
    return smql::storage::Database::open(dir.string());
}

void row(const std::string& what, const std::vector<smql::fleet::PushReport>& reports, double seconds) {
    std::size_t sent = 0, nodes = 0;
    for (const auto& r : reports) sent += r.sent, nodes += r.nodes;
    fmt::print("| {} | {} | {} | {:.2f} s | {:.0f} | {:.0f} |\n", what, sent, nodes, seconds, sent / seconds,
               nodes / seconds);
}

// The median of `rounds` runs, in microseconds.
double medianMicros(const std::function<void()>& run, int rounds = 31) {
    std::vector<double> times;
    for (int i = 0; i < rounds; ++i) {
        const auto started = Clock::now();
        run();
        times.push_back(secondsSince(started) * 1e6);
    }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

// Statements on the store (one scene of the first device; every scene of every device) against the
// same statements in the first device's own database.
void queryLatency(const std::string& url, const std::string& device, const fs::path& local) {
    struct Query {
        std::string what, scene, statement;
    };
    const std::vector<Query> queries = {
        {"one scene: FIND chair", "room_0", "FIND chair"},
        {"one scene: FIND chair WHERE near(table)", "room_0", "FIND chair WHERE near(table)"},
        {"one scene: FIND object WHERE on(table)", "room_0", "FIND object WHERE on(table)"},
        {"one scene: FIND object NEAREST TO door LIMIT 5", "room_0", "FIND object NEAREST TO door LIMIT 5"},
        {"all scenes: COUNT chair", "*", "COUNT chair"},
        {"all scenes: FIND chair LIMIT 100", "*", "FIND chair LIMIT 100"},
    };
    smql::fleet::StoreSession mine(url, device), everyone(url, "");
    auto engine = smql::Engine::open(local.string());
    const auto ignore = [](smql::ResultSet&&) {};
    fmt::print("\n| statement | store p50 | local smql p50 | store / local |\n|---|---|---|---|\n");
    for (const auto& q : queries) {
        smql::fleet::StoreSession& session = q.scene == "*" ? everyone : mine;
        session.execute(fmt::format("USE SCENE '{}'", q.scene), ignore);
        engine->execute(fmt::format("USE SCENE '{}'", q.scene));
        const double store = medianMicros([&] { session.execute(q.statement, ignore); });
        const double mineLocal = medianMicros([&] { engine->execute(q.statement); });
        fmt::print("| {} | {:.0f} us | {:.0f} us | {:.1f}x |\n", q.what, store, mineLocal, store / mineLocal);
    }
    fmt::print(
        "\nThe store's all-scenes statements range over every device's scenes, the local ones over the "
        "first device's.\n");
}

int run(const Options& options) {
    std::string whyNot;
    auto cluster = smql::fleet::pg::LocalCluster::start({.settings = {}, .prefix = "smql-bench-fleet"}, whyNot);
    if (!cluster) {
        fmt::print("smql_bench_fleet: skipped: {}\n", whyNot);
        return 0;
    }
    std::string pattern = (fs::temp_directory_path() / "smql-bench-fleet-XXXXXX").string();
    fs::path work = mkdtemp(pattern.data());
    std::vector<std::unique_ptr<smql::storage::Database>> devices;
    for (int d = 0; d < 5; ++d) devices.push_back(buildDevice(work / fmt::format("device{}", d), d, options));

    cluster->createDatabase("fleet");
    const std::string url = cluster->url("fleet");
    // Shards: the first on this cluster beside the coordinator, the others on clusters of their own.
    std::vector<std::unique_ptr<smql::fleet::pg::LocalCluster>> others;
    std::vector<std::string> shards;
    for (int i = 0; i < options.shards; ++i) {
        if (i > 0)
            others.push_back(
                smql::fleet::pg::LocalCluster::start({.settings = {}, .prefix = "smql-bench-fleet"}, whyNot));
        smql::fleet::pg::LocalCluster& at = i == 0 ? *cluster : *others.back();
        at.createDatabase("fleet_shard");
        shards.push_back(at.url("fleet_shard"));
    }
    if (shards.empty())
        smql::fleet::init(url);
    else
        smql::fleet::initSharded(url, shards);
    fmt::print("{}; {} scenes x {} objects per device; {}; {} hardware threads\n\n", cluster->version(), options.scenes,
               options.objects,
               shards.empty() ? std::string("one server") : fmt::format("a coordinator over {} shards", shards.size()),
               std::thread::hardware_concurrency());
    fmt::print("| push | scene versions sent | nodes sent | time | scenes/s | nodes/s |\n|---|---|---|---|---|---|\n");

    auto started = Clock::now();
    auto one = smql::fleet::push(*devices[0], url);
    row("one device", {one}, secondsSince(started));

    std::vector<smql::fleet::PushReport> four(4);
    std::vector<std::thread> threads;
    started = Clock::now();
    for (int d = 0; d < 4; ++d)
        threads.emplace_back([&, d] { four[static_cast<std::size_t>(d)] = smql::fleet::push(*devices[d + 1], url); });
    for (auto& t : threads) t.join();
    row("four devices at once", four, secondsSince(started));

    started = Clock::now();
    auto nothing = smql::fleet::push(*devices[0], url);
    fmt::print("| again, nothing to send ({} present) | {} | {} | {:.1f} ms | - | - |\n", nothing.present, nothing.sent,
               nothing.nodes, secondsSince(started) * 1000);
    queryLatency(url, one.device, work / "device0");
    devices.clear();
    fs::remove_all(work);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"smql_bench_fleet: push throughput into a fleet store (PostgreSQL + PostGIS)"};
    Options options;
    app.add_option("--scenes", options.scenes, "scenes per device (default 100)")->check(CLI::PositiveNumber);
    app.add_option("--objects", options.objects, "objects per scene (default 200)")->check(CLI::PositiveNumber);
    app.add_option("--shards", options.shards, "push through a coordinator over this many shards (default: one server)")
        ->check(CLI::Range(1, 8));
    CLI11_PARSE(app, argc, argv);
    try {
        return run(options);
    } catch (const std::exception& e) {
        std::cerr << "smql_bench_fleet: " << e.what() << "\n";
        return 1;
    }
}
