#include "ingest/pipeline/observations.hpp"

#include <unordered_map>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace smql::ingest {

std::vector<Observation> observeInstances(const FrameImages& images, const Pose& pose, std::uint32_t frame,
                                          int stride, int minPixels) {
    std::vector<Observation> out;
    if (images.instances.empty()) return out;
    const auto& K = images.intrinsics;
    const auto& R = pose.rotation;
    const auto& t = pose.translation;

    // One sweep over the mask: areas, bounds and centroids of every instance.
    struct Extent {
        int pixels = 0;
        int x0 = INT32_MAX, y0 = INT32_MAX, x1 = -1, y1 = -1;
        double sumX = 0;
    };
    std::unordered_map<std::uint16_t, Extent> extents;
    for (int y = 0; y < images.instances.rows; ++y) {
        const auto* row = images.instances.ptr<std::uint16_t>(y);
        for (int x = 0; x < images.instances.cols; ++x) {
            if (!row[x]) continue;
            auto& e = extents[row[x]];
            ++e.pixels;
            e.sumX += x;
            e.x0 = std::min(e.x0, x), e.y0 = std::min(e.y0, y), e.x1 = std::max(e.x1, x), e.y1 = std::max(e.y1, y);
        }
    }
    std::unordered_map<std::uint16_t, std::size_t> slot;
    for (const auto& [id, e] : extents) {
        if (e.pixels < minPixels) continue;
        Observation o;
        o.frame = frame;
        o.instance = id;
        o.pixels = e.pixels;
        o.bounds = cv::Rect(e.x0, e.y0, e.x1 - e.x0 + 1, e.y1 - e.y0 + 1);
        o.centreX = e.sumX / e.pixels / images.instances.cols;
        slot.emplace(id, out.size());
        out.push_back(std::move(o));
    }

    std::vector<std::vector<cv::Vec3b>> samples(out.size());
    for (int y = 0; y < images.instances.rows; y += stride) {
        const auto* ids = images.instances.ptr<std::uint16_t>(y);
        const auto* bgr = images.color.ptr<cv::Vec3b>(y);
        const float* depth = images.depth.empty() ? nullptr : images.depth.ptr<float>(y);
        for (int x = 0; x < images.instances.cols; x += stride) {
            auto it = slot.find(ids[x]);
            if (it == slot.end()) continue;
            Observation& o = out[it->second];
            samples[it->second].push_back(bgr[x]);
            if (!depth || !(depth[x] > 0)) continue;
            double z = depth[x];
            double cx = (x - K.cx) / K.fx * z, cy = (y - K.cy) / K.fy * z;
            o.points.push_back({R[0] * cx + R[1] * cy + R[2] * z + t.x, R[3] * cx + R[4] * cy + R[5] * z + t.y,
                                R[6] * cx + R[7] * cy + R[8] * z + t.z});
        }
    }
    for (std::size_t i = 0; i < out.size(); ++i) cv::Mat(samples[i], true).copyTo(out[i].colors);
    return out;
}

std::string encodeCrop(const cv::Mat& color, const cv::Rect& bounds, int size) {
    int padX = bounds.width / 10, padY = bounds.height / 10;
    cv::Rect padded(bounds.x - padX, bounds.y - padY, bounds.width + 2 * padX, bounds.height + 2 * padY);
    padded &= cv::Rect(0, 0, color.cols, color.rows);
    cv::Mat crop = color(padded);
    double scale = double(size) / std::max(crop.cols, crop.rows);
    if (scale < 1) cv::resize(crop, crop, cv::Size(), scale, scale, cv::INTER_AREA);
    std::vector<std::uint8_t> bytes;
    cv::imencode(".jpg", crop, bytes, {cv::IMWRITE_JPEG_QUALITY, 85});
    return std::string(bytes.begin(), bytes.end());
}

}  // namespace smql::ingest
