#include "relations/viewer.hpp"

#include <cmath>
#include <limits>

namespace smql::relations {

std::optional<model::Viewpoint> lookingAt(const model::Vec3& origin, const model::Vec2& towards) {
    const double dx = towards.x - origin.x, dy = towards.y - origin.y;
    if (std::hypot(dx, dy) < 1e-6) return std::nullopt;
    return model::Viewpoint{{origin.x, origin.y, origin.z}, std::atan2(dy, dx)};
}

model::Vec2 middleOf(std::span<const model::Vec2> centres, const model::Vec3& origin) {
    if (centres.empty()) return {origin.x, origin.y + 1};
    double sx = 0, sy = 0;
    for (const auto& c : centres) sx += c.x, sy += c.y;
    const auto n = static_cast<double>(centres.size());
    return {sx / n, sy / n};
}

std::optional<std::size_t> farthestOnSide(const Frame& viewer, std::string_view side,
                                          std::span<const model::Vec2> centres) {
    std::optional<std::size_t> best;
    double bestScore = -std::numeric_limits<double>::infinity();
    bool bestInSector = false;
    for (std::size_t i = 0; i < centres.size(); ++i) {
        // The centre in the viewer's frame: `lateral` to the right, `depth` ahead.
        const double dx = centres[i].x - viewer.position.x, dy = centres[i].y - viewer.position.y;
        const double lateral = dx * viewer.right.x + dy * viewer.right.y;
        const double depth = dx * viewer.forward.x + dy * viewer.forward.y;
        const double along = side == "left" ? -lateral : side == "right" ? lateral : side == "front" ? depth : -depth;
        const double across = side == "left" || side == "right" ? depth : lateral;
        const bool inSector = along > 0 && along >= std::abs(across);
        if (!best || (inSector && !bestInSector) || (inSector == bestInSector && along > bestScore))
            best = i, bestScore = along, bestInSector = inSector;
    }
    if (!best || bestScore <= 0) return std::nullopt;
    return best;
}

}  // namespace smql::relations
