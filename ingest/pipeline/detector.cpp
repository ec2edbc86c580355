// NanoDet through OpenCV's DNN module (docs/ingest.md "Detector"). The graph
// (scripts/detector/tfjs_to_onnx.py) takes a 1x3x416x416 BGR image
// normalised by NanoDet's mean and deviation, and gives per level (strides 8,
// 16, 32) class scores (sigmoid, N x 80) and box sides as distributions over 11
// bins (N x 44, GFL: left, top, right, bottom, in strides).
#include "ingest/pipeline/detector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.hpp"

#ifndef SMQL_MODEL_DIR
#define SMQL_MODEL_DIR "/usr/local/share/smql/models"
#endif

namespace smql::ingest {

namespace fs = std::filesystem;

namespace {

constexpr int kInputSize = 416;
constexpr int kBins = 11;  // reg_max + 1: each box side is a distribution over 0..10 strides
constexpr std::array<int, 3> kStrides = {8, 16, 32};
constexpr double kNmsIou = 0.5;
// NanoDet's training normalisation, BGR order.
const cv::Scalar kMean{103.53, 116.28, 123.675};
const cv::Scalar kStd{57.375, 57.12, 58.395};

constexpr const char* kModelFile = "nanodet.onnx";
constexpr const char* kClassFile = "coco.names";

// COCO classes whose name is not the memory's: renamed, or "" for what a room's memory does not keep
// (people and animals move, vehicles and street furniture are not indoors). Others keep their name with
// spaces as underscores ("wine glass" -> "wine_glass").
constexpr std::pair<std::string_view, std::string_view> kCocoToMemory[] = {
    {"couch", "sofa"},
    {"sofa", "sofa"},
    {"dining table", "table"},
    {"diningtable", "table"},
    {"tv", "tv"},
    {"tvmonitor", "tv"},
    {"potted plant", "plant"},
    {"pottedplant", "plant"},
    {"cell phone", "phone"},
    {"refrigerator", "fridge"},
    {"cup", "mug"},
    {"teddy bear", "toy"},
    {"hair drier", "hair_dryer"},
    {"person", ""},
    {"bicycle", ""},
    {"car", ""},
    {"motorcycle", ""},
    {"motorbike", ""},
    {"airplane", ""},
    {"aeroplane", ""},
    {"bus", ""},
    {"train", ""},
    {"truck", ""},
    {"boat", ""},
    {"traffic light", ""},
    {"fire hydrant", ""},
    {"stop sign", ""},
    {"parking meter", ""},
    {"bird", ""},
    {"cat", ""},
    {"dog", ""},
    {"horse", ""},
    {"sheep", ""},
    {"cow", ""},
    {"elephant", ""},
    {"bear", ""},
    {"zebra", ""},
    {"giraffe", ""},
};

std::vector<std::string> readClassNames(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw Error(ErrorKind::Input, fmt::format("{}: cannot read the class names", path.string()));
    std::vector<std::string> names;
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (!line.empty()) names.push_back(line);
    }
    return names;
}

class NanoDetDetector : public ObjectDetector {
public:
    NanoDetDetector(const DetectorFiles& files, double minScore) : minScore_(minScore) {
        try {
            net_ = cv::dnn::readNetFromONNX(files.model.string());
        } catch (const cv::Exception& e) {
            throw Error(ErrorKind::Input,
                        fmt::format("{}: not a model OpenCV can load: {}", files.model.string(), e.msg), std::nullopt,
                        "prepare it with scripts/detector/setup.sh");
        }
        net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
        net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
        classes_ = readClassNames(files.classes);
        for (const auto& name : classes_) categories_.push_back(memoryCategory(name));
        outputNames_ = net_.getUnconnectedOutLayersNames();
        if (outputNames_.size() != 2 * kStrides.size())
            throw Error(ErrorKind::Input, fmt::format("{}: {} outputs, NanoDet has {} (scores and boxes per level)",
                                                      files.model.string(), outputNames_.size(), 2 * kStrides.size()));
    }

