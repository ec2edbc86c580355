// The models' graphs (ONNX) and what runs them. NanoDet, the Open Images SSD and DeepLab are mostly 1x1
// and depthwise convolutions, which XNNPACK's kernels (Debian's libxnnpack) run two to three times faster
// than OpenCV's DNN on a core; a graph is run on XNNPACK's operators when each operator its outputs need
// is one this runner knows (below), and by OpenCV's DNN otherwise (a --detector graph of other operators).
// docs/ingest.md, "Detector".
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace smql::ingest {

class Network {
public:
    virtual ~Network() = default;
    // The outputs for an N x C x H x W float blob of the graph's input shape, in outputs()'s order, as
    // OpenCV's DNN gives them: a 4-d tensor N x C x H x W, any other in its own shape. Each run's tensors
    // are the caller's.
    virtual std::vector<cv::Mat> run(const cv::Mat& blob) = 0;
    virtual const std::vector<std::string>& outputs() const = 0;
    // The N x C x H x W the graph's input is read as, where the engine plans for one size; empty where it
    // takes any (OpenCV's DNN).
    virtual std::vector<int> inputShape() const = 0;
    // "XNNPACK" or "OpenCV DNN".
    virtual std::string_view engine() const = 0;
};

// The graph in `model`, run up to `outputs` (the graph's own outputs when none are named): on XNNPACK
// when it can, each run on `threads` threads (the caller's and a pool of XNNPACK's; OpenCV's DNN takes
// the process's count, cv::setNumThreads), else on OpenCV's DNN. Throws smql::Error(Input) when neither
// loads the file or an output is not in the graph.
std::unique_ptr<Network> loadNetwork(const std::filesystem::path& model, const std::vector<std::string>& outputs = {},
                                     int threads = 1);

// Each engine on its own (the tests hold one to the other). loadXnnpackNetwork gives nullptr, saying
// why in `whyNot` when given, for a graph it does not run: an operator or attribute outside the ones
// below, an input of unknown size, a machine XNNPACK does not support.
//   Conv (any groups, dilations, pads, auto_pad) with a Clip or Relu after it folded in, Clip, Relu,
//   LeakyRelu, Sigmoid, Exp, MaxPool, GlobalAveragePool, Resize and Upsample (linear, nearest), Add, Sub,
//   Mul (broadcasting), Concat, Split, Slice (step 1), Reshape, Flatten, Transpose, Identity.
std::unique_ptr<Network> loadXnnpackNetwork(const std::filesystem::path& model,
                                            const std::vector<std::string>& outputs = {}, std::string* whyNot = nullptr,
                                            int threads = 1);
std::unique_ptr<Network> loadOpenCvNetwork(const std::filesystem::path& model,
                                           const std::vector<std::string>& outputs = {});

}  // namespace smql::ingest
