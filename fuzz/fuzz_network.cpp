// The runner of the models' graphs (ingest/pipeline/network.hpp) on an ONNX file's bytes: a graph it
// does not plan is refused with a reason; a graph it plans runs on a blob of its input's shape, and
// anything wrong then is an smql::Error. The seeds are small graphs of the operators it knows.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fuzz_support.hpp"
#include "ingest/pipeline/network.hpp"
#include "model/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // A blob of at most a million floats: the runner refuses more than 128 MiB of tensors in all, and a
    // run's time should go to the operators, not to filling a large input.
    constexpr std::int64_t kMaxInput = 1'000'000;
    static const smql::fuzz::Scratch scratch;
    const std::string path = scratch.write("graph.onnx", smql::fuzz::bytesOf(data, size));
    std::string whyNot;
    try {
        const auto network = smql::ingest::loadXnnpackNetwork(path, {}, &whyNot);
        if (!network) {
            if (whyNot.empty()) std::abort();  // a refusal says why
            return 0;
        }
        const std::vector<int> shape = network->inputShape();
        std::int64_t count = 1;
        for (const int d : shape) count *= d;
        if (count > kMaxInput) return 0;
        cv::Mat blob(static_cast<int>(shape.size()), shape.data(), CV_32F, cv::Scalar(0.5));
        for (const cv::Mat& output : network->run(blob))
            if (output.type() != CV_32F) std::abort();
    } catch (const smql::Error&) {
    }
    return 0;
}
