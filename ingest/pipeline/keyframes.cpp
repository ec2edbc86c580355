#include "ingest/pipeline/keyframes.hpp"

#include <algorithm>
#include <cmath>

#include "model/geometry.hpp"
namespace smql::ingest {

bool Keyframes::take(const Pose& pose) {
    if (last_) {
        const auto& a = last_->translation;
        const auto& b = pose.translation;
        const double moved =
            std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
        // The cameras' view directions: the third column of each rotation (the camera looks along +z).
        const auto& r = last_->rotation;
        const auto& s = pose.rotation;
        const double cosine = std::clamp(r[2] * s[2] + r[5] * s[5] + r[8] * s[8], -1.0, 1.0);
        const double turned = std::acos(cosine) / model::kDegree;
        if (moved < rule_.move && turned < rule_.turn) return false;
    }
    last_ = pose;
    return true;
}

}  // namespace smql::ingest
