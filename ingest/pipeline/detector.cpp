// The detectors, their graphs run by a Network (network.hpp; docs/ingest.md "Detector").
// NanoDet's graph (scripts/detector/tfjs_to_onnx.py) takes a 1x3x416x416 BGR
// image normalised by NanoDet's mean and deviation, and gives per level
// (strides 8, 16, 32) class scores (sigmoid, N x 80) and box sides as
// distributions over 11 bins (N x 44, GFL: left, top, right, bottom, in
// strides). The Open Images SSD's (scripts/detector/oid_tflite_to_onnx.py)
// decodes its anchors in the graph.
#include "ingest/pipeline/detector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/pipeline/network.hpp"
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
constexpr double kNestedShare = 0.85;  // suppressPerClass
// NanoDet's training normalisation, BGR order.
const cv::Scalar kMean{103.53, 116.28, 123.675};
const cv::Scalar kStd{57.375, 57.12, 58.395};

constexpr int kSsdInputSize = 300;

const std::vector<PackagedModel> kPackagedModels{
    {"nanodet", "nanodet.onnx", "coco.names", ModelRole::Detector, "NanoDet, trained on COCO (80 classes)"},
    {"oid", "oid_ssd.onnx", "oid.names", ModelRole::Detector,
     "MediaPipe Objectron's SSD, trained on Open Images (23 classes: desk, table, computer monitor, book, box ...)"},
    {"deeplab", "deeplab_voc.onnx", "voc.names", ModelRole::Segmenter,
     "DeepLab v3 (MobileNetV2), trained on PASCAL VOC (20 classes: chair, sofa, dining table, tv, plant, bottle ...)"},
};

// The models' classes whose name is not the memory's, in lower case: renamed, or "" for what a room's
// memory does not keep (people and animals move, vehicles and street furniture are not indoors, shoes
// are not furniture). Others keep their name in lower case with spaces as underscores ("wine glass" ->
// "wine_glass").
constexpr std::pair<std::string_view, std::string_view> kClassToMemory[] = {
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
    // Open Images (the SSD's), lower-cased.
    {"computer monitor", "monitor"},
    {"computer mouse", "mouse"},
    {"coffee cup", "mug"},
    {"stationary bicycle", ""},
    {"cattle", ""},
    {"vehicle", ""},
    {"footwear", ""},
    {"boot", ""},
    {"high heels", ""},
    // PASCAL VOC (the segmenter's): what is no thing.
    {"background", ""},
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
    NanoDetDetector(const DetectorFiles& files, double minScore, const GraphPlacement& placement)
        : minScore_(minScore), file_(files.model.filename().string()), net_(loadNetwork(files.model, {}, placement)) {
        classes_ = readClassNames(files.classes);
        for (const auto& name : classes_) categories_.push_back(memoryCategory(name));
        if (net_->outputs().size() != 2 * kStrides.size())
            throw Error(ErrorKind::Input,
                        fmt::format("{}: {} outputs, NanoDet has {} (scores and boxes per level)", files.model.string(),
                                    net_->outputs().size(), 2 * kStrides.size()));
    }

    std::vector<Detection> detect(const cv::Mat& bgr) override {
        cv::Mat resized, input;
        cv::resize(bgr, resized, cv::Size(kInputSize, kInputSize), 0, 0, cv::INTER_LINEAR);
        resized.convertTo(input, CV_32FC3);
        cv::subtract(input, kMean, input);
        cv::divide(input, kStd, input);
        const std::vector<cv::Mat> outputs = net_->run(cv::dnn::blobFromImage(input));

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
        return suppressPerClass(boxes, scores, labels, categories_, minScore_);
    }

    std::string describe() const override { return file_; }

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

    double minScore_;
    std::string file_;
    std::unique_ptr<Network> net_;
    std::vector<std::string> classes_, categories_;
};

// The Open Images SSD: its graph decodes the anchors; what is left is the best class of each anchor
// and the suppression.
class SsdDetector : public ObjectDetector {
public:
    SsdDetector(const DetectorFiles& files, double minScore, const GraphPlacement& placement)
        : minScore_(minScore),
          file_(files.model.filename().string()),
          net_(loadNetwork(files.model, {"boxes", "scores"}, placement)) {
        for (const auto& name : readClassNames(files.classes)) categories_.push_back(memoryCategory(name));
    }

