// The instance map: things in the world, not detections in a frame. Each
// frame's views of things (their points in the aligned frame, what they were
// detected as and how surely) are fused into instances, one per real thing:
// a view joins the instance whose cells its own lie among (3D overlap and
// name), a frame's two views are two things, and, between frames, pieces of one
// thing are merged while things that merely touch (a table and its chairs) or
// rest on one another (a mug on a table) stay apart, and so, by their names, do a
// thing and what carries it (a monitor and its desk), however their points mix (a
// desk's views take in what stands on it, depth from photos smears one onto the
// other). The map is updated frame by
// frame, so a live memory can run it as frames stream in; consolidate() can run
// at any time (docs/ingest.md, "Objects from detections", gives the rules and
// their thresholds).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "ingest/geometry/point_cloud.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct InstanceMapOptions {
    double cell = 0.05;          // edge of the map's cells (m)
    double joinShare = 0.25;     // a view joins an instance of its name when this share of its cells (or of the
                                 // instance's) lie next to the other's cells
    double relabelShare = 0.6;   // ... of another name (voteLabels), when this share of the view's cells or of the
                                 // instance's lie next to the other's
    double relabelLeast = 0.2;   // ... and this share of both: a view that lies against an instance with few of its
                                 // own cells (a nightstand's, called "tv", beside a desk's end seen alone) is another
    double fragmentShare = 0.5;  // an instance with this share of its cells next to a larger one's core is a
                                 // piece of it (consolidate), unless it rests on it ...
    double coreShare = 0.15;     // ... the core: its cells seen by this share of its views (and two), not those a
                                 // few views took in from a neighbour
    double restingShare = 0.7;   // "rests on": this share of the larger's cells under its footprint lie below its
                                 // lowest cells (plus restingGap)
    double restingGap = 0.05;    // m
    bool voteLabels = true;      // a closed-set detector: names differ from view to view, the votes decide; but
                                 // a thing and what carries it (a monitor and its desk) are no pieces of one, and
                                 // a view of the thing joins no instance of what carries it
};

// One view of one thing: its points in the aligned frame, and what it was detected as.
struct InstanceView {
    std::uint32_t frame = 0;
    std::string label;
    double score = 1;
    std::vector<std::pair<std::string, double>> alsoSeenAs;  // other models' names for it, and their scores
    PointCloud points;
    std::size_t source = 0;  // the caller's index of the view (its Observation)
};

// A cell of an instance: the points of its views that fell in it, and how many views saw it.
struct InstanceCell {
    model::Vec3 sum{0, 0, 0};
    std::array<std::uint32_t, 3> colourSum{0, 0, 0};  // RGB
    std::uint32_t points = 0;
    std::uint32_t views = 0;
    std::uint32_t lastView = UINT32_MAX;  // the last view counted (each view counts once)
};

// What one view of an instance said it was: its label, its score, and how many of the map's cells its
// points filled (a view of the whole thing fills more than a view of a part).
struct InstanceVote {
    std::string label;
    double score = 1;
    std::size_t cells = 0;
};

struct Instance {
    std::vector<InstanceVote> votes;
    std::unordered_map<std::uint64_t, InstanceCell> cells;
    std::vector<std::size_t> sources;                           // InstanceView::source of every view fused in
    std::vector<std::uint32_t> frames;                          // sorted, unique
    model::Vec3 lo{1e18, 1e18, 1e18}, hi{-1e18, -1e18, -1e18};  // bounds of its cells' centres

    // label -> the sum of its views' scores, each weighed by the share of the instance its view
    // filled (up to half of its cells counts in full): views of the whole thing name it, views of a
    // part (an armrest seen as a "mouse") barely.
    std::map<std::string, double> tally() const;
    // The label with the largest tally.
    std::string category() const;
    bool named(const std::string& label) const;
    // The mean point of every cell seen by at least `minViews` views, with its colour.
    PointCloud points(std::uint32_t minViews = 1) const;
};

// The share of `a`'s points that have one of `b`'s in their cell of edge `cell` or a neighbouring one (the
// map's own test of pieces, InstanceMap::consolidate, on points): how much of a piece touches a thing.
double shareOfPointsNear(const PointCloud& a, const PointCloud& b, double cell);

class InstanceMap {
public:
    explicit InstanceMap(InstanceMapOptions options = {}) : options_(options) {}
    // One frame's views: each joins the instance it fits best (none of the frame's views joins one
    // another has joined), or starts one.
    void integrate(std::vector<InstanceView> frameViews);
    // Merges instances that are pieces of one thing (fragmentShare), the smaller into the larger.
    void consolidate();
    const std::vector<Instance>& instances() const { return instances_; }
    std::vector<Instance> take() { return std::move(instances_); }

private:
    std::uint64_t keyOf(const model::Vec3& p) const;
    // The share of `a`'s cells that have a cell of `b` among their 27 neighbours.
    double shareNear(const std::unordered_map<std::uint64_t, InstanceCell>& a,
                     const std::unordered_map<std::uint64_t, InstanceCell>& b) const;
    bool restsOn(const Instance& upper, const Instance& lower) const;
    std::unordered_map<std::uint64_t, InstanceCell> core(const Instance& instance) const;
    void add(Instance& instance, const InstanceView& view) const;
    static void absorb(Instance& into, Instance&& from);

    InstanceMapOptions options_;
    std::vector<Instance> instances_;
    std::uint32_t viewsAdded_ = 0;
};

}  // namespace smql::ingest
