#include "ingest/import/oriented_box.hpp"

#include <cmath>

#include "model/geometry.hpp"
namespace smql::import::detail {

model::Box uprightBox(const model::Vec3& center, const model::Vec3& sizes, const Eigen::Matrix3d& rotation) {
    model::Box box;
    box.center = center;
    if (rotation(2, 2) >= std::cos(kMaxTiltDegrees * model::kDegree)) {
        box.size = sizes;
        box.yaw = std::atan2(rotation(1, 0), rotation(0, 0));
    } else {
        Eigen::Vector3d extents = rotation.cwiseAbs() * Eigen::Vector3d(sizes.x, sizes.y, sizes.z);
        box.size = {extents.x(), extents.y(), extents.z()};
    }
    return box;
}

}  // namespace smql::import::detail
