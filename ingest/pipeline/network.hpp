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

namespace detail {
// Frees a tensor buffer: `bytes` of pages mapped for it (TensorArena::acquire), or an array when 0.
struct TensorPages {
    void operator()(float* data) const;
    std::size_t bytes = 0;
};
}  // namespace detail

// The memory graphs plan their tensors in. Graphs one thread runs one after another (a stream's two
// detectors and its segmenter) can share one: each plans into the buffers the graphs before it left, as a
// graph's later steps reuse the buffers of its earlier steps' tensors, and asks for new memory only for
// what those do not hold. A constant read as a tensor keeps a buffer of its own while its graph lives.
class TensorArena {
public:
    // The smallest free buffer of at least n floats, taken, or (and always without `reuse`) a new one,
    // with the bytes XNNPACK may read past a tensor's end.
    std::size_t acquire(std::size_t n, bool reuse = true);
    void release(std::size_t buffer) { buffers_[buffer].free = true; }
    float* data(std::size_t buffer) { return buffers_[buffer].data.get(); }
    // The floats of all its buffers.
    std::size_t floats() const { return floats_; }

private:
    struct Buffer {
        std::unique_ptr<float[], detail::TensorPages> data;
        std::size_t size = 0;
        bool free = false;
    };
    std::vector<Buffer> buffers_;
    std::size_t floats_ = 0;
};

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

// Where a graph on XNNPACK runs: each run on `threads` threads (the caller's and a pool of XNNPACK's; OpenCV's
// DNN takes the process's count, cv::setNumThreads), its tensors in `tensors` when given, else in an arena of
// its own (a shared one's graphs must never run at the same time).
struct GraphPlacement {
    int threads = 1;
    std::shared_ptr<TensorArena> tensors;
};

// The graph in `model`, run up to `outputs` (the graph's own outputs when none are named): on XNNPACK
// when it can, as `placement` says, else on OpenCV's DNN. Throws smql::Error(Input) when neither loads the
// file or an output is not in the graph.
std::unique_ptr<Network> loadNetwork(const std::filesystem::path& model, const std::vector<std::string>& outputs = {},
                                     const GraphPlacement& placement = {});

// Each engine on its own (the tests hold one to the other). loadXnnpackNetwork gives nullptr, saying
// why in `whyNot` when given, for a graph it does not run: an operator or attribute outside the ones
// below, an input of unknown size, a machine XNNPACK does not support.
//   Conv (any groups, dilations, pads, auto_pad) with a Clip or Relu after it folded in, Clip, Relu,
//   LeakyRelu, Sigmoid, Exp, MaxPool, GlobalAveragePool, Resize and Upsample (linear, nearest), Add, Sub,
//   Mul (broadcasting), Concat, Split, Slice (step 1), Reshape, Flatten, Transpose, Identity.
std::unique_ptr<Network> loadXnnpackNetwork(const std::filesystem::path& model,
                                            const std::vector<std::string>& outputs = {}, std::string* whyNot = nullptr,
                                            const GraphPlacement& placement = {});
std::unique_ptr<Network> loadOpenCvNetwork(const std::filesystem::path& model,
                                           const std::vector<std::string>& outputs = {});

}  // namespace smql::ingest
