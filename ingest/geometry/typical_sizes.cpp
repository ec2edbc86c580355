#include "ingest/geometry/typical_sizes.hpp"

namespace smql::ingest {

namespace {

// Heights: the common standard sizes (a dining table's top at 28-30 in, a door 80 in), only where
// the kind varies by a tenth or so (0: it varies more). Footprints: the large end of what shops
// sell (a three-seat sofa, a king bed, a bookcase), so that only a hull far too long is cut.
struct Typical {
    std::string_view category;
    double height;
    Footprint largest;
};
constexpr Typical kTypical[] = {
    {"table", 0.75, {2.2, 1.2}},   {"desk", 0.75, {1.8, 0.9}},  {"chair", 0.9, {0.7, 0.7}},
    {"sofa", 0.85, {2.5, 1.1}},    {"bed", 0.55, {2.2, 2.0}},   {"fridge", 1.75, {0.95, 0.85}},
    {"toilet", 0.75, {0.75, 0.5}}, {"door", 2.03, {1.2, 0.3}},  {"nightstand", 0.6, {0.65, 0.55}},
    {"shelf", 0, {1.5, 0.5}},      {"cabinet", 0, {1.8, 0.7}},  {"counter", 0, {3.5, 0.8}},
    {"wardrobe", 0, {2.4, 0.7}},   {"dresser", 0, {1.8, 0.6}},  {"armchair", 0, {1.1, 1.0}},
    {"stool", 0, {0.5, 0.5}},      {"bench", 0, {2.0, 0.6}},    {"tv", 0, {1.8, 0.4}},
    {"monitor", 0, {0.8, 0.3}},    {"lamp", 0, {0.6, 0.6}},     {"plant", 0, {0.8, 0.8}},
    {"cushion", 0, {0.65, 0.65}},  {"laptop", 0, {0.42, 0.32}}, {"book", 0, {0.35, 0.28}},
    {"clock", 0, {0.5, 0.2}},      {"vase", 0, {0.35, 0.35}},   {"bowl", 0, {0.35, 0.35}},
    {"bottle", 0, {0.15, 0.15}},   {"mug", 0, {0.15, 0.12}},    {"microwave", 0, {0.6, 0.45}},
    {"sink", 0, {1.0, 0.6}},       {"oven", 0, {0.9, 0.7}},     {"keyboard", 0, {0.5, 0.2}},
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

std::optional<Footprint> largestFootprint(std::string_view category) {
    const Typical* t = find(category);
    if (!t) return std::nullopt;
    return t->largest;
}

}  // namespace smql::ingest
