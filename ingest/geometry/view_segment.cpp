#include "ingest/geometry/view_segment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <unordered_map>

#include "ingest/geometry/clusters.hpp"

namespace smql::ingest {

RoomSurfaces roomSurfaces(const Alignment& alignment, const std::vector<WallSegment>* walls) {
    return {alignment.floorFound, alignment.ceilingHeight, walls, alignment.tableTopHeight};
}

bool onRoomSurface(const model::Vec3& p, const RoomSurfaces& room, const ViewSegmentOptions& options) {
    if (room.floorFound && p.z < options.floorMargin) return true;
    if (room.ceilingHeight && p.z > *room.ceilingHeight - options.ceilingMargin) return true;
    if (!room.walls) return false;
    for (const auto& wall : *room.walls) {
        // In front of the wall's plane by more than the margin (and its surface band): the room.
        if (wall.signedDistance(p) > std::max(options.wallMargin, wall.surfaceBand())) continue;
        const model::Vec3 d = wall.direction();
        const double along = d.x * p.x + d.y * p.y;
        if (along >= wall.along0 - options.wallReach && along <= wall.along1 + options.wallReach &&
            p.z >= wall.z0 - options.wallReach && p.z <= wall.z1 + options.wallReach)
            return true;
    }
    return false;
}

namespace {

// The height of the top a thing stands on: the fullest bin of the heights, when it holds
// surfaceShare of the points and enough points lie above it.
std::optional<double> supportTop(const PointCloud& cloud, const ViewSegmentOptions& options) {
    std::map<long, std::size_t> bins;
    for (const auto& p : cloud.points) ++bins[static_cast<long>(std::floor(p.z / options.surfaceBin))];
    auto fullest =
        std::max_element(bins.begin(), bins.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    if (fullest == bins.end() ||
        static_cast<double>(fullest->second) < options.surfaceShare * static_cast<double>(cloud.size()))
        return std::nullopt;
    const double top = static_cast<double>(fullest->first + 1) * options.surfaceBin;
    const auto above =
        std::count_if(cloud.points.begin(), cloud.points.end(), [&](const auto& p) { return p.z > top; });
    if (static_cast<std::size_t>(above) < options.minPoints) return std::nullopt;
    return top;
}

double distance(const model::Vec3& a, const model::Vec3& b) {
    return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

}  // namespace

PointCloud thingInView(const ViewRegion& region, const RoomSurfaces& room, bool onSurface,
                       const ViewSegmentOptions& options) {
    PointCloud inside;
    std::vector<std::array<int, 2>> grid;
    for (std::size_t i = 0; i < region.points.size(); ++i) {
        const auto& p = region.points.points[i];
        if (onRoomSurface(p, room, options)) continue;
        inside.push(p, region.points.colors[i], region.points.frames.empty() ? 0 : region.points.frames[i]);
        grid.push_back(region.grid[i]);
    }
    if (inside.size() < options.minPoints) return {};
    if (onSurface)
        if (auto top = supportTop(inside, options)) {
            PointCloud above;
            std::vector<std::array<int, 2>> aboveGrid;
            for (std::size_t i = 0; i < inside.size(); ++i)
                if (inside.points[i].z > *top) {
                    above.push(inside.points[i], inside.colors[i], inside.frames[i]);
                    aboveGrid.push_back(grid[i]);
                }
            inside = std::move(above);
            grid = std::move(aboveGrid);
        }

    // Chains of near points, and of grid neighbours whose gap a surface seen at a grazing angle explains.
    UnionFind chains(inside.size());
    uniteNear(inside.points, options.tolerance, chains);
    std::unordered_map<std::int64_t, std::size_t> at;
    auto key = [](int column, int row) {
        return (static_cast<std::int64_t>(row) << 32) | static_cast<std::uint32_t>(column);
    };
    for (std::size_t i = 0; i < inside.size(); ++i) at.emplace(key(grid[i][0], grid[i][1]), i);
    const double reach = std::max(options.tolerance, options.pitchGaps * region.pitch);
    for (std::size_t i = 0; i < inside.size(); ++i)
        for (const auto& [dc, dr] : {std::array<int, 2>{1, 0}, {0, 1}, {1, 1}, {-1, 1}}) {
            auto it = at.find(key(grid[i][0] + dc, grid[i][1] + dr));
            if (it != at.end() && distance(inside.points[i], inside.points[it->second]) <= reach)
                chains.unite(i, it->second);
        }
    std::unordered_map<std::size_t, std::vector<std::size_t>> members;
    for (std::size_t i = 0; i < inside.size(); ++i) members[chains.find(i)].push_back(i);
    const std::vector<std::size_t>* largest = nullptr;
    for (const auto& [root, points] : members)
        if (!largest || points.size() > largest->size() ||
            (points.size() == largest->size() && points.front() < largest->front()))
            largest = &points;
    if (largest->size() < options.minPoints) return {};
    return subset(inside, *largest);
}

}  // namespace smql::ingest
