#include "ingest/geometry/colmap_database.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "model/error.hpp"

namespace smql::ingest {

namespace {

// COLMAP's camera models by id (src/base/camera_models.h).
constexpr const char* kModelNames[] = {"SIMPLE_PINHOLE",
                                       "PINHOLE",
                                       "SIMPLE_RADIAL",
                                       "RADIAL",
                                       "OPENCV",
                                       "OPENCV_FISHEYE",
                                       "FULL_OPENCV",
                                       "FOV",
                                       "SIMPLE_RADIAL_FISHEYE",
                                       "RADIAL_FISHEYE",
                                       "THIN_PRISM_FISHEYE"};
// Pairs are stored under one id: image_id1 * kMaxImages + image_id2 (COLMAP's Database::ImagePairToPairId).
constexpr sqlite3_int64 kMaxImages = 2147483647;

using Connection = std::unique_ptr<sqlite3, decltype(&sqlite3_close)>;
using Statement = std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)>;

Statement prepare(sqlite3* db, const std::string& path, const char* sql) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db, sql, -1, &statement, nullptr) != SQLITE_OK)
        throw Error(ErrorKind::Input, fmt::format("{}: not a COLMAP database ({})", path, sqlite3_errmsg(db)));
    return Statement(statement, sqlite3_finalize);
}

Connection openReadOnly(const std::string& path) {
    sqlite3* raw = nullptr;
    int opened = sqlite3_open_v2(path.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
    Connection db(raw, sqlite3_close);
    if (opened != SQLITE_OK)
        throw Error(ErrorKind::Input, fmt::format("{}: cannot open COLMAP's database: {}", path,
                                                  raw ? sqlite3_errmsg(raw) : "out of memory"));
    return db;
}

}  // namespace

std::vector<ColmapDatabaseImage> readColmapImages(const std::string& path) {
    Connection db = openReadOnly(path);
    std::vector<ColmapDatabaseImage> out;
    Statement images = prepare(db.get(), path, "SELECT image_id, camera_id, name FROM images ORDER BY image_id");
    while (sqlite3_step(images.get()) == SQLITE_ROW) {
        const auto* name = sqlite3_column_text(images.get(), 2);
        out.push_back({sqlite3_column_int64(images.get(), 0), sqlite3_column_int64(images.get(), 1),
                       name ? reinterpret_cast<const char*>(name) : ""});
    }
    return out;
}

ColmapDatabaseSummary readColmapDatabase(const std::string& path, int minMatches) {
    Connection db = openReadOnly(path);
    ColmapDatabaseSummary out;

    Statement cameras = prepare(db.get(), path, "SELECT model, width, height, params FROM cameras ORDER BY camera_id");
    while (sqlite3_step(cameras.get()) == SQLITE_ROW) {
        ColmapDatabaseSummary::Camera camera;
        int model = sqlite3_column_int(cameras.get(), 0);
        camera.model = model >= 0 && model < static_cast<int>(std::size(kModelNames)) ? kModelNames[model]
                                                                                      : fmt::format("model {}", model);
        camera.width = sqlite3_column_int(cameras.get(), 1);
        camera.height = sqlite3_column_int(cameras.get(), 2);
        const void* blob = sqlite3_column_blob(cameras.get(), 3);
        int bytes = sqlite3_column_bytes(cameras.get(), 3);
        camera.params.resize(static_cast<std::size_t>(bytes) / sizeof(double));
        if (blob && !camera.params.empty())
            std::memcpy(camera.params.data(), blob, camera.params.size() * sizeof(double));
        out.cameras.push_back(std::move(camera));
    }

    Statement images = prepare(db.get(), path, "SELECT COUNT(*) FROM images");
    if (sqlite3_step(images.get()) == SQLITE_ROW)
        out.images = static_cast<std::size_t>(sqlite3_column_int64(images.get(), 0));
    Statement keypoints = prepare(db.get(), path, "SELECT COUNT(*) FROM keypoints WHERE rows > 0");
    if (sqlite3_step(keypoints.get()) == SQLITE_ROW)
        out.imagesWithFeatures = static_cast<std::size_t>(sqlite3_column_int64(keypoints.get(), 0));

    // A pair overlaps when geometric verification kept enough inlier matches (config 0 is "undefined",
    // 1 "degenerate": the matcher found no valid geometry).
    Statement pairs =
        prepare(db.get(), path, "SELECT pair_id FROM two_view_geometries WHERE rows >= ?1 AND config >= 2");
    sqlite3_bind_int(pairs.get(), 1, minMatches);
    // Groups of images linked through overlapping pairs (union-find): one model can grow at most over one group.
    std::map<sqlite3_int64, sqlite3_int64> parent;
    auto root = [&](sqlite3_int64 image) {
        auto [it, added] = parent.emplace(image, image);
        while (it->second != image) {
            image = it->second;
            it = parent.find(image);
        }
        return image;
    };
    while (sqlite3_step(pairs.get()) == SQLITE_ROW) {
        sqlite3_int64 id = sqlite3_column_int64(pairs.get(), 0);
        sqlite3_int64 a = root(id / kMaxImages), b = root(id % kMaxImages);
        if (a != b) parent[a] = b;
        ++out.overlappingPairs;
    }
    out.overlappingImages = parent.size();
    std::map<sqlite3_int64, std::size_t> groups;
    for (const auto& [image, up] : parent)
        out.largestOverlapGroup = std::max(out.largestOverlapGroup, ++groups[root(image)]);
    return out;
}

}  // namespace smql::ingest
