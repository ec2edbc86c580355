#include "ingest/generate/room_generator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace smql::generate {

using model::Box;
using model::GeometryKind;
using model::Node;
using model::NodeKind;

namespace {

struct FurnitureKind {
    const char* category;
    double sx, sy, sz;  // typical size (m)
    int smallSlots;     // how many small things fit on top
};

// Each furniture group fills one cell of the floor: a main piece, sometimes chairs beside it.
constexpr std::array<FurnitureKind, 8> kFurniture = {{{"desk", 1.2, 0.6, 0.75, 3},
                                                      {"table", 1.4, 0.9, 0.74, 4},
                                                      {"sofa", 2.0, 0.9, 0.85, 3},
                                                      {"bed", 2.0, 1.6, 0.55, 3},
                                                      {"cabinet", 1.0, 0.5, 0.9, 2},
                                                      {"shelf", 0.9, 0.35, 1.8, 2},
                                                      {"nightstand", 0.45, 0.4, 0.55, 1},
                                                      {"counter", 1.8, 0.6, 0.9, 4}}};

struct SmallKind {
    const char* category;
    double sx, sy, sz;
};
constexpr std::array<SmallKind, 10> kSmall = {{{"mug", 0.09, 0.09, 0.1},
                                               {"book", 0.22, 0.16, 0.04},
                                               {"lamp", 0.25, 0.25, 0.45},
                                               {"plant", 0.25, 0.25, 0.4},
                                               {"laptop", 0.34, 0.24, 0.03},
                                               {"bottle", 0.08, 0.08, 0.28},
                                               {"bowl", 0.18, 0.18, 0.08},
                                               {"vase", 0.14, 0.14, 0.3},
                                               {"clock", 0.2, 0.08, 0.2},
                                               {"cushion", 0.4, 0.4, 0.15}}};

constexpr std::array<const char*, 11> kColors = {"red",  "orange", "yellow", "green", "blue", "purple",
                                                 "pink", "brown",  "black",  "white", "gray"};

constexpr double kCell = 2.6;  // side of a furniture cell (m)
constexpr double kWallHeight = 2.7;
constexpr double kWallThickness = 0.1;

class Builder {
public:
    explicit Builder(const RoomOptions& o) : rng_(o.seed), options_(o) {}

    GeneratedRoom build() {
        // A cell holds four objects on average (a piece, sometimes chairs, small things on top):
        // size the floor for 3.5 per cell so that the cells hold the requested count.
        int cells = std::max(1, (options_.objectCount * 2 + 6) / 7);
        int cols = std::max(2, static_cast<int>(std::ceil(std::sqrt(cells * 1.3))));
        int rows = std::max(2, (cells + cols - 1) / cols);
        width_ = cols * kCell;
        depth_ = rows * kCell;
        scene_.info.name = options_.name;
        scene_.info.source = "generated:seed=" + std::to_string(options_.seed);

        addStructure();
        std::vector<std::pair<int, int>> order;
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) order.emplace_back(r, c);
        std::shuffle(order.begin(), order.end(), rng_);
        for (const auto& [r, c] : order) {
            if (objects_ >= options_.objectCount) break;
            addGroup(c * kCell, r * kCell);
        }
        // Default viewpoint: just inside the door at eye height, looking into the room (+y).
        scene_.info.viewpoint = {{doorX_, 0.6, 1.6}, M_PI / 2};
        scene_.info.viewpointNote = "standing 0.6 m inside the door at eye height (1.6 m), facing into the room";
        return {std::move(scene_), std::move(supports_)};
    }

private:
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

    model::NodeId add(NodeKind kind, std::string category, GeometryKind g, Box box) {
        Node n;
        n.id = scene_.nodes.size() + 1;
        n.kind = kind;
        n.category = std::move(category);
        n.geometry = g;
        n.box = box;
        n.sourceId = static_cast<std::int64_t>(n.id);
        n.confidence = kind == NodeKind::Object ? static_cast<float>(uniform(0.6, 1.0)) : 1.0f;
        if (kind == NodeKind::Object) {
            ++objects_;
            n.attributes.push_back({"color", kColors[pick(kColors.size())]});
        }
        scene_.nodes.push_back(std::move(n));
        return scene_.nodes.back().id;
    }

