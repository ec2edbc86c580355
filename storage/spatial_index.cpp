#include "storage/spatial_index.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/iterator/function_output_iterator.hpp>

namespace smql::storage {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {
using Point = bg::model::point<double, 3, bg::cs::cartesian>;
using Bounds = bg::model::box<Point>;
using Value = std::pair<Bounds, std::uint32_t>;

Bounds toBounds(const model::Aabb& a) {
    return Bounds(Point(a.min.x, a.min.y, a.min.z), Point(a.max.x, a.max.y, a.max.z));
}
}  // namespace

struct SpatialIndex::Tree {
    bgi::rtree<Value, bgi::rstar<16>> rtree;
};

SpatialIndex::SpatialIndex() : tree_(std::make_unique<Tree>()) {}

SpatialIndex::SpatialIndex(const std::vector<Entry>& entries) {
    std::vector<Value> values;
    values.reserve(entries.size());
    for (const auto& e : entries) values.emplace_back(toBounds(e.bounds), e.slot);
    // The range constructor packs the tree (STR bulk loading): better queries than inserting one by one.
    tree_ = std::make_unique<Tree>(Tree{bgi::rtree<Value, bgi::rstar<16>>(values)});
}

SpatialIndex::SpatialIndex(SpatialIndex&&) noexcept = default;
SpatialIndex& SpatialIndex::operator=(SpatialIndex&&) noexcept = default;
SpatialIndex::~SpatialIndex() = default;

void SpatialIndex::intersecting(const model::Aabb& region, std::vector<std::uint32_t>& out) const {
    tree_->rtree.query(bgi::intersects(toBounds(region)),
                       boost::make_function_output_iterator([&](const Value& v) { out.push_back(v.second); }));
}

}  // namespace smql::storage
