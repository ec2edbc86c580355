#include "engine/eval/evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/engine.hpp"
#include "engine/guide/route_graph.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"
#include "model/names.hpp"
#include "relations/predicates.hpp"

namespace smql::eval {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using model::Node;
using Report = std::vector<Metric>;

namespace {

// The suite's settings, each with its documented default (docs/eval.md).
struct Settings {
    double dThr = 1.0;       // guidance succeeds when the walk ends this close to the goal's footprint (m)
    double tauLoc = 0.5;     // a retrieved thing is the sought one when its centre is this close (m)
    double tauMatch = 1.0;   // a truth reference is the memory's node of its category this close (m)
    double truthBody = 0.1;  // the body radius a step must clear in the true room (m)
};

double centreDistance(const Node& a, const Node& b) {
    return std::hypot(a.box.center.x - b.box.center.x, a.box.center.y - b.box.center.y,
                      a.box.center.z - b.box.center.z);
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

struct Ratio {
    std::size_t hits = 0, total = 0;
    void add(bool hit) {
        hits += hit;
        ++total;
    }
    double value() const { return total ? static_cast<double>(hits) / total : 0; }
};

class Evaluation {
public:
    Evaluation(Engine& engine, model::SceneData truth, model::SceneData memory, Settings settings)
        : engine_(engine), truth_(std::move(truth)), memory_(std::move(memory)), settings_(settings) {
        for (const auto& n : truth_.nodes) truthById_.emplace(n.id, &n);
        for (const auto& n : memory_.nodes) memoryById_.emplace(n.id, &n);
    }

    // How far apart two things are for matching: their centres; for two planes (walls), how far
    // the memory's centre lies off the truth's plane, when it lies within the plane's extent (a
    // wall seen in part has its centre elsewhere on the same wall).
    static double matchDistance(const Node& memory, const Node& truth) {
        if (memory.geometry != model::GeometryKind::Plane || truth.geometry != model::GeometryKind::Plane)
            return centreDistance(memory, truth);
        const model::Box& b = truth.box;
        bool alongX = b.size.x >= b.size.y;
        double angle = b.yaw + (alongX ? 0.0 : M_PI / 2);
        double ux = std::cos(angle), uy = std::sin(angle);
        double dx = memory.box.center.x - b.center.x, dy = memory.box.center.y - b.center.y;
        double along = std::abs(dx * ux + dy * uy), across = std::abs(-dx * uy + dy * ux);
        double halfLength = (alongX ? b.size.x : b.size.y) / 2;
        double parallel = std::abs(std::sin(memory.box.yaw - b.yaw));
        bool sameLine = parallel < 0.2 || parallel > 0.98;  // either horizontal axis may be the long one
        return sameLine && along <= halfLength ? across : std::numeric_limits<double>::infinity();
    }

    // The memory's node for a truth node: its category, the nearest within tauMatch.
    const Node* match(const Node& t) const {
        const Node* best = nullptr;
        double bestDistance = settings_.tauMatch;
        for (const auto& n : memory_.nodes) {
            if (n.hidden || n.category != t.category || n.geometry == model::GeometryKind::None) continue;
            double d = matchDistance(n, t);
            if (d <= bestDistance) {
                bestDistance = d;
                best = &n;
            }
        }
        return best;
    }

    const Node& truthNode(const Json& id) const {
        auto it = truthById_.find(id.get<model::NodeId>());
        if (it == truthById_.end())
            throw Error(ErrorKind::Input,
                        fmt::format("the suite names truth node {}, which truth.json lacks", id.dump()), std::nullopt,
                        "regenerate the suite with smql synth");
        return *it->second;
    }

    ResultSet query(const std::string& statement, std::vector<double>& latencies) {
        const auto start = std::chrono::steady_clock::now();
        ResultSet rs = engine_.execute(statement).back();
        latencies.push_back(
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
        return rs;
    }

    // Left or right of the anchor in the true room, as the memory's viewpoint sees it; nullopt: neither.
    std::optional<model::RelationType> lateral(const Node& a, const Node& b, const relations::Frame& frame) const {
        const relations::Thresholds thresholds;
        const relations::NodeObstacles obstacles(truth_.nodes);
        for (auto type : {model::RelationType::LeftOf, model::RelationType::RightOf})
            if (relations::evaluate(type, a, b, thresholds, frame, obstacles) > 0) return type;
        return std::nullopt;
    }

    void relativePosition(const Json& episodes, Report& report) {
        const relations::Frame frame = relations::viewFrame(memory_.info.viewpoint);
        std::map<std::string, Ratio> byAnchor;
        Ratio all;
        std::vector<double> latency;
        for (const auto& e : episodes) {
            const Node& subject = truthNode(e["subject"]);
            const Node& anchor = truthNode(e["anchor"]);
            auto truth = lateral(subject, anchor, frame);
            if (!truth) continue;  // side by side in depth: no lateral answer to score
            bool correct = false;
            const Node* s = match(subject);
            const Node* a = match(anchor);
            if (s && a) {
                auto left = query(fmt::format("COUNT #{} WHERE left_of(#{})", s->id, a->id), latency);
                auto right = query(fmt::format("COUNT #{} WHERE right_of(#{})", s->id, a->id), latency);
                bool isLeft = std::get<std::int64_t>(left.rows[0][0]) > 0;
                bool isRight = std::get<std::int64_t>(right.rows[0][0]) > 0;
                correct = *truth == model::RelationType::LeftOf ? isLeft && !isRight : isRight && !isLeft;
            }
            all.add(correct);
            byAnchor[anchor.category].add(correct);
        }
        add(report, "relative position", "Acc_rel", all, latency);
        for (const auto& [type, ratio] : byAnchor)
            add(report, "relative position", "Acc_rel (" + type + ")", ratio, latency);
    }

    // The categories from the room down to the node, scene excluded.
    static std::vector<const Node*> chain(const Node& n, const std::unordered_map<model::NodeId, const Node*>& byId) {
        std::vector<const Node*> out{&n};
        for (auto it = byId.find(n.parent); it != byId.end() && it->second->kind != model::NodeKind::Scene;
             it = byId.find(it->second->parent))
            out.push_back(it->second);
        std::reverse(out.begin(), out.end());
        return out;
    }

    void retrieval(const Json& episodes, Report& report) {
        Ratio found, parent, path, colour, locParent, locPath;
        std::vector<double> latency;
        for (const auto& e : episodes) {
            const Node& t = truthNode(e["object"]);
            auto rs = query(fmt::format("FIND '{}' PATH", t.category), latency);
            const Node* hit = nullptr;
            double best = settings_.tauLoc;
            int idColumn = rs.columnIndex("id");
            for (const auto& row : rs.rows) {
                auto it = memoryById_.find(static_cast<model::NodeId>(std::get<std::int64_t>(row[idColumn])));
                if (it == memoryById_.end()) continue;
                double d = centreDistance(*it->second, t);
                if (d <= best) best = d, hit = it->second;
            }
            found.add(hit != nullptr);
            auto truthChain = chain(t, truthById_);
            std::vector<const Node*> memoryChain = hit ? chain(*hit, memoryById_) : std::vector<const Node*>{};
            auto category = [](const std::vector<const Node*>& c, std::size_t fromEnd) {
                return c.size() > fromEnd ? c[c.size() - 1 - fromEnd]->category : std::string("(none)");
            };
            parent.add(hit && category(memoryChain, 1) == category(truthChain, 1));
            bool samePath = hit && memoryChain.size() == truthChain.size();
            bool locatedPath = samePath;
            for (std::size_t i = 0; samePath && i < truthChain.size(); ++i) {
                samePath = memoryChain[i]->category == truthChain[i]->category;
                locatedPath =
                    locatedPath && samePath && matchDistance(*memoryChain[i], *truthChain[i]) <= settings_.tauMatch;
            }
            path.add(samePath);
            locPath.add(locatedPath);
            // A thing whose parent is the room itself (a layout without anchors) has its parent
            // located when the memory's is the room too.
            const bool bothUnderRoom = memoryChain.size() == 1 && truthChain.size() == 1;
            bool parentThere =
                hit && (bothUnderRoom || (memoryChain.size() >= 2 && truthChain.size() >= 2 &&
                                          category(memoryChain, 1) == category(truthChain, 1) &&
                                          matchDistance(*memoryChain[memoryChain.size() - 2],
                                                        *truthChain[truthChain.size() - 2]) <= settings_.tauMatch));
            locParent.add(parentThere);
            if (const std::string* c = t.attribute("color")) {
                const std::string* m = hit ? hit->attribute("color") : nullptr;
                colour.add(m && *m == *c);
            }
        }
        add(report, "object retrieval", "SR_obj", found, latency);
        add(report, "object retrieval", "Acc_parent", parent, latency);
        add(report, "object retrieval", "Acc_path", path, latency);
        add(report, "object retrieval", "Color Acc", colour, latency);
        add(report, "object retrieval", "Loc@parent", locParent, latency);
        add(report, "object retrieval", "Loc@path", locPath, latency);
    }

    void guidance(const Json& episodes, Report& report) {
        // The shortest way in the true room, for the same walker as GUIDE's; and the true room for a
        // thinner one, in which a step must be walkable (boxes that are a little off do not fail it).
        guide::GraphOptions truthOptions;
        guide::FreeSpace truthSpace(truth_.nodes, truthOptions);
        guide::RouteGraph truthGraph = guide::buildGraph(truth_.nodes, truthSpace, truthOptions);
        guide::GraphOptions thinOptions;
        thinOptions.bodyRadius = settings_.truthBody;
        guide::FreeSpace thinSpace(truth_.nodes, thinOptions);
        Ratio success, routed;
        std::vector<double> stepCompletion, spl, failedErrors, latency;
        for (const auto& e : episodes) {
            // From a door (a truth node) or from a point of the floor.
            const bool fromPoint = e.contains("from_point");
            const Node* from = fromPoint ? nullptr : &truthNode(e["from"]);
            const guide::Point origin =
                fromPoint ? guide::Point{e["from_point"][0].get<double>(), e["from_point"][1].get<double>()}
                          : guide::Point{from->box.center.x, from->box.center.y};
            const Node& to = truthNode(e["to"]);
            const Node* start = fromPoint ? nullptr : match(*from);
            const Node* goal = match(to);
            std::vector<guide::Point> walk;
            double walked = 0;
            if ((fromPoint || start) && goal) {
                try {
                    auto rs = query(fromPoint ? fmt::format("GUIDE FROM ({}, {}) TO #{}", origin.x, origin.y, goal->id)
                                              : fmt::format("GUIDE FROM #{} TO #{}", start->id, goal->id),
                                    latency);
                    int x = rs.columnIndex("x"), y = rs.columnIndex("y"), d = rs.columnIndex("distance");
                    // The last row is the goal itself, not a place walked to.
                    for (std::size_t i = 0; i + 1 < rs.rows.size(); ++i) {
                        walk.push_back({std::get<double>(rs.rows[i][x]), std::get<double>(rs.rows[i][y])});
                        walked += std::get<double>(rs.rows[i][d]);
                    }
                } catch (const Error&) {
                    walk.clear();  // no route in the memory: the episode fails
                }
            }
            routed.add(!walk.empty());
            if (walk.empty()) {
                success.add(false);
                stepCompletion.push_back(0);
                spl.push_back(0);
                failedErrors.push_back(model::footprintGap(to.box, {origin.x, origin.y}));
                continue;
            }
            double error = model::footprintGap(to.box, {walk.back().x, walk.back().y});
            bool reached = error <= settings_.dThr;
            success.add(reached);
            std::size_t completed = 0;
            for (std::size_t i = 1; i < walk.size(); ++i) completed += thinSpace.clear(walk[i - 1], walk[i]);
            stepCompletion.push_back(walk.size() > 1 ? static_cast<double>(completed) / (walk.size() - 1) : 1.0);
            double shortest = walked;
            if (auto end = truthSpace.nearestFree(walk.back(), 1.0))
                if (auto route = guide::shortestRoute(truthGraph, truthSpace, walk.front(), *end, truthOptions))
                    shortest = route->length;
            // A goal reached without a step (the start is beside it) is a perfect walk.
            const double longer = std::max(walked, shortest);
            spl.push_back(!reached ? 0 : longer > 0 ? shortest / longer : 1);
            if (!reached) failedErrors.push_back(error);
        }
        add(report, "guidance", "Reach", routed, latency);
        add(report, "guidance", "SR_nav", success, latency);
        addValue(report, "guidance", "StepComp", mean(stepCompletion), stepCompletion.size(), latency);
        addValue(report, "guidance", "SPL", mean(spl), spl.size(), latency);
        addValue(report, "guidance", "NE (m, failed)", mean(failedErrors), failedErrors.size(), latency);
    }

    const std::string& sceneName() const { return memory_.info.name; }

private:
    static double mean(const std::vector<double>& v) {
        double sum = 0;
        for (double x : v) sum += x;
        return v.empty() ? 0 : sum / v.size();
    }
    static void add(Report& report, const std::string& task, const std::string& metric, const Ratio& r,
                    const std::vector<double>& latency) {
        addValue(report, task, metric, r.value(), r.total, latency);
    }
    static void addValue(Report& report, const std::string& task, const std::string& metric, double value,
                         std::size_t episodes, const std::vector<double>& latency) {
        report.push_back({task, metric, value, episodes, median(latency)});
    }

    Engine& engine_;
    model::SceneData truth_, memory_;
    Settings settings_;
    std::unordered_map<model::NodeId, const Node*> truthById_, memoryById_;
};

// A thing the suite asks about: an object with a box, not walked over (a rug) and not above a
// walker's reach (a ceiling light).
constexpr double kReachHeight = 1.8;

// The anchors relative position is scored against: walls, doors and windows; in a layout without
// them, the largest things standing on the floor, as the landmarks a person would name.
constexpr std::size_t kFurnitureAnchors = 4;

// A suite for a scene that is its own truth (docs/eval.md, "Suites for real layouts"): every thing
// paired with every anchor and sought; every thing on the floor or on what stands there routed to
// from every door (or, without doors, from the open floor nearest the room's middle).
Json generateSuite(const model::SceneData& truth) {
    const guide::GraphOptions options;
    const guide::Footing footing(truth.nodes, options);
    std::vector<const Node*> things, goals, anchors, doors, standing;
    for (const Node& n : truth.nodes) {
        if (n.hidden || n.geometry == model::GeometryKind::None) continue;
        if (n.kind == model::NodeKind::Anchor) {
            if (n.category == "wall" || n.category == "door" || n.category == "window") anchors.push_back(&n);
            if (n.category == "door") doors.push_back(&n);
        } else if (n.kind == model::NodeKind::Object && !footing.walkedOver(n) &&
                   model::bottom(n.box) - footing.floor() < kReachHeight) {
            things.push_back(&n);
            if (footing.stands(n)) standing.push_back(&n);
            // Guidance goes to what stands on the floor or rests on something that does, not to
            // what hangs on a wall (a picture, a wall plug).
            if (footing.stands(footing.support(n))) goals.push_back(&n);
        }
    }
    Json suite{{"smql_eval", 1}, {"scene", truth.info.name}, {"truth", "truth.json"}};
    if (anchors.empty()) {
        std::sort(standing.begin(), standing.end(), [](const Node* a, const Node* b) {
            return model::footprintArea(a->box) > model::footprintArea(b->box);
        });
        anchors.assign(standing.begin(), standing.begin() + std::min(standing.size(), kFurnitureAnchors));
    }
    Json relative = Json::array(), guidance = Json::array(), retrieval = Json::array();
    for (const Node* t : things) {
        for (const Node* a : anchors)
            if (a != t) relative.push_back({{"subject", t->id}, {"anchor", a->id}});
        retrieval.push_back({{"object", t->id}});
    }
    if (!doors.empty()) {
        for (const Node* d : doors)
            for (const Node* t : goals) guidance.push_back({{"from", d->id}, {"to", t->id}});
    } else {
        const guide::FreeSpace space(truth.nodes, options);
        const guide::Point middle{space.minX() + space.width() * space.cell() / 2,
                                  space.minY() + space.height() * space.cell() / 2};
        if (auto start = space.nearestFree(middle, std::hypot(space.width(), space.height()) * space.cell()))
            for (const Node* t : goals)
                guidance.push_back(
                    {{"from_point", {std::round(start->x * 1000) / 1000, std::round(start->y * 1000) / 1000}},
                     {"to", t->id}});
    }
    suite["relative_position"] = relative;
    suite["guidance"] = guidance;
    suite["retrieval"] = retrieval;
    return suite;
}

Json readSuite(const std::string& path) {
    std::ifstream in(path);
    if (!in)
        throw Error(ErrorKind::Input, fmt::format("cannot read the suite {}", path), std::nullopt,
                    "smql synth writes one as <out>/eval-suite.json; smql eval --write-suite DIR another");
    Json suite;
    try {
        suite = Json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(ErrorKind::Input, fmt::format("{}: not a suite: {}", path, e.what()), std::nullopt,
                    "docs/eval.md describes the format");
    }
    if (!suite.contains("smql_eval") || !suite.contains("truth"))
        throw Error(ErrorKind::Input, fmt::format("{}: not an smql evaluation suite", path), std::nullopt,
                    "docs/eval.md describes the format");
    return suite;
}

}  // namespace

EvalReport evaluate(Engine& engine, const EvalRequest& request) {
    std::vector<std::string> stored;
    const auto shown = engine.execute("SHOW SCENES");
    for (const auto& row : shown.back().rows) stored.push_back(std::get<std::string>(row[0]));
    auto has = [&](const std::string& name) { return std::find(stored.begin(), stored.end(), name) != stored.end(); };

    Json suite = request.suite.empty() ? Json() : readSuite(request.suite);
    // The memory's scene: named, else the suite's when the database has it, else the only one.
    std::string sceneName = request.scene;
    if (sceneName.empty() && !request.suite.empty()) sceneName = suite.value("scene", std::string());
    if (!request.scene.empty() || !sceneName.empty()) {
        if (!has(sceneName) && request.scene.empty() && stored.size() == 1) sceneName = stored.front();
        engine.execute("USE SCENE " + model::quoted(sceneName));
    }
    model::SceneData memory = engine.readScene(sceneName);

    EvalReport report;
    if (request.suite.empty()) {
        // The scene as a file (local ids, as `smql export json` writes it): the truth the suite names.
        report.truth = engine.exportScene(memory.info.name);
        suite = generateSuite(report.truth);
    } else {
        const fs::path truthPath = fs::path(request.suite).parent_path() / suite["truth"].get<std::string>();
        report.truth = import::read("json", truthPath.string());
    }
    report.suiteJson = suite.dump(1) + "\n";

    Settings settings;
    if (auto s = suite.find("settings"); s != suite.end()) {
        settings.dThr = s->value("d_thr", settings.dThr);
        settings.tauLoc = s->value("tau_loc", settings.tauLoc);
        settings.tauMatch = s->value("tau_match", settings.tauMatch);
        settings.truthBody = s->value("truth_body_radius", settings.truthBody);
    }
    Evaluation evaluation(engine, report.truth, std::move(memory), settings);
    evaluation.relativePosition(suite.value("relative_position", Json::array()), report.metrics);
    evaluation.guidance(suite.value("guidance", Json::array()), report.metrics);
    evaluation.retrieval(suite.value("retrieval", Json::array()), report.metrics);
    report.scene = evaluation.sceneName();
    return report;
}

}  // namespace smql::eval
