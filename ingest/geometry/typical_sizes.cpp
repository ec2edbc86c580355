#include "ingest/geometry/typical_sizes.hpp"

namespace smql::ingest {

namespace {

// Heights: the common standard sizes (a dining table's top at 28-30 in, a door 80 in), only where
// the kind varies by a tenth or so (0: it varies more). Footprints: the large end of what shops
// sell (a three-seat sofa, a king bed, a bookcase), so that only a hull far too long is cut.
// Extents: the largest side, height included, things of the kind commonly have (a floor lamp's
// 1.9 m, a bookcase's 2.2 m): what a box named so may reach before its name is doubted. The rows
// cover the memory's names for the detector's COCO classes (detector.cpp) and the kinds of
// labelled captures.
struct Typical {
    std::string_view category;
    double height;
    Footprint largest;
    double extent;
};
constexpr Typical kTypical[] = {
    {"table", 0.75, {2.2, 1.2}, 2.4},     {"desk", 0.75, {1.8, 0.9}, 1.9},      {"chair", 0.9, {0.7, 0.7}, 1.2},
    {"sofa", 0.85, {2.5, 1.1}, 2.8},      {"bed", 0.55, {2.2, 2.0}, 2.3},       {"fridge", 1.75, {0.95, 0.85}, 2.0},
    {"toilet", 0.75, {0.75, 0.5}, 0.9},   {"door", 2.03, {1.2, 0.3}, 2.4},      {"nightstand", 0.6, {0.65, 0.55}, 0.8},
    {"shelf", 0, {1.5, 0.5}, 2.4},        {"cabinet", 0, {1.8, 0.7}, 2.4},      {"counter", 0, {3.5, 0.8}, 4.0},
    {"wardrobe", 0, {2.4, 0.7}, 2.6},     {"dresser", 0, {1.8, 0.6}, 1.9},      {"armchair", 0, {1.1, 1.0}, 1.2},
    {"stool", 0, {0.5, 0.5}, 0.9},        {"bench", 0, {2.0, 0.6}, 2.2},        {"tv", 0, {1.8, 0.4}, 2.0},
    {"monitor", 0, {0.8, 0.3}, 0.9},      {"lamp", 0, {0.6, 0.6}, 2.0},         {"plant", 0, {0.8, 0.8}, 2.2},
    {"cushion", 0, {0.65, 0.65}, 0.8},    {"laptop", 0, {0.42, 0.32}, 0.5},     {"book", 0, {0.35, 0.28}, 0.5},
    {"clock", 0, {0.5, 0.2}, 0.6},        {"vase", 0, {0.35, 0.35}, 0.8},       {"bowl", 0, {0.35, 0.35}, 0.45},
    {"bottle", 0, {0.15, 0.15}, 0.45},    {"mug", 0, {0.15, 0.12}, 0.2},        {"microwave", 0, {0.6, 0.45}, 0.7},
    {"sink", 0, {1.0, 0.6}, 1.2},         {"oven", 0, {0.9, 0.7}, 1.0},         {"keyboard", 0, {0.5, 0.2}, 0.55},
    {"backpack", 0, {0.45, 0.35}, 0.65},  {"umbrella", 0, {1.1, 0.3}, 1.2},     {"handbag", 0, {0.5, 0.3}, 0.55},
    {"suitcase", 0, {0.8, 0.55}, 0.9},    {"sports_ball", 0, {0.3, 0.3}, 0.35}, {"tennis_racket", 0, {0.7, 0.3}, 0.75},
    {"wine_glass", 0, {0.12, 0.12}, 0.3}, {"fork", 0, {0.25, 0.05}, 0.3},       {"knife", 0, {0.35, 0.05}, 0.4},
    {"spoon", 0, {0.25, 0.06}, 0.3},      {"banana", 0, {0.25, 0.1}, 0.3},      {"apple", 0, {0.12, 0.12}, 0.15},
    {"orange", 0, {0.12, 0.12}, 0.15},    {"sandwich", 0, {0.25, 0.15}, 0.3},   {"broccoli", 0, {0.3, 0.2}, 0.35},
    {"carrot", 0, {0.3, 0.06}, 0.35},     {"hot_dog", 0, {0.25, 0.1}, 0.3},     {"pizza", 0, {0.5, 0.5}, 0.55},
    {"donut", 0, {0.15, 0.15}, 0.2},      {"cake", 0, {0.45, 0.45}, 0.5},       {"mouse", 0, {0.15, 0.08}, 0.2},
    {"remote", 0, {0.25, 0.08}, 0.3},     {"phone", 0, {0.2, 0.1}, 0.25},       {"toaster", 0, {0.45, 0.3}, 0.5},
    {"scissors", 0, {0.3, 0.12}, 0.35},   {"toy", 0, {0.6, 0.5}, 1.0},          {"hair_dryer", 0, {0.35, 0.15}, 0.4},
    {"toothbrush", 0, {0.25, 0.05}, 0.3}, {"skateboard", 0, {0.85, 0.25}, 0.9},
};

const Typical* find(std::string_view category) {
    for (const auto& t : kTypical)
        if (t.category == category) return &t;
    return nullptr;
}

}  // namespace

std::optional<double> typicalHeight(std::string_view category) {
    const Typical* t = find(category);
    if (!t || t->height <= 0) return std::nullopt;
    return t->height;
}

std::optional<double> typicalExtent(std::string_view category) {
    const Typical* t = find(category);
    if (!t) return std::nullopt;
    return t->extent;
}

std::optional<Footprint> largestFootprint(std::string_view category) {
    const Typical* t = find(category);
    if (!t) return std::nullopt;
    return t->largest;
}

}  // namespace smql::ingest
