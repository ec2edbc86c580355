#include "ingest/geometry/typical_sizes.hpp"

namespace smql::ingest {

namespace {

// Heights: the common standard sizes (a dining table's top at 28-30 in, a door 80 in), only where
// the kind varies by a tenth or so (0: it varies more). Footprints: the large end of what shops
// sell (a three-seat sofa, a king bed, a bookcase), so that only a hull far too long is cut.
// Extents: the largest side, height included, things of the kind commonly have (a floor lamp's
// 1.9 m, a bookcase's 2.2 m): what a box named so may reach before its name is doubted. Support:
// what things of the kind usually stand on (the floor, or a table, desk or counter), which tells a
// floor from a table top (floor_evidence.hpp), as does whether things are put on the kind's top
// (a table's, a bed's). The rows cover the memory's names for the detector's COCO classes
// (detector.cpp) and the kinds of labelled captures.
struct Typical {
    std::string_view category;
    double height;
    Footprint largest;
    double extent;
    Support support;
    bool holdsThings = false;
};
constexpr Typical kTypical[] = {
    {"table", 0.75, {2.2, 1.2}, 2.4, Support::Floor, true},
    {"desk", 0.75, {1.8, 0.9}, 1.9, Support::Floor, true},
    {"chair", 0.9, {0.7, 0.7}, 1.2, Support::Floor},
    {"sofa", 0.85, {2.5, 1.1}, 2.8, Support::Floor},
    {"bed", 0.55, {2.2, 2.0}, 2.3, Support::Floor, true},
    {"fridge", 1.75, {0.95, 0.85}, 2.0, Support::Floor},
    {"toilet", 0.75, {0.75, 0.5}, 0.9, Support::Floor},
    {"door", 2.03, {1.2, 0.3}, 2.4, Support::Floor},
    {"nightstand", 0.6, {0.65, 0.55}, 0.8, Support::Floor, true},
    {"shelf", 0, {1.5, 0.5}, 2.4, Support::Floor},
    {"cabinet", 0, {1.8, 0.7}, 2.4, Support::Floor},
    {"counter", 0, {3.5, 0.8}, 4.0, Support::Floor, true},
    {"wardrobe", 0, {2.4, 0.7}, 2.6, Support::Floor},
    {"dresser", 0, {1.8, 0.6}, 1.9, Support::Floor},
    {"armchair", 0, {1.1, 1.0}, 1.2, Support::Floor},
    {"stool", 0, {0.5, 0.5}, 0.9, Support::Floor},
    {"bench", 0, {2.0, 0.6}, 2.2, Support::Floor},
    {"tv", 0, {1.8, 0.4}, 2.0, Support::Either},
    {"monitor", 0, {0.8, 0.3}, 0.9, Support::Surface},
    {"lamp", 0, {0.6, 0.6}, 2.0, Support::Either},
    {"plant", 0, {0.8, 0.8}, 2.2, Support::Either},
    {"cushion", 0, {0.65, 0.65}, 0.8, Support::Either},
    {"laptop", 0, {0.42, 0.32}, 0.5, Support::Surface},
    {"book", 0, {0.35, 0.28}, 0.5, Support::Surface},
    {"clock", 0, {0.5, 0.2}, 0.6, Support::Either},
    {"vase", 0, {0.35, 0.35}, 0.8, Support::Surface},
    {"bowl", 0, {0.35, 0.35}, 0.45, Support::Surface},
    {"bottle", 0, {0.15, 0.15}, 0.45, Support::Surface},
    {"mug", 0, {0.15, 0.12}, 0.2, Support::Surface},
    {"microwave", 0, {0.6, 0.45}, 0.7, Support::Surface},
    {"sink", 0, {1.0, 0.6}, 1.2, Support::Either},
    {"oven", 0, {0.9, 0.7}, 1.0, Support::Floor},
    {"keyboard", 0, {0.5, 0.2}, 0.55, Support::Surface},
    {"backpack", 0, {0.45, 0.35}, 0.65, Support::Either},
    {"umbrella", 0, {1.1, 0.3}, 1.2, Support::Either},
    {"handbag", 0, {0.5, 0.3}, 0.55, Support::Either},
    {"suitcase", 0, {0.8, 0.55}, 0.9, Support::Floor},
    {"sports_ball", 0, {0.3, 0.3}, 0.35, Support::Either},
    {"tennis_racket", 0, {0.7, 0.3}, 0.75, Support::Either},
    {"wine_glass", 0, {0.12, 0.12}, 0.3, Support::Surface},
    {"fork", 0, {0.25, 0.05}, 0.3, Support::Surface},
    {"knife", 0, {0.35, 0.05}, 0.4, Support::Surface},
    {"spoon", 0, {0.25, 0.06}, 0.3, Support::Surface},
    {"banana", 0, {0.25, 0.1}, 0.3, Support::Surface},
    {"apple", 0, {0.12, 0.12}, 0.15, Support::Surface},
    {"orange", 0, {0.12, 0.12}, 0.15, Support::Surface},
    {"sandwich", 0, {0.25, 0.15}, 0.3, Support::Surface},
    {"broccoli", 0, {0.3, 0.2}, 0.35, Support::Surface},
    {"carrot", 0, {0.3, 0.06}, 0.35, Support::Surface},
    {"hot_dog", 0, {0.25, 0.1}, 0.3, Support::Surface},
    {"pizza", 0, {0.5, 0.5}, 0.55, Support::Surface},
    {"donut", 0, {0.15, 0.15}, 0.2, Support::Surface},
    {"cake", 0, {0.45, 0.45}, 0.5, Support::Surface},
    {"mouse", 0, {0.15, 0.08}, 0.2, Support::Surface},
    {"remote", 0, {0.25, 0.08}, 0.3, Support::Surface},
    {"phone", 0, {0.2, 0.1}, 0.25, Support::Surface},
    {"toaster", 0, {0.45, 0.3}, 0.5, Support::Surface},
    {"scissors", 0, {0.3, 0.12}, 0.35, Support::Surface},
    {"toy", 0, {0.6, 0.5}, 1.0, Support::Either},
    {"hair_dryer", 0, {0.35, 0.15}, 0.4, Support::Surface},
    {"toothbrush", 0, {0.25, 0.05}, 0.3, Support::Surface},
    {"skateboard", 0, {0.85, 0.25}, 0.9, Support::Floor},
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

bool holdsThings(std::string_view category) {
    const Typical* t = find(category);
    return t && t->holdsThings;
}

Support usualSupport(std::string_view category) {
    const Typical* t = find(category);
    return t ? t->support : Support::Either;
}

std::optional<Footprint> largestFootprint(std::string_view category) {
    const Typical* t = find(category);
    if (!t) return std::nullopt;
    return t->largest;
}

}  // namespace smql::ingest
