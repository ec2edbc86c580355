#include "ingest/capture/detections.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "model/embedding.hpp"
#include "model/error.hpp"
#include "model/utf8.hpp"

namespace smql::ingest {

namespace fs = std::filesystem;

namespace {

constexpr const char* kHint =
    "detections.json is a JSON array (or {\"detections\": [...]}) of {\"image\": \"12.png\" or \"image_id\": 12, "
    "\"label\": \"mug\", \"score\": 0.87, \"bbox\": [x, y, w, h], optional \"segmentation\": [[x1, y1, x2, y2, ...]]}";

// The frame number in a colour file's name ("0007.jpg" = 7), as the readers number frames.
std::optional<long long> numberOf(const fs::path& file) {
    std::string stem = file.stem().string();
    if (stem.empty() || stem.size() > 15 ||
        !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return std::nullopt;
    return std::stoll(stem);
}

}  // namespace

namespace {

// COCO run-length masks: {"size": [height, width], "counts": [...] or "..."}. Runs alternate
// background and object, starting with background, over the pixels in column-major order; the string
// form packs each run in 5-bit groups (6 bits a character from '0'), after the second run as the
// difference from the run two before (pycocotools' rleFrString).
cv::Mat1b decodeRle(const nlohmann::json& s, const Intrinsics& K, const std::function<void(const std::string&)>& bad) {
    if (!s.contains("size") || !s["size"].is_array() || s["size"].size() != 2 || !s["size"][0].is_number_integer() ||
        !s["size"][1].is_number_integer())
        bad("RLE mask: expected \"size\": [height, width]");
    long long height = s["size"][0].get<long long>(), width = s["size"][1].get<long long>();
    if (height != K.height || width != K.width)
        bad(fmt::format("RLE mask of {}x{} for a {}x{} image", width, height, K.width, K.height));
    std::vector<long long> runs;
    if (!s.contains("counts")) bad("RLE mask: missing \"counts\"");
    const auto& counts = s["counts"];
    if (counts.is_array()) {
        for (const auto& c : counts) {
            if (!c.is_number_integer() || c.get<long long>() < 0) bad("RLE mask: counts must be whole numbers >= 0");
            runs.push_back(c.get<long long>());
        }
    } else if (counts.is_string()) {
        const std::string text = counts.get<std::string>();
        for (std::size_t p = 0; p < text.size();) {
            long long x = 0;
            int k = 0;
            bool more = true;
            while (more) {
                if (p >= text.size()) bad("RLE mask: counts string is truncated");
                // A run never exceeds the pixel count (< 2^34 for the largest images the readers
                // accept), which 7 groups hold with its sign; more would also shift past 64 bits.
                if (k == 7) bad("RLE mask: a run in the counts string is longer than any image");
                int c = text[p++] - 48;
                if (c < 0 || c > 63) bad("RLE mask: counts string holds a character outside '0'..'o'");
                x |= static_cast<long long>(c & 0x1f) << (5 * k);
                more = c & 0x20;
                ++k;
                if (!more && (c & 0x10)) x |= -1LL << (5 * k);
            }
            if (runs.size() > 2) x += runs[runs.size() - 2];
            runs.push_back(x);
        }
    } else {
        bad("RLE mask: counts must be a list of numbers or a string");
    }
    cv::Mat1b mask = cv::Mat1b::zeros(static_cast<int>(height), static_cast<int>(width));
    long long at = 0, total = height * width;
    for (std::size_t r = 0; r < runs.size(); ++r) {
        if (runs[r] < 0 || at + runs[r] > total) bad("RLE mask: the runs do not add up to the image's size");
        if (r % 2 == 1)
            for (long long q = at; q < at + runs[r]; ++q)
                mask(static_cast<int>(q % height), static_cast<int>(q / height)) = 255;
        at += runs[r];
    }
    if (at != total) bad(fmt::format("RLE mask: the runs cover {} pixels, the image has {}", at, total));
    return mask;
}

// What a malformed field says: detections[i].FIELD: WHAT (it throws).
using Complaint = std::function<void(const std::string& field, const std::string& what)>;

// bbox: [x, y, w, h] in pixels, within the frame's image (half a pixel of slack: detectors round
// box edges to the image border either way).
cv::Rect2d readBox(const nlohmann::json& e, const Intrinsics& K, const Complaint& bad) {
    if (!e.contains("bbox")) bad("bbox", "missing");
    const auto& b = e["bbox"];
    if (!b.is_array() || b.size() != 4 || !std::all_of(b.begin(), b.end(), [](const auto& v) { return v.is_number(); }))
        bad("bbox", "expected [x, y, w, h] (4 numbers)");
    double x = b[0].get<double>(), y = b[1].get<double>(), w = b[2].get<double>(), h = b[3].get<double>();
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(w) || !std::isfinite(h)) bad("bbox", "not finite");
    if (w <= 0 || h <= 0) bad("bbox", "width and height must be positive");
    if (x < -0.5 || y < -0.5 || x + w > K.width + 0.5 || y + h > K.height + 0.5)
        bad("bbox", fmt::format("[{}, {}, {}, {}] lies outside the {}x{} image", x, y, w, h, K.width, K.height));
    return cv::Rect2d(x, y, w, h);
}

// embedding: finite single-precision numbers.
std::vector<float> readEmbedding(const nlohmann::json& v, const Complaint& bad) {
    if (!v.is_array() || !std::all_of(v.begin(), v.end(), [](const auto& x) { return x.is_number(); }))
        bad("embedding", "expected a list of numbers");
    std::vector<float> out;
    for (const auto& x : v) {
        // Beyond float's range a value cannot be stored (and converting it is undefined).
        const double value = x.get<double>();
        if (!(std::abs(value) <= std::numeric_limits<float>::max()))
            bad("embedding", fmt::format("value {} ({}) is not a finite single-precision number", out.size(), value));
        out.push_back(static_cast<float>(value));
    }
    if (auto problem = model::embeddingProblem(out)) bad("embedding", *problem);
    return out;
}

// segmentation as polygons: [[x1, y1, x2, y2, ...], ...] in pixels, within the image.
std::vector<std::vector<cv::Point2d>> readPolygons(const nlohmann::json& s, const Intrinsics& K, const Complaint& bad) {
    if (!s.is_array()) bad("segmentation", "expected a list of polygons [[x1, y1, x2, y2, ...], ...] or an RLE mask");
    std::vector<std::vector<cv::Point2d>> out;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const auto& poly = s[k];
        std::string field = fmt::format("segmentation[{}]", k);
        if (!poly.is_array() || poly.size() < 6 || poly.size() % 2)
            bad(field, "expected a polygon of at least 3 points: [x1, y1, x2, y2, x3, y3, ...]");
        std::vector<cv::Point2d> points;
        for (std::size_t p = 0; p < poly.size(); p += 2) {
            if (!poly[p].is_number() || !poly[p + 1].is_number()) bad(field, "expected numbers");
            double px = poly[p].get<double>(), py = poly[p + 1].get<double>();
            if (!std::isfinite(px) || !std::isfinite(py)) bad(field, "not finite");
            if (px < -0.5 || py < -0.5 || px > K.width + 0.5 || py > K.height + 0.5)
                bad(field, fmt::format("point ({}, {}) lies outside the {}x{} image", px, py, K.width, K.height));
            points.emplace_back(px, py);
        }
        out.push_back(std::move(points));
    }
    return out;
}

}  // namespace

