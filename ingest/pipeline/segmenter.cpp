#include "ingest/pipeline/segmenter.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <optional>

#include <fmt/format.h>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/geometry/typical_sizes.hpp"
#include "ingest/pipeline/network.hpp"
#include "model/error.hpp"

namespace smql::ingest {

namespace {

// The input the graph was converted at (scripts/detector/setup.sh, segmenter_size): a 640 x 480
// frame keeps its aspect.
const cv::Size kInput{513, 385};
constexpr const char* kLowResolution = "logits_lowres";

class DeepLabSegmenter : public SemanticSegmenter {
public:
    DeepLabSegmenter(const DetectorFiles& files, const GraphPlacement& placement)
        : file_(files.model.filename().string()), net_(loadNetwork(files.model, {kLowResolution}, placement)) {
        std::ifstream in(files.classes);
        if (!in) throw Error(ErrorKind::Input, fmt::format("{}: cannot read the class names", files.classes.string()));
        for (std::string line; std::getline(in, line);) {
            if (!line.empty() && line.back() == '\r') line.pop_back();
            if (!line.empty()) categories_.push_back(memoryCategory(line));
        }
    }

    cv::Mat1b segment(const cv::Mat& bgr) override {
        cv::Mat logits = net_->run(cv::dnn::blobFromImage(bgr, 1 / 127.5, kInput, cv::Scalar(127.5, 127.5, 127.5),
                                                          /*swapRB=*/true, /*crop=*/false))
                             .front();
        const int classes = logits.size[1], rows = logits.size[2], columns = logits.size[3];
        if (logits.dims != 4 || classes != static_cast<int>(categories_.size()))
            throw Error(ErrorKind::Input,
                        fmt::format("{}: its output is not {} class scores a pixel", file_, categories_.size()));
        // Each class's scores brought up to the frame's size, and the best class of every pixel (the first of
        // equal scores), in one pass a class: masks copied through would cost more than the model's last layers.
        cv::Mat1f best(bgr.size(), -1e30f);
        cv::Mat1b labels(bgr.size(), 0);
        cv::Mat1f scaled;
        for (int c = 0; c < classes; ++c) {
            cv::Mat plane(rows, columns, CV_32F, logits.ptr<float>(0, c));
            cv::resize(plane, scaled, bgr.size(), 0, 0, cv::INTER_LINEAR);
            for (int y = 0; y < labels.rows; ++y) {
                const float* score = scaled[y];
                float* top = best[y];
                std::uint8_t* label = labels[y];
                for (int x = 0; x < labels.cols; ++x)
                    if (score[x] > top[x]) {
                        top[x] = score[x];
                        label[x] = static_cast<std::uint8_t>(c);
                    }
            }
        }
        return labels;
    }

    const std::vector<std::string>& categories() const override { return categories_; }
    std::string describe() const override { return file_; }

private:
    std::string file_;
    std::unique_ptr<Network> net_;
    std::vector<std::string> categories_;
};

}  // namespace

std::unique_ptr<SemanticSegmenter> makeDeepLabSegmenter(const DetectorFiles& files, const GraphPlacement& placement) {
    return std::make_unique<DeepLabSegmenter>(files, placement);
}

namespace {

// The segmenter's label for the detection's kind, when it knows the kind.
std::optional<std::uint8_t> labelOf(const Detection& detection, const std::vector<std::string>& categories) {
    const std::string kind(kindName(detection.category));
    auto known = std::find(categories.begin(), categories.end(), kind);
    if (kind.empty() || known == categories.end()) return std::nullopt;
    return static_cast<std::uint8_t>(known - categories.begin());
}

}  // namespace

bool segmentable(const Detection& detection, const std::vector<std::string>& categories) {
    return labelOf(detection, categories).has_value();
}

void maskBySegments(Detection& detection, const cv::Mat1b& labels, const std::vector<std::string>& categories) {
    const std::optional<std::uint8_t> known = labelOf(detection, categories);
    if (!known) return;
    const std::uint8_t label = *known;
    const cv::Rect box = cv::Rect(cv::Point(static_cast<int>(std::floor(detection.box.x)),
                                            static_cast<int>(std::floor(detection.box.y))),
                                  cv::Point(static_cast<int>(std::ceil(detection.box.x + detection.box.width)),
                                            static_cast<int>(std::ceil(detection.box.y + detection.box.height)))) &
                         cv::Rect(0, 0, labels.cols, labels.rows);
    if (box.empty()) return;
    cv::Mat1b mask = cv::Mat1b::zeros(labels.size());
    mask(box) = labels(box) == label;
    if (cv::countNonZero(mask(box)) < kMinMaskShare * box.area()) return;
    detection.mask = std::move(mask);
}

}  // namespace smql::ingest
