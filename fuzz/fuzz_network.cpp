// The runner of the models' graphs (ingest/pipeline/network.hpp) on an ONNX file's bytes: a graph it
// does not plan is refused with a reason; a graph it plans runs on a blob of its input's shape, and
// anything wrong then is an smql::Error. The seeds are small graphs of the operators it knows.
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <onnx/onnx_pb.h>
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
        onnx::ModelProto model;
        std::ifstream in(path, std::ios::binary);
        if (!model.ParseFromIstream(&in)) std::abort();  // the runner planned what protobuf does not read
        std::vector<int> shape;
        std::int64_t count = 1;
        for (const auto& input : model.graph().input()) {
            bool constant = false;
            for (const auto& t : model.graph().initializer()) constant = constant || t.name() == input.name();
            if (constant) continue;
            for (const auto& d : input.type().tensor_type().shape().dim()) {
                shape.push_back(static_cast<int>(d.dim_value()));
                count *= d.dim_value();
                if (count > kMaxInput) return 0;
            }
            break;
        }
        cv::Mat blob(static_cast<int>(shape.size()), shape.data(), CV_32F, cv::Scalar(0.5));
        for (const cv::Mat& output : network->run(blob))
            if (output.type() != CV_32F) std::abort();
    } catch (const smql::Error&) {
    }
    return 0;
}