std::vector<std::vector<Detection>> readDetections(const Capture& capture) {
    const std::string& path = capture.detectionsPath;
    auto fail = [&](const std::string& what) {
        throw Error(ErrorKind::Input, fmt::format("{}: {}", path, what), std::nullopt, kHint);
    };
    std::ifstream in(path);
    if (!in) fail("cannot read the file");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        fail(fmt::format("not valid JSON ({})", model::escapeInvalidUtf8(e.what())));  // it quotes the file's bytes
    }
    if (j.is_object() && j.contains("detections")) j = j["detections"];
    if (!j.is_array()) fail("detections: expected an array");

    std::map<std::string, std::size_t> byName;
    std::map<long long, std::size_t> byNumber;
    for (std::size_t f = 0; f < capture.frames.size(); ++f) {
        fs::path file(capture.frames[f].colorPath);
        byName.emplace(file.filename().string(), f);
        if (auto n = numberOf(file)) byNumber.emplace(*n, f);
    }

    std::vector<std::vector<Detection>> out(capture.frames.size());
    std::optional<std::size_t> firstEmbedding;  // the first entry with one: every other has its length
    for (std::size_t i = 0; i < j.size(); ++i) {
        const auto& e = j[i];
        auto bad = [&](const std::string& field, const std::string& what) {
            fail(fmt::format("detections[{}].{}: {}", i, field, what));
        };
        if (!e.is_object()) fail(fmt::format("detections[{}]: expected an object", i));

        std::size_t frame = 0;
        if (e.contains("image")) {
            if (!e["image"].is_string()) bad("image", "expected a file name (string)");
            auto name = fs::path(e["image"].get<std::string>()).filename().string();
            auto it = byName.find(name);
            if (it == byName.end()) bad("image", fmt::format("'{}' is not a frame of the capture", name));
            frame = it->second;
        } else if (e.contains("image_id")) {
            if (!e["image_id"].is_number_integer()) bad("image_id", "expected a frame number (integer)");
            auto id = e["image_id"].get<long long>();
            auto it = byNumber.find(id);
            if (it == byNumber.end()) bad("image_id", fmt::format("{} is not a frame number of the capture", id));
            frame = it->second;
        } else {
            bad("image", "missing (give \"image\": the colour file name, or \"image_id\": the frame number)");
        }

        Detection d;
        const char* labelKey = e.contains("label") ? "label" : "category";
        if (!e.contains(labelKey)) bad("label", "missing (give \"label\" or \"category\")");
        if (!e[labelKey].is_string() || e[labelKey].get<std::string>().empty())
            bad(labelKey, "expected a non-empty string");
        d.category = e[labelKey].get<std::string>();

        if (!e.contains("score")) bad("score", "missing");
        if (!e["score"].is_number()) bad("score", "expected a number");
        d.score = e["score"].get<double>();
        if (!std::isfinite(d.score)) bad("score", "not finite");

        const Intrinsics& K = capture.frames[frame].intrinsics ? *capture.frames[frame].intrinsics : capture.intrinsics;
        d.box = readBox(e, K, bad);
        if (e.contains("embedding") && !e["embedding"].is_null()) {
            d.embedding = readEmbedding(e["embedding"], bad);
            if (!firstEmbedding) firstEmbedding = i;
            const std::size_t length = j[*firstEmbedding]["embedding"].size();
            if (d.embedding.size() != length)
                bad("embedding", fmt::format("{} numbers, detections[{}].embedding has {}: the embeddings of one file "
                                             "come from one model",
                                             d.embedding.size(), *firstEmbedding, length));
        }

        if (e.contains("segmentation") && !e["segmentation"].is_null()) {
            const auto& s = e["segmentation"];
            if (s.is_object())
                d.mask = decodeRle(s, K, [&](const std::string& what) { bad("segmentation", what); });
            else
                d.polygons = readPolygons(s, K, bad);
        }
        out[frame].push_back(std::move(d));
    }
    return out;
}

