#include "ingest/geometry/openings.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <opencv2/imgproc.hpp>

namespace smql::ingest {

model::Box WallOpening::box(const WallSegment& w) const {
    WallSegment part = w;
    part.along0 = along0, part.along1 = along1, part.z0 = z0, part.z1 = z1;
    return part.box();
}

namespace {

double alongOf(const WallSegment& w, const model::Vec3& p) {
    model::Vec3 d = w.direction();
    return d.x * p.x + d.y * p.y;
}

// Each cell of the wall (rows up from the floor, columns along it): the wall's own points in it, and
// the rays from cameras to points behind the wall that cross it.
struct WallCells {
    int columns = 0, rows = 0;
    cv::Mat1i surface, through;
};

WallCells countCells(const PointCloud& cloud, const std::unordered_map<std::uint32_t, model::Vec3>& cameras,
                     const WallSegment& wall, const OpeningOptions& options) {
    WallCells cells;
    cells.columns = std::max(1, static_cast<int>(std::ceil(wall.length() / options.cell)));
    cells.rows = std::max(1, static_cast<int>(std::ceil(wall.z1 / options.cell)));
    cells.surface = cv::Mat1i::zeros(cells.rows, cells.columns);
    cells.through = cv::Mat1i::zeros(cells.rows, cells.columns);
    auto cellOf = [&](double along, double z) -> std::optional<cv::Point> {
        if (along < wall.along0 || along >= wall.along1 || z < 0 || z >= wall.z1) return std::nullopt;
        return cv::Point(std::min(cells.columns - 1, static_cast<int>((along - wall.along0) / options.cell)),
                         std::min(cells.rows - 1, static_cast<int>(z / options.cell)));
    };
    const double onWall = std::max(wall.thickness, 0.05);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const model::Vec3& p = cloud.points[i];
        double s = wall.signedDistance(p);
        if (std::abs(s) <= onWall) {
            if (auto cell = cellOf(alongOf(wall, p), p.z)) ++cells.surface(*cell);
            continue;
        }
        if (s > -options.behindDistance) continue;
        auto camera = cameras.find(cloud.frames[i]);
        if (camera == cameras.end()) continue;
        const model::Vec3& c = camera->second;
        double sc = wall.signedDistance(c);
        if (sc <= 0) continue;  // a camera behind the wall sees nothing through it
        // Where the ray from the camera to the point crosses the wall's plane.
        double t = sc / (sc - s);
        model::Vec3 x{c.x + t * (p.x - c.x), c.y + t * (p.y - c.y), c.z + t * (p.z - c.z)};
        if (auto cell = cellOf(alongOf(wall, x), x.z)) ++cells.through(*cell);
    }
    return cells;
}

}  // namespace

std::vector<WallOpening> findOpenings(const PointCloud& aligned,
                                      const std::unordered_map<std::uint32_t, model::Vec3>& cameras,
                                      const std::vector<WallSegment>& walls, const OpeningOptions& options) {
    std::vector<WallOpening> openings;
    for (std::size_t w = 0; w < walls.size(); ++w) {
        const WallSegment& wall = walls[w];
        if (wall.length() <= 0 || wall.z1 <= 0) continue;
        WallCells cells = countCells(aligned, cameras, wall, options);
        cv::Mat1b open = cv::Mat1b::zeros(cells.rows, cells.columns);
        for (int r = 0; r < cells.rows; ++r)
            for (int c = 0; c < cells.columns; ++c) {
                int through = cells.through(r, c);
                open(r, c) = through >= options.minThrough && cells.surface(r, c) <= options.surfaceShare * through;
            }
        cv::Mat labels, stats, centroids;
        int count = cv::connectedComponentsWithStats(open, labels, stats, centroids, 8, CV_32S);
        for (int label = 1; label < count; ++label) {
            int x = stats.at<int>(label, cv::CC_STAT_LEFT), y = stats.at<int>(label, cv::CC_STAT_TOP);
            int width = stats.at<int>(label, cv::CC_STAT_WIDTH), height = stats.at<int>(label, cv::CC_STAT_HEIGHT);
            int area = stats.at<int>(label, cv::CC_STAT_AREA);
            if (area < options.minFill * width * height) continue;
            WallOpening o{w,
                          "",
                          wall.along0 + x * options.cell,
                          std::min(wall.along1, wall.along0 + (x + width) * options.cell),
                          y * options.cell,
                          std::min(wall.z1, (y + height) * options.cell),
                          0};
            // Below it, the wall itself unseen (furniture in front hides it): the opening may reach the floor.
            int below = 0, wallBelow = 0;
            for (int r = 0; r < y; ++r)
                for (int c = x; c < x + width; ++c) ++below, wallBelow += cells.surface(r, c) > 0;
            const bool hiddenBelow = below > 0 && wallBelow <= options.hiddenShare * below;
            const double across = o.along1 - o.along0, tall = o.z1 - o.z0;
            const bool fromFloor = o.z0 <= options.doorSill || (hiddenBelow && o.z1 >= options.doorHeight);
            if (fromFloor && o.z1 >= options.doorHeight && across >= options.doorWidth[0] &&
                across <= options.doorWidth[1]) {
                o.category = "door";
                o.z0 = 0;
            } else if (o.z0 >= options.windowSill[0] && o.z0 <= options.windowSill[1] && across >= options.windowSize &&
                       tall >= options.windowSize) {
                o.category = "window";
            } else {
                continue;
            }
            for (int r = y; r < y + height; ++r)
                for (int c = x; c < x + width; ++c)
                    if (labels.at<int>(r, c) == label) o.through += cells.through(r, c);
            openings.push_back(o);
        }
    }
    return openings;
}

}  // namespace smql::ingest
