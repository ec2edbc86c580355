#include "ingest/geometry/colmap_database.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
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

Connection open(const std::string& path, int flags = SQLITE_OPEN_READONLY) {
    sqlite3* raw = nullptr;
    int opened = sqlite3_open_v2(path.c_str(), &raw, flags, nullptr);
    Connection db(raw, sqlite3_close);
    if (opened != SQLITE_OK)
        throw Error(ErrorKind::Input, fmt::format("{}: cannot open COLMAP's database: {}", path,
                                                  raw ? sqlite3_errmsg(raw) : "out of memory"));
    return db;
}

// Runs `sql` (no rows) on the database at `path`.
void exec(sqlite3* db, const std::string& path, const std::string& sql) {
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK)
        throw Error(ErrorKind::Storage, fmt::format("{}: {}", path, sqlite3_errmsg(db)));
}

// A text column, "" for NULL.
std::string columnText(sqlite3_stmt* row, int column) {
    const auto* text = sqlite3_column_text(row, column);
    return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

std::vector<ColmapDatabaseImage> readColmapImages(const std::string& path) {
    Connection db = open(path);
    std::vector<ColmapDatabaseImage> out;
    Statement images = prepare(db.get(), path, "SELECT image_id, camera_id, name FROM images ORDER BY image_id");
    while (sqlite3_step(images.get()) == SQLITE_ROW)
        out.push_back({sqlite3_column_int64(images.get(), 0), sqlite3_column_int64(images.get(), 1),
                       columnText(images.get(), 2)});
    return out;
}

std::vector<ColmapDescriptors> readColmapDescriptors(const std::string& path) {
    Connection db = open(path);
    std::vector<ColmapDescriptors> out;
    Statement rows = prepare(db.get(), path, "SELECT image_id, rows, cols, data FROM descriptors ORDER BY image_id");
    while (sqlite3_step(rows.get()) == SQLITE_ROW) {
        ColmapDescriptors d{sqlite3_column_int64(rows.get(), 0),
                            static_cast<std::size_t>(std::max<sqlite3_int64>(sqlite3_column_int64(rows.get(), 1), 0)),
                            {}};
        const auto bytes = static_cast<std::size_t>(sqlite3_column_bytes(rows.get(), 3));
        if (d.rows > 0 && (sqlite3_column_int(rows.get(), 2) != 128 || bytes != d.rows * 128))
            throw Error(ErrorKind::Input,
                        fmt::format("{}: image {}'s descriptors are not {} rows of 128 bytes", path, d.image, d.rows));
        const auto* blob = static_cast<const std::uint8_t*>(sqlite3_column_blob(rows.get(), 3));
        d.data.assign(blob, blob + bytes);
        out.push_back(std::move(d));
    }
    return out;
}

std::vector<ColmapPairMatches> readColmapMatches(const std::string& path) {
    Connection db = open(path);
    std::vector<ColmapPairMatches> out;
    Statement rows = prepare(db.get(), path, "SELECT pair_id, rows, cols, data FROM matches ORDER BY pair_id");
    while (sqlite3_step(rows.get()) == SQLITE_ROW) {
        const sqlite3_int64 id = sqlite3_column_int64(rows.get(), 0);
        ColmapPairMatches pair{id / kMaxImages, id % kMaxImages, {}};
        const auto count = static_cast<std::size_t>(std::max<sqlite3_int64>(sqlite3_column_int64(rows.get(), 1), 0));
        if (count > 0 && (sqlite3_column_int(rows.get(), 2) != 2 ||
                          static_cast<std::size_t>(sqlite3_column_bytes(rows.get(), 3)) != count * 8))
            throw Error(ErrorKind::Input, fmt::format("{}: the matches of images {} and {} are not {} pairs of indices",
                                                      path, pair.first, pair.second, count));
        const auto* data = static_cast<const std::uint32_t*>(sqlite3_column_blob(rows.get(), 3));
        for (std::size_t k = 0; k < count; ++k) pair.matches.emplace_back(data[2 * k], data[2 * k + 1]);
        out.push_back(std::move(pair));
    }
    return out;
}

std::vector<ColmapPairCount> readUnverifiedPairs(const std::string& path, std::size_t minMatches) {
    Connection db = open(path);
    std::vector<ColmapPairCount> out;
    Statement rows = prepare(db.get(), path,
                             "SELECT pair_id, rows FROM matches WHERE rows >= ?1 AND pair_id NOT IN "
                             "(SELECT pair_id FROM two_view_geometries) ORDER BY pair_id");
    sqlite3_bind_int64(rows.get(), 1, static_cast<sqlite3_int64>(minMatches));
    while (sqlite3_step(rows.get()) == SQLITE_ROW) {
        const sqlite3_int64 id = sqlite3_column_int64(rows.get(), 0);
        out.push_back(
            {id / kMaxImages, id % kMaxImages, static_cast<std::size_t>(sqlite3_column_int64(rows.get(), 1))});
    }
    return out;
}

void numberColmapImagesByName(const std::string& path) {
    Connection db = open(path, SQLITE_OPEN_READWRITE);
    auto count = [&](const char* sql) {
        Statement rows = prepare(db.get(), path, sql);
        return sqlite3_step(rows.get()) == SQLITE_ROW ? sqlite3_column_int64(rows.get(), 0) : 0;
    };
    if (count("SELECT count(*) FROM matches") + count("SELECT count(*) FROM two_view_geometries") > 0)
        throw Error(ErrorKind::Input, fmt::format("{}: its images cannot be numbered again once matched", path));
    if (count("SELECT count(*) FROM (SELECT image_id, row_number() OVER (ORDER BY name) AS n FROM images) "
              "WHERE image_id <> n") == 0)
        return;
    exec(db.get(), path, "BEGIN");
    // Moved out of the way first (COLMAP's ids stay under 2^31 - 1), so that no two rows share an id on the way.
    exec(db.get(), path,
         "CREATE TEMP TABLE numbered AS SELECT image_id + 1000000000 AS moved, row_number() OVER (ORDER BY name) AS "
         "number FROM images");
    for (const char* table : {"images", "keypoints", "descriptors"}) {
        exec(db.get(), path, fmt::format("UPDATE {0} SET image_id = image_id + 1000000000", table));
        exec(db.get(), path,
             fmt::format("UPDATE {0} SET image_id = (SELECT number FROM numbered WHERE moved = {0}.image_id)", table));
    }
    exec(db.get(), path, "DROP TABLE numbered");
    exec(db.get(), path, "COMMIT");
}

namespace {

// Whether VLFeat leaves the descriptor of a keypoint (COLMAP's x, y with its +0.5, and scale, in the pixels of
// a `width` x `height` image) unwritten in an octave it may have been found in. Its octave is not stored: its
// scale is sigma0 2^(o + s / S), the level s refined to within 1.5 of one of 0 .. S - 1 (vl_sift_detect), so
// each octave that scale allows is tried.
bool descriptorUnwritten(double x, double y, double scale, int width, int height, int octaveResolution) {
    const double resolution = octaveResolution, sigma0 = 1.6 * std::pow(2.0, 1.0 / resolution);
    const double octaves = std::log2(scale / sigma0);
    x -= 0.5;
    y -= 0.5;
    for (int o = -1; o < 16; ++o) {
        if (o <= octaves - (resolution + 0.5) / resolution || o >= octaves + 1.5 / resolution) continue;
        const double per = std::ldexp(1.0, o);
        const int w = o < 0 ? width * 2 : width >> o, h = o < 0 ? height * 2 : height >> o;
        const double xi = std::floor(x / per + 0.5), yi = std::floor(y / per + 0.5);
        if (xi < 0 || xi >= w || yi < 0 || yi >= h - 1) return true;
    }
    return false;
}

}  // namespace

std::size_t clearUnwrittenDescriptors(const std::string& path, int octaveResolution) {
    Connection db = open(path, SQLITE_OPEN_READWRITE);
    Statement rows =
        prepare(db.get(), path,
                "SELECT k.image_id, k.rows, k.cols, k.data, d.rows, d.data, c.width, c.height FROM keypoints "
                "k JOIN descriptors d USING (image_id) JOIN images i USING (image_id) JOIN cameras c "
                "USING (camera_id)");
    std::vector<std::pair<sqlite3_int64, std::vector<std::uint8_t>>> cleared;
    std::size_t count = 0;
    while (sqlite3_step(rows.get()) == SQLITE_ROW) {
        const auto keypoints =
            static_cast<std::size_t>(std::max<sqlite3_int64>(sqlite3_column_int64(rows.get(), 1), 0));
        const int columns = sqlite3_column_int(rows.get(), 2);
        // x, y, then a11 a12 a21 a22 (the scale the length of the first column) or scale and orientation.
        if (keypoints == 0 || (columns != 4 && columns != 6) ||
            static_cast<std::size_t>(sqlite3_column_int64(rows.get(), 4)) != keypoints ||
            static_cast<std::size_t>(sqlite3_column_bytes(rows.get(), 3)) != keypoints * columns * sizeof(float) ||
            static_cast<std::size_t>(sqlite3_column_bytes(rows.get(), 5)) != keypoints * 128)
            continue;
        const auto* k = static_cast<const float*>(sqlite3_column_blob(rows.get(), 3));
        const auto* d = static_cast<const std::uint8_t*>(sqlite3_column_blob(rows.get(), 5));
        const int width = sqlite3_column_int(rows.get(), 6), height = sqlite3_column_int(rows.get(), 7);
        std::vector<std::uint8_t> descriptors;
        for (std::size_t i = 0; i < keypoints; ++i) {
            const float* p = k + i * static_cast<std::size_t>(columns);
            const double scale = columns == 6 ? std::hypot(p[2], p[4]) : p[2];
            if (!descriptorUnwritten(p[0], p[1], scale, width, height, octaveResolution)) continue;
            if (descriptors.empty()) descriptors.assign(d, d + keypoints * 128);
            std::fill_n(descriptors.begin() + static_cast<std::ptrdiff_t>(i * 128), 128, std::uint8_t{0});
            ++count;
        }
        if (!descriptors.empty()) cleared.emplace_back(sqlite3_column_int64(rows.get(), 0), std::move(descriptors));
    }
    rows.reset();
    exec(db.get(), path, "BEGIN");
    Statement update = prepare(db.get(), path, "UPDATE descriptors SET data = ?2 WHERE image_id = ?1");
    for (const auto& [image, data] : cleared) {
        sqlite3_bind_int64(update.get(), 1, image);
        sqlite3_bind_blob(update.get(), 2, data.data(), static_cast<int>(data.size()), SQLITE_STATIC);
        if (sqlite3_step(update.get()) != SQLITE_DONE)
            throw Error(ErrorKind::Storage, fmt::format("{}: {}", path, sqlite3_errmsg(db.get())));
        sqlite3_reset(update.get());
    }
    exec(db.get(), path, "COMMIT");
    return count;
}

void writeColmapMatches(const std::string& path, const std::vector<ColmapPairMatches>& pairs) {
    Connection db = open(path, SQLITE_OPEN_READWRITE);
    exec(db.get(), path, "BEGIN");
    Statement insert =
        prepare(db.get(), path, "INSERT OR IGNORE INTO matches (pair_id, rows, cols, data) VALUES (?1, ?2, 2, ?3)");
    std::vector<std::uint32_t> data;
    for (const auto& pair : pairs) {
        // COLMAP keeps a pair under the smaller id first, its matches' columns in that order.
        const bool swapped = pair.first > pair.second;
        data.clear();
        for (const auto& [a, b] : pair.matches) {
            data.push_back(swapped ? b : a);
            data.push_back(swapped ? a : b);
        }
        const sqlite3_int64 low = std::min(pair.first, pair.second), high = std::max(pair.first, pair.second);
        sqlite3_bind_int64(insert.get(), 1, low * kMaxImages + high);
        sqlite3_bind_int64(insert.get(), 2, static_cast<sqlite3_int64>(pair.matches.size()));
        if (data.empty())
            sqlite3_bind_zeroblob(insert.get(), 3, 0);
        else
            sqlite3_bind_blob(insert.get(), 3, data.data(), static_cast<int>(data.size() * sizeof(std::uint32_t)),
                              SQLITE_TRANSIENT);
        if (sqlite3_step(insert.get()) != SQLITE_DONE)
            throw Error(ErrorKind::Storage, fmt::format("{}: {}", path, sqlite3_errmsg(db.get())));
        sqlite3_reset(insert.get());
    }
    exec(db.get(), path, "COMMIT");
}

ColmapDatabaseSummary readColmapDatabase(const std::string& path, int minMatches) {
    Connection db = open(path);
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

    // An image without a keypoints row had none written (COLMAP writes an empty one for a blank image).
    Statement named = prepare(db.get(), path,
                              "SELECT images.image_id, images.name, COALESCE(keypoints.rows, 0) FROM images "
                              "LEFT JOIN keypoints ON keypoints.image_id = images.image_id");
    std::map<sqlite3_int64, std::string> names;
    while (sqlite3_step(named.get()) == SQLITE_ROW) {
        const sqlite3_int64 id = sqlite3_column_int64(named.get(), 0);
        names[id] = columnText(named.get(), 1);
        if (sqlite3_column_int64(named.get(), 2) > 0)
            ++out.imagesWithFeatures;
        else
            out.featureless.insert(names[id]);
    }
    out.images = names.size();

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
    for (const auto& [image, up] : parent) {
        const sqlite3_int64 group = root(image);
        out.largestOverlapGroup = std::max(out.largestOverlapGroup, ++groups[group]);
        if (auto name = names.find(image); name != names.end()) out.overlapGroup[name->second] = group;
    }
    return out;
}

}  // namespace smql::ingest