namespace {

// Pixel centres sit at integer coordinates, so scaling maps centre to centre.
cv::Point2d toWorking(cv::Point2d p, double scale) { return {(p.x + 0.5) * scale - 0.5, (p.y + 0.5) * scale - 0.5}; }

// Paints the detection's mask (its RLE mask, else its polygons, else its box), scaled from the stored
// image by `scale`, into `mask` with `value`.
void drawDetection(const Detection& det, double scale, cv::Mat& mask, int value) {
    constexpr int kShift = 3;  // fillPoly's sub-pixel bits: keeps small polygons' shapes at low resolution
    auto fixed = [&](cv::Point2d p) {
        p = toWorking(p, scale);
        return cv::Point(static_cast<int>(std::lround(p.x * (1 << kShift))),
                         static_cast<int>(std::lround(p.y * (1 << kShift))));
    };
    if (!det.mask.empty()) {
        cv::Mat1b resized;
        cv::resize(det.mask, resized, mask.size(), 0, 0, cv::INTER_NEAREST);
        mask.setTo(value, resized);
        return;
    }
    std::vector<std::vector<cv::Point>> polys;
    for (const auto& poly : det.polygons) {
        polys.emplace_back();
        for (const auto& p : poly) polys.back().push_back(fixed(p));
    }
    if (polys.empty()) {
        // The box [x, y, w, h] covers the pixels whose centres lie in x .. x + w - 1.
        cv::Point2d a(det.box.x, det.box.y), b(det.box.x + det.box.width - 1, det.box.y + det.box.height - 1);
        polys.push_back({fixed(a), fixed({b.x, a.y}), fixed(b), fixed({a.x, b.y})});
    }
    cv::fillPoly(mask, polys, cv::Scalar(value), cv::LINE_8, kShift);
}

double workingScale(const Intrinsics& K, int storedWidth) {
    return storedWidth > 0 ? double(K.width) / storedWidth : 1.0;
}

}  // namespace

