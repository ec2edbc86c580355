// A bed's headboard or a sofa's back that a detector named as a thing of its own (object_fusion.hpp:
// uprightEndOf) is told from the things that merely stand near the bed. The boxes are those a real
// Kinect frame gave (SUN RGB-D 000004, a bedroom display: the bed's frame and mattress, and its
// leather headboard called a "tv"), and their neighbours as a bedroom places them.
#include <catch2/catch.hpp>

#include <cmath>

#include "ingest/pipeline/object_fusion.hpp"

using namespace smql;
using namespace smql::ingest;

namespace {

model::Box box(model::Vec3 centre, model::Vec3 size, double yawDegrees) {
    model::Box b;
    b.center = centre;
    b.size = size;
    b.yaw = yawDegrees * M_PI / 180;
    return b;
}

}  // namespace

TEST_CASE("upright ends: a headboard named apart is the bed's; its neighbours are not", "[ingest][fusion]") {
    // The bed 1.77 m long along y (its box turned 86 degrees), 1.68 m wide; the headboard 1.52 m wide,
    // 0.45 m deep, rising 0.6 m above the mattress at the bed's far end.
    const model::Box bed = box({0.42, 2.80, 0.34}, {1.77, 1.68, 0.68}, 86);
    const model::Box headboard = box({0.26, 3.77, 0.95}, {1.52, 0.45, 0.68}, -1);
    CHECK(uprightEndOf(headboard, bed));
    // The same headboard turned a quarter (its box's sides given the other way round) is the same thing.
    CHECK(uprightEndOf(box({0.26, 3.77, 0.95}, {0.45, 1.52, 0.68}, 89), bed));
    // A footboard at the near end.
    CHECK(uprightEndOf(box({0.40, 1.90, 0.55}, {1.60, 0.10, 0.55}, 0), bed));

    // A nightstand beside the head: too narrow for the bed's end, and at its side.
    CHECK_FALSE(uprightEndOf(box({1.50, 3.40, 0.30}, {0.45, 0.40, 0.60}, 0), bed));
    // A picture on the wall above the headboard: it starts above the bed's top.
    CHECK_FALSE(uprightEndOf(box({0.30, 3.95, 1.60}, {1.00, 0.04, 0.60}, 0), bed));
    // A tv on a low stand 0.6 m past the bed's foot.
    CHECK_FALSE(uprightEndOf(box({0.40, 1.30, 0.80}, {1.20, 0.30, 0.75}, 0), bed));
    // A bench at the foot no higher than the mattress.
    CHECK_FALSE(uprightEndOf(box({0.40, 1.70, 0.25}, {1.40, 0.40, 0.50}, 0), bed));
    // A wardrobe beside the bed, as long as it and deep: not thin, and not at an end.
    CHECK_FALSE(uprightEndOf(box({1.70, 2.80, 1.00}, {0.60, 1.80, 2.00}, 0), bed));
    // A chair turned 45 degrees against the foot: not parallel to it.
    CHECK_FALSE(uprightEndOf(box({0.40, 1.80, 0.45}, {0.50, 0.50, 0.90}, 45), bed));
}