    void addStructure() {
        add(NodeKind::Anchor, "floor", GeometryKind::Plane,
            {{width_ / 2, depth_ / 2, -0.01}, {width_, depth_, 0.02}, 0});
        add(NodeKind::Anchor, "ceiling", GeometryKind::Plane,
            {{width_ / 2, depth_ / 2, kWallHeight + 0.01}, {width_, depth_, 0.02}, 0});
        const double h = kWallHeight / 2, t = kWallThickness;
        // South, north, west, east: each wall's box x axis runs along the wall.
        add(NodeKind::Anchor, "wall", GeometryKind::Plane, {{width_ / 2, -t / 2, h}, {width_, t, kWallHeight}, 0});
        add(NodeKind::Anchor, "wall", GeometryKind::Plane,
            {{width_ / 2, depth_ + t / 2, h}, {width_, t, kWallHeight}, 0});
        add(NodeKind::Anchor, "wall", GeometryKind::Plane,
            {{-t / 2, depth_ / 2, h}, {depth_, t, kWallHeight}, M_PI / 2});
        add(NodeKind::Anchor, "wall", GeometryKind::Plane,
            {{width_ + t / 2, depth_ / 2, h}, {depth_, t, kWallHeight}, M_PI / 2});
        doorX_ = uniform(1.0, width_ - 1.0);
        add(NodeKind::Anchor, "door", GeometryKind::Plane, {{doorX_, -t / 2, 1.05}, {0.9, t, 2.1}, 0});
        int windows = 1 + static_cast<int>(width_ / 6);
        for (int i = 0; i < windows; ++i) {
            double x = width_ * (i + 0.5) / windows;
            add(NodeKind::Anchor, "window", GeometryKind::Plane, {{x, depth_ + t / 2, 1.5}, {1.2, t, 1.2}, 0});
        }
        add(NodeKind::Anchor, "window", GeometryKind::Plane,
            {{width_ + t / 2, uniform(1.0, depth_ - 1.0), 1.5}, {1.2, t, 1.2}, M_PI / 2});
    }

    void addGroup(double x0, double y0) {
        const FurnitureKind& kind = kFurniture[pick(kFurniture.size())];
        double scale = uniform(0.9, 1.1);
        double sx = kind.sx * scale, sy = kind.sy * scale, sz = kind.sz * uniform(0.95, 1.05);
        // Turn a quarter of the pieces by 90 degrees, and jitter each a little.
        double yaw = (pick(4) == 0 ? M_PI / 2 : 0) + uniform(-0.05, 0.05);
        double cx = x0 + kCell / 2 + uniform(-0.3, 0.3), cy = y0 + kCell / 2 + uniform(-0.3, 0.3);
        Box main{{cx, cy, sz / 2}, {sx, sy, sz}, yaw};
        model::NodeId mainId = add(NodeKind::Object, kind.category, GeometryKind::Box, main);

        std::string_view category = kind.category;
        if ((category == "desk" || category == "table") && objects_ < options_.objectCount) {
            int chairs = category == "desk" ? 1 : 2;
            for (int i = 0; i < chairs && objects_ < options_.objectCount; ++i) {
                double side = i == 0 ? -1 : 1;
                double ox = -std::sin(yaw) * side * (sy / 2 + 0.35), oy = std::cos(yaw) * side * (sy / 2 + 0.35);
                add(NodeKind::Object, "chair", GeometryKind::Box, {{cx + ox, cy + oy, 0.45}, {0.5, 0.5, 0.9}, yaw});
            }
        }
        // Small things in slots along the top, each resting on it.
        int slots = kind.smallSlots;
        for (int i = 0; i < slots && objects_ < options_.objectCount; ++i) {
            const SmallKind& small =
                category == "sofa" || category == "bed" ? kSmall[9] : kSmall[pick(kSmall.size() - 1)];
            double along = (i + 0.5) / slots - 0.5;
            double lx = along * sx * 0.9, ly = uniform(-0.2, 0.2) * sy;
            double wx = cx + std::cos(yaw) * lx - std::sin(yaw) * ly;
            double wy = cy + std::sin(yaw) * lx + std::cos(yaw) * ly;
            double s = uniform(0.85, 1.15);
            model::NodeId id = add(NodeKind::Object, small.category, GeometryKind::Box,
                                   {{wx, wy, sz + small.sz * s / 2},
                                    {small.sx * s, small.sy * s, small.sz * s},
                                    yaw + uniform(-0.3, 0.3)});
            supports_.push_back({id, mainId});
        }
    }

    std::mt19937_64 rng_;
    RoomOptions options_;
    model::SceneData scene_;
    std::vector<Support> supports_;
    double width_ = 0, depth_ = 0, doorX_ = 0;
    int objects_ = 0;
};

}  // namespace

model::SceneData generateRoom(const RoomOptions& options) { return Builder(options).build().scene; }

GeneratedRoom generateRoomWithSupports(const RoomOptions& options) { return Builder(options).build(); }

}  // namespace smql::generate