cv::Rect detectionBounds(const Detection& detection, const Intrinsics& K, int storedWidth) {
    const double scale = workingScale(K, storedWidth);
    const cv::Rect2d& b = detection.box;
    const cv::Point first(static_cast<int>(std::floor(b.x * scale)), static_cast<int>(std::floor(b.y * scale)));
    const cv::Point end(static_cast<int>(std::ceil((b.x + b.width) * scale)),
                        static_cast<int>(std::ceil((b.y + b.height) * scale)));
    return cv::Rect(first, end) & cv::Rect(0, 0, K.width, K.height);
}

cv::Mat1b detectionOutline(const Detection& detection, const Intrinsics& K, int storedWidth) {
    if (detection.polygons.empty() && detection.mask.empty()) return {};
    cv::Mat1b whole = cv::Mat1b::zeros(K.height, K.width);
    drawDetection(detection, workingScale(K, storedWidth), whole, 255);
    return whole(detectionBounds(detection, K, storedWidth)).clone();
}

cv::Mat detectionInstances(const Intrinsics& K, const std::vector<Detection>& detections, int storedWidth) {
    std::vector<std::size_t> order;
    for (std::size_t d = 0; d < detections.size() && d + 1 < 65536; ++d)
        if (detections[d].score >= kMinDetectionScore) order.push_back(d);
    // The larger first, so a smaller thing in front (a mug on a table) keeps its pixels.
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return detections[a].box.area() > detections[b].box.area(); });
    cv::Mat instances = cv::Mat::zeros(K.height, K.width, CV_16U);
    double scale = workingScale(K, storedWidth);
    for (auto d : order) drawDetection(detections[d], scale, instances, static_cast<int>(d + 1));
    return instances;
}