    std::vector<Detection> detect(const cv::Mat& bgr) override {
        const std::vector<cv::Mat> outputs =
            net_->run(cv::dnn::blobFromImage(bgr, 1 / 127.5, cv::Size(kSsdInputSize, kSsdInputSize),
                                             cv::Scalar(127.5, 127.5, 127.5), /*swapRB=*/true, /*crop=*/false));
        const cv::Mat& boxes = outputs[0];
        const cv::Mat& scores = outputs[1];
        if (boxes.dims != 3 || scores.dims != 3 || boxes.size[2] != 4 || scores.size[1] != boxes.size[1] ||
            scores.size[2] != static_cast<int>(categories_.size()))
            throw Error(ErrorKind::Input, fmt::format("{}: its outputs are not an SSD's boxes and {} class scores",
                                                      file_, categories_.size()));
        std::vector<cv::Rect2d> found;
        std::vector<float> foundScores;
        std::vector<int> labels;
        const int anchors = boxes.size[1], classes = scores.size[2];
        for (int a = 0; a < anchors; ++a) {
            const float* s = scores.ptr<float>(0) + std::size_t(a) * classes;
            const int best = static_cast<int>(std::max_element(s, s + classes) - s);
            if (s[best] < minScore_ || categories_[best].empty()) continue;
            const float* b = boxes.ptr<float>(0) + std::size_t(a) * 4;  // top, left, bottom, right
            const double x0 = std::clamp<double>(b[1], 0, 1) * bgr.cols, y0 = std::clamp<double>(b[0], 0, 1) * bgr.rows;
            const double x1 = std::clamp<double>(b[3], 0, 1) * bgr.cols, y1 = std::clamp<double>(b[2], 0, 1) * bgr.rows;
            if (x1 <= x0 || y1 <= y0) continue;
            found.emplace_back(x0, y0, x1 - x0, y1 - y0);
            foundScores.push_back(s[best]);
            labels.push_back(best);
        }
        return suppressPerClass(found, foundScores, labels, categories_, minScore_);
    }

    std::string describe() const override { return file_; }

private:
    double minScore_;
    std::string file_;
    std::unique_ptr<Network> net_;
    std::vector<std::string> categories_;
};

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
    const double inter = (a & b).area();
    return inter > 0 ? inter / (a.area() + b.area() - inter) : 0;
}

class DetectorEnsemble : public ObjectDetector {
public:
    explicit DetectorEnsemble(std::vector<std::unique_ptr<ObjectDetector>> members) : members_(std::move(members)) {}

    std::vector<Detection> detect(const cv::Mat& bgr) override {
        std::vector<std::pair<std::size_t, Detection>> all;  // (member, detection)
        for (std::size_t m = 0; m < members_.size(); ++m)
            for (auto& d : members_[m]->detect(bgr)) all.emplace_back(m, std::move(d));
        std::stable_sort(all.begin(), all.end(),
                         [](const auto& a, const auto& b) { return a.second.score > b.second.score; });
        std::vector<std::pair<std::size_t, Detection>> kept;
        for (auto& entry : all) {
            const std::size_t member = entry.first;
            Detection& d = entry.second;
            auto same = std::find_if(kept.begin(), kept.end(), [&](const auto& k) {
                return k.first != member && iou(k.second.box, d.box) >= kSameThingIou &&
                       std::none_of(k.second.alsoSeenAs.begin(), k.second.alsoSeenAs.end(),
                                    [&](const auto& other) { return other.first == d.category; });
            });
            if (same == kept.end())
                kept.emplace_back(member, std::move(d));
            else
                same->second.alsoSeenAs.emplace_back(d.category, d.score);
        }
        std::vector<Detection> out;
        for (auto& [member, d] : kept) out.push_back(std::move(d));
        return out;
    }

    std::string describe() const override {
        std::string out;
        for (const auto& m : members_) out += (out.empty() ? "" : " + ") + m->describe();
        return out;
    }

private:
    std::vector<std::unique_ptr<ObjectDetector>> members_;
};

}  // namespace