    std::vector<Detection> detect(const cv::Mat& bgr) override {
        cv::Mat resized, input;
        cv::resize(bgr, resized, cv::Size(kInputSize, kInputSize), 0, 0, cv::INTER_LINEAR);
        resized.convertTo(input, CV_32FC3);
        cv::subtract(input, kMean, input);
        cv::divide(input, kStd, input);
        net_.setInput(cv::dnn::blobFromImage(input));
        std::vector<cv::Mat> outputs;
        net_.forward(outputs, outputNames_);

        std::vector<cv::Rect2d> boxes;
        std::vector<float> scores;
        std::vector<int> labels;
        double sx = double(bgr.cols) / kInputSize, sy = double(bgr.rows) / kInputSize;
        for (int stride : kStrides) {
            int side = kInputSize / stride;
            const cv::Mat* classScores = nullptr;
            const cv::Mat* distances = nullptr;
            for (const auto& o : outputs) {
                if (o.dims != 3 || o.size[1] != side * side) continue;
                if (o.size[2] == int(classes_.size())) classScores = &o;
                if (o.size[2] == 4 * kBins) distances = &o;
            }
            if (!classScores || !distances)
                throw Error(ErrorKind::Input,
                            fmt::format("the detector has no {}x{} outputs of {} scores and {} box bins (stride {}); "
                                        "is the class file the model's?",
                                        side, side, classes_.size(), 4 * kBins, stride));
            decodeLevel(*classScores, *distances, stride, sx, sy, boxes, scores, labels);
        }
        return suppress(boxes, scores, labels);
    }

private:
    // Cells whose best class scores at least minScore_ become boxes: each side
    // is the expectation of its softmax distribution over the bins, in strides,
    // from the cell's centre.
    void decodeLevel(const cv::Mat& classScores, const cv::Mat& distances, int stride, double sx, double sy,
                     std::vector<cv::Rect2d>& boxes, std::vector<float>& scores, std::vector<int>& labels) const {
        int side = kInputSize / stride, classes = classScores.size[2];
        for (int cell = 0; cell < side * side; ++cell) {
            const float* cellScores = classScores.ptr<float>(0) + std::size_t(cell) * classes;
            int best = int(std::max_element(cellScores, cellScores + classes) - cellScores);
            if (cellScores[best] < minScore_ || categories_[best].empty()) continue;
            const float* bins = distances.ptr<float>(0) + std::size_t(cell) * 4 * kBins;
            std::array<double, 4> sides{};
            for (int s = 0; s < 4; ++s) {
                const float* b = bins + s * kBins;
                float top = *std::max_element(b, b + kBins);
                double sum = 0, expectation = 0;
                for (int k = 0; k < kBins; ++k) {
                    double e = std::exp(double(b[k]) - top);
                    sum += e, expectation += e * k;
                }
                sides[s] = expectation / sum * stride;
            }
            int column = cell % side, row = cell / side;  // the cell's grid position
            double cx = (column + 0.5) * stride, cy = (row + 0.5) * stride;
            double x0 = std::max(0.0, cx - sides[0]), y0 = std::max(0.0, cy - sides[1]);
            double x1 = std::min<double>(kInputSize, cx + sides[2]), y1 = std::min<double>(kInputSize, cy + sides[3]);
            if (x1 <= x0 || y1 <= y0) continue;
            boxes.emplace_back(x0 * sx, y0 * sy, (x1 - x0) * sx, (y1 - y0) * sy);
            scores.push_back(cellScores[best]);
            labels.push_back(best);
        }
    }

    // Non-maximum suppression per class: the cells of one object all vote for it.
    std::vector<Detection> suppress(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                                    const std::vector<int>& labels) const {
        std::map<int, std::vector<int>> byClass;
        for (std::size_t i = 0; i < boxes.size(); ++i) byClass[labels[i]].push_back(int(i));
        std::vector<Detection> out;
        for (const auto& [label, members] : byClass) {
            std::vector<cv::Rect2d> classBoxes;
            std::vector<float> classScores;
            for (int i : members) classBoxes.push_back(boxes[i]), classScores.push_back(scores[i]);
            std::vector<int> kept;
            cv::dnn::NMSBoxes(classBoxes, classScores, float(minScore_), float(kNmsIou), kept);
            for (int k : kept) {
                Detection d;
                d.category = categories_[label];
                d.score = classScores[k];
                d.box = classBoxes[k];
                out.push_back(std::move(d));
            }
        }
        std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.score > b.score; });
        return out;
    }

    double minScore_;
    cv::dnn::Net net_;
    std::vector<std::string> classes_, categories_;
    std::vector<std::string> outputNames_;
};

}  // namespace

fs::path defaultModelDir() { return SMQL_MODEL_DIR; }

std::optional<DetectorFiles> findDetectorFiles(const std::string& model, const std::string& classes) {
    DetectorFiles files;
    files.model = model.empty() ? defaultModelDir() / kModelFile : fs::path(model);
    files.classes = !classes.empty() ? fs::path(classes) : files.model.parent_path() / kClassFile;
    std::error_code ec;
    if (!fs::is_regular_file(files.model, ec) || !fs::is_regular_file(files.classes, ec)) return std::nullopt;
    return files;
}

std::unique_ptr<ObjectDetector> makeNanoDetDetector(const DetectorFiles& files, double minScore) {
    return std::make_unique<NanoDetDetector>(files, minScore);
}

std::string memoryCategory(std::string_view cocoName) {
    for (const auto& [coco, memory] : kCocoToMemory)
        if (coco == cocoName) return std::string(memory);
    std::string name(cocoName);
    std::replace(name.begin(), name.end(), ' ', '_');
    return name;
}

}  // namespace smql::ingest