std::vector<Observation> observeDetections(const FrameImages& images, const Pose& pose, std::uint32_t frame,
                                           const std::vector<Detection>& detections, int storedWidth, int stride,
                                           int minPixels) {
    std::vector<Observation> out;
    if (images.depth.empty()) return out;
    const auto& K = images.intrinsics;
    const auto& R = pose.rotation;
    const auto& t = pose.translation;
    // Detections are in stored-image pixels; frames are loaded at the working resolution.
    const double scale = workingScale(K, storedWidth);

    // Each detection's mask, its area, and the median depth inside it: most of a good mask is on
    // the thing.
    struct Candidate {
        std::size_t detection = 0;
        cv::Mat1b mask;
        int area = 0;
        double median = 0;
        int regionStride = 1;
    };
    std::vector<Candidate> candidates;
    for (std::size_t d = 0; d < detections.size() && d + 1 < 65536; ++d) {
        if (detections[d].score < kMinDetectionScore) continue;
        Candidate c{d, cv::Mat1b::zeros(images.depth.size())};
        drawDetection(detections[d], scale, c.mask, 255);
        c.area = cv::countNonZero(c.mask);
        if (c.area < minPixels) continue;
        std::vector<float> depths;
        for (int y = 0; y < c.mask.rows; ++y) {
            const auto* m = c.mask.ptr<std::uint8_t>(y);
            const float* z = images.depth.ptr<float>(y);
            for (int x = 0; x < c.mask.cols; ++x)
                if (m[x] && z[x] > 0) depths.push_back(z[x]);
        }
        if (depths.empty()) continue;
        auto mid = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
        std::nth_element(depths.begin(), mid, depths.end());
        c.median = *mid;
        c.regionStride = std::max(stride, static_cast<int>(std::ceil(std::sqrt(double(c.area) / kRegionPoints))));
        candidates.push_back(std::move(c));
    }
    // The smaller first: a pixel in several masks belongs to the smallest that it is not behind.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.area < b.area; });

    struct Gathered {
        int kept = 0, x0 = INT32_MAX, y0 = INT32_MAX, x1 = -1, y1 = -1;
        double sumX = 0;
        std::vector<cv::Vec3b> samples;
    };
    std::vector<Gathered> gathered(candidates.size());
    out.resize(candidates.size());
    for (int y = 0; y < images.depth.rows; ++y) {
        const float* z = images.depth.ptr<float>(y);
        const auto* bgr = images.color.ptr<cv::Vec3b>(y);
        for (int x = 0; x < images.depth.cols; ++x) {
            if (!(z[x] > 0)) continue;
            std::size_t owner = candidates.size();
            for (std::size_t c = 0; c < candidates.size(); ++c) {
                if (!candidates[c].mask(y, x)) continue;
                owner = c;
                if (z[x] <= candidates[c].median + kOwnedBehind) break;
            }
            if (owner == candidates.size()) continue;
            const Candidate& c = candidates[owner];
            Observation& o = out[owner];
            const double zz = z[x];
            const double cx = (x - K.cx) / K.fx * zz, cy = (y - K.cy) / K.fy * zz;
            const model::Vec3 world{R[0] * cx + R[1] * cy + R[2] * zz + t.x, R[3] * cx + R[4] * cy + R[5] * zz + t.y,
                                    R[6] * cx + R[7] * cy + R[8] * zz + t.z};
            if (y % c.regionStride == 0 && x % c.regionStride == 0)
                o.region.push_back({static_cast<float>(world.x), static_cast<float>(world.y),
                                    static_cast<float>(world.z), bgr[x], static_cast<std::uint16_t>(x / c.regionStride),
                                    static_cast<std::uint16_t>(y / c.regionStride)});
            if (std::abs(zz - c.median) > kDetectionDepthBand) continue;
            Gathered& g = gathered[owner];
            ++g.kept;
            g.sumX += x;
            g.x0 = std::min(g.x0, x), g.y0 = std::min(g.y0, y), g.x1 = std::max(g.x1, x), g.y1 = std::max(g.y1, y);
            if (y % stride || x % stride) continue;
            g.samples.push_back(bgr[x]);
            o.points.push_back(world);
        }
    }
    std::vector<Observation> kept;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
        Observation& o = out[c];
        const Gathered& g = gathered[c];
        if (g.kept < minPixels || o.points.empty()) continue;
        const Detection& detection = detections[candidates[c].detection];
        o.frame = frame;
        o.instance = static_cast<std::uint16_t>(candidates[c].detection + 1);
        o.pixels = g.kept;
        o.bounds = cv::Rect(g.x0, g.y0, g.x1 - g.x0 + 1, g.y1 - g.y0 + 1);
        o.centreX = g.sumX / g.kept / images.depth.cols;
        o.label = detection.category;
        o.score = detection.score;
        o.alsoSeenAs = detection.alsoSeenAs;
        o.regionPitch = candidates[c].regionStride * candidates[c].median / K.fx;
        cv::Mat(g.samples, true).copyTo(o.colors);
        kept.push_back(std::move(o));
    }
    // In the detections' order, as before ownership sorted them.
    std::sort(kept.begin(), kept.end(),
              [](const Observation& a, const Observation& b) { return a.instance < b.instance; });
    return kept;
}