// Non-maximum suppression per class: the cells (anchors) of one object all vote for it. Then of two boxes of a
// class that overlap by kNestedShare of the smaller one, one nested in the other, only the better scored is kept:
// one thing seen whole and in part (a toilet's bowl inside the box of the toilet with its tank). IoU leaves such
// pairs apart, and the part's box would own the thing's pixels and leave the whole's box what stands behind it.
// Best first.
std::vector<Detection> suppressPerClass(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                                        const std::vector<int>& labels, const std::vector<std::string>& categories,
                                        double minScore) {
    std::map<int, std::vector<int>> byClass;
    for (std::size_t i = 0; i < boxes.size(); ++i) byClass[labels[i]].push_back(int(i));
    std::vector<Detection> out;
    for (const auto& [label, members] : byClass) {
        std::vector<cv::Rect2d> classBoxes;
        std::vector<float> classScores;
        for (int i : members) classBoxes.push_back(boxes[i]), classScores.push_back(scores[i]);
        std::vector<int> kept;
        cv::dnn::NMSBoxes(classBoxes, classScores, float(minScore), float(kNmsIou), kept);
        // Best first (NMSBoxes' order): a box nested in a better one, or holding a better one, is dropped.
        std::vector<Detection> things;
        for (int k : kept) {
            const cv::Rect2d& box = classBoxes[k];
            const bool nested = std::any_of(things.begin(), things.end(), [&](const Detection& w) {
                const double inter = (w.box & box).area();
                return inter >= kNestedShare * std::min(box.area(), w.box.area()) && inter > 0;
            });
            if (nested) continue;
            Detection d;
            d.category = categories[label];
            d.score = classScores[k];
            d.box = box;
            things.push_back(std::move(d));
        }
        for (auto& d : things) out.push_back(std::move(d));
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.score > b.score; });
    return out;
}

const std::vector<PackagedModel>& packagedModels() { return kPackagedModels; }

fs::path defaultModelDir() { return SMQL_MODEL_DIR; }

std::optional<DetectorFiles> installedModel(std::string_view name) {
    for (const auto& m : kPackagedModels) {
        if (m.name != name) continue;
        DetectorFiles files{defaultModelDir() / m.file, defaultModelDir() / m.classes};
        std::error_code ec;
        if (fs::is_regular_file(files.model, ec) && fs::is_regular_file(files.classes, ec)) return files;
    }
    return std::nullopt;
}

std::optional<DetectorFiles> findDetectorFiles(const std::string& model, const std::string& classes) {
    if (model.empty() && classes.empty()) return installedModel("nanodet");
    DetectorFiles files;
    files.model = model.empty() ? defaultModelDir() / kPackagedModels.front().file : fs::path(model);
    files.classes = !classes.empty() ? fs::path(classes) : files.model.parent_path() / kPackagedModels.front().classes;
    std::error_code ec;
    if (!fs::is_regular_file(files.model, ec) || !fs::is_regular_file(files.classes, ec)) return std::nullopt;
    return files;
}

std::unique_ptr<ObjectDetector> makeNanoDetDetector(const DetectorFiles& files, double minScore,
                                                    const GraphPlacement& placement) {
    return std::make_unique<NanoDetDetector>(files, minScore, placement);
}

std::unique_ptr<ObjectDetector> makeSsdDetector(const DetectorFiles& files, double minScore,
                                                const GraphPlacement& placement) {
    return std::make_unique<SsdDetector>(files, minScore, placement);
}

std::unique_ptr<ObjectDetector> makeDetectorEnsemble(std::vector<std::unique_ptr<ObjectDetector>> members) {
    return std::make_unique<DetectorEnsemble>(std::move(members));
}

std::unique_ptr<ObjectDetector> makeDetector(const DetectorFiles& files, bool packaged,
                                             const GraphPlacement& placement) {
    std::vector<std::unique_ptr<ObjectDetector>> members;
    members.push_back(makeNanoDetDetector(files, kNanoDetMinScore, placement));
    if (packaged)
        if (auto oid = installedModel("oid")) members.push_back(makeSsdDetector(*oid, kSsdMinScore, placement));
    if (members.size() == 1) return std::move(members.front());
    return makeDetectorEnsemble(std::move(members));
}

std::string memoryCategory(std::string_view className) {
    std::string name(className);
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const auto& [model, memory] : kClassToMemory)
        if (model == name) return std::string(memory);
    std::replace(name.begin(), name.end(), ' ', '_');
    return name;
}

}  // namespace smql::ingest
