#include "model/floor.hpp"

#include "model/geometry.hpp"

namespace smql::model {

const Node* labelledFloor(std::span<const Node> nodes) {
    const Node* floor = nullptr;
    for (const Node& n : nodes)
        if (!n.hidden && n.geometry != GeometryKind::None && n.category == "floor" &&
            (!floor || footprintArea(n.box) > footprintArea(floor->box)))
            floor = &n;
    return floor;
}

}  // namespace smql::model