namespace {

// Padded volume of axis-aligned bounds. Bounds are padded by 2 cm: a surface seen face-on (a window, a
// table top) has no thickness, and boxes without volume would never overlap.
double paddedVolume(const model::Vec3& lo, const model::Vec3& hi) {
    constexpr double kPad = 0.02;
    return std::max(0.0, hi.x - lo.x + 2 * kPad) * std::max(0.0, hi.y - lo.y + 2 * kPad) *
           std::max(0.0, hi.z - lo.z + 2 * kPad);
}

}  // namespace

// How well `b` fits the track `a` (IoU, then centroid distance); nullopt when the rule rejects it.
std::optional<std::pair<double, double>> DetectionTracker::fit(const Extent& a, const Extent& b) {
    auto centroid = [](const Extent& e) {
        double n = std::max<std::size_t>(e.count, 1);
        return model::Vec3{e.sum.x / n, e.sum.y / n, e.sum.z / n};
    };
    model::Vec3 lo{std::max(a.lo.x, b.lo.x), std::max(a.lo.y, b.lo.y), std::max(a.lo.z, b.lo.z)};
    model::Vec3 hi{std::min(a.hi.x, b.hi.x), std::min(a.hi.y, b.hi.y), std::min(a.hi.z, b.hi.z)};
    double inter = paddedVolume(lo, hi);
    double va = paddedVolume(a.lo, a.hi), vb = paddedVolume(b.lo, b.hi);
    double iou = inter / (va + vb - inter);
    // A partial view of a large thing (the end of a sofa) overlaps little of its bounds but lies inside them.
    double inside = inter / std::min(va, vb);
    model::Vec3 ca = centroid(a), cb = centroid(b);
    double distance =
        std::sqrt((ca.x - cb.x) * (ca.x - cb.x) + (ca.y - cb.y) * (ca.y - cb.y) + (ca.z - cb.z) * (ca.z - cb.z));
    // The larger of the two extents: a track started by a sliver (a seat seen edge-on) must still take
    // the full view that comes next.
    double extent = std::max(
        {a.hi.x - a.lo.x, a.hi.y - a.lo.y, a.hi.z - a.lo.z, b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z});
    if (iou < 0.1 && inside < 0.5 && distance > std::max(0.3, extent / 2)) return std::nullopt;
    return std::make_pair(iou, distance);
}

void DetectionTracker::merge(Extent& into, const Extent& from) {
    into.lo = {std::min(into.lo.x, from.lo.x), std::min(into.lo.y, from.lo.y), std::min(into.lo.z, from.lo.z)};
    into.hi = {std::max(into.hi.x, from.hi.x), std::max(into.hi.y, from.hi.y), std::max(into.hi.z, from.hi.z)};
    into.sum = {into.sum.x + from.sum.x, into.sum.y + from.sum.y, into.sum.z + from.sum.z};
    into.count += from.count;
    into.frames.insert(from.frames.begin(), from.frames.end());
    for (const auto& [category, score] : from.votes) into.votes[category] += score;
}

void DetectionTracker::relabel(ObjectTrack& track, const Extent& extent) {
    auto best = std::max_element(extent.votes.begin(), extent.votes.end(),
                                 [](const auto& a, const auto& b) { return a.second < b.second; });
    if (best != extent.votes.end()) track.category = best->first;
}

std::vector<ObjectTrack> DetectionTracker::take() {
    // Greedy association depends on the order views come in: a track started by a sliver may miss views
    // that came before it grew. Tracks of one category that the rule joins, and that never share a
    // frame, are one thing: merge them until nothing changes.
    std::vector<bool> gone(tracks_.size(), false);
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t a = 0; a < tracks_.size(); ++a)
            for (std::size_t b = a + 1; b < tracks_.size() && !gone[a]; ++b) {
                if (gone[b] || tracks_[a].category != tracks_[b].category) continue;
                const auto& fa = extents_[a].frames;
                if (std::any_of(extents_[b].frames.begin(), extents_[b].frames.end(),
                                [&](auto f) { return fa.contains(f); }))
                    continue;
                if (!fit(extents_[a], extents_[b])) continue;
                merge(extents_[a], extents_[b]);
                relabel(tracks_[a], extents_[a]);
                auto& views = tracks_[a].views;
                for (auto& v : tracks_[b].views) views.push_back(std::move(v));
                std::stable_sort(views.begin(), views.end(),
                                 [](const auto& x, const auto& y) { return x.frame < y.frame; });
                if (tracks_[b].evidence.pixels > tracks_[a].evidence.pixels)
                    tracks_[a].evidence = std::move(tracks_[b].evidence);
                gone[b] = true;
                changed = true;
            }
    }
    std::vector<ObjectTrack> out;
    for (std::size_t k = 0; k < tracks_.size(); ++k)
        if (!gone[k]) out.push_back(std::move(tracks_[k]));
    tracks_.clear();
    extents_.clear();
    return out;
}

bool isOpening(const std::string& category) { return category == "door" || category == "window"; }

model::NodeKind detectionKind(const std::string& category) {
    return category == "wall" || category == "floor" || category == "ceiling" || isOpening(category)
               ? model::NodeKind::Anchor
               : model::NodeKind::Object;
}

ObjectTrack& DetectionTracker::add(Observation observation, const std::string& category, double score) {
    Extent mine;
    for (const auto& p : observation.points) {
        mine.lo = {std::min(mine.lo.x, p.x), std::min(mine.lo.y, p.y), std::min(mine.lo.z, p.z)};
        mine.hi = {std::max(mine.hi.x, p.x), std::max(mine.hi.y, p.y), std::max(mine.hi.z, p.z)};
        mine.sum = {mine.sum.x + p.x, mine.sum.y + p.y, mine.sum.z + p.z};
    }
    mine.count = observation.points.size();
    mine.frames.insert(observation.frame);
    mine.votes[category] = score;

    // The best candidate: the largest overlap, then the nearest centroid.
    std::size_t best = tracks_.size();
    double bestIou = -1, bestDistance = 1e18;
    for (std::size_t k = 0; k < tracks_.size(); ++k) {
        // Two detections of one frame are two things (detectors suppress duplicates).
        if (extents_[k].frames.contains(observation.frame)) continue;
        bool sameCategory = tracks_[k].category == category;
        if (!sameCategory && !voteLabels_) continue;
        auto f = fit(extents_[k], mine);
        // Another label joins only a track it overlaps closely: the same thing, named differently.
        if (!f || (!sameCategory && f->first < kRelabelIou)) continue;
        auto [iou, distance] = *f;
        if (iou > bestIou + 1e-9 || (std::abs(iou - bestIou) <= 1e-9 && distance < bestDistance))
            best = k, bestIou = iou, bestDistance = distance;
    }
    if (best == tracks_.size()) {
        ObjectTrack track;
        track.category = category;
        track.kind = detectionKind(category);
        tracks_.push_back(std::move(track));
        extents_.emplace_back();
    }
    merge(extents_[best], mine);
    relabel(tracks_[best], extents_[best]);
    tracks_[best].views.push_back(std::move(observation));
    return tracks_[best];
}

}  // namespace smql::ingest
