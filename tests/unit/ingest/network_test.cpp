// The models' graphs on XNNPACK's operators (ingest/pipeline/network.hpp), held to OpenCV's DNN running the
// same graphs: the packaged models on real frames (TUM fr1/rpy's desk, the dining room), and small graphs
// of the operators and layouts the packaged ones do not reach. A graph of an operator the runner lacks goes
// to OpenCV's DNN, which says why.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <onnx/onnx_pb.h>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/pipeline/detector.hpp"
#include "ingest/pipeline/network.hpp"
#include "model/error.hpp"
#include "scratch_dir.hpp"

using namespace smql::ingest;
using smql::ingest::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

// The largest difference between two engines' tensors, after checking they have the same shape.
double largestDifference(const cv::Mat& a, const cv::Mat& b) {
    REQUIRE(a.dims == b.dims);
    for (int d = 0; d < a.dims; ++d) REQUIRE(a.size[d] == b.size[d]);
    return cv::norm(a.reshape(1, 1), b.reshape(1, 1), cv::NORM_INF);
}

void requireSameOutputs(Network& xnnpack, Network& opencv, const cv::Mat& blob) {
    const std::vector<cv::Mat> ours = xnnpack.run(blob), theirs = opencv.run(blob);
    REQUIRE(ours.size() == theirs.size());
    for (std::size_t o = 0; o < ours.size(); ++o) {
        INFO(fmt::format("output '{}'", xnnpack.outputs()[o]));
        const double scale = 1 + cv::norm(theirs[o].reshape(1, 1), cv::NORM_INF);
        CHECK(largestDifference(ours[o], theirs[o]) <= 1e-4 * scale);
    }
}

// Real frames: three of TUM fr1/rpy's desk, the five of the dining room.
std::vector<cv::Mat> realFrames() {
    std::vector<cv::Mat> frames;
    std::vector<cv::String> tum;
    cv::glob(std::string(SMQL_SHARED_DATA) + "/captures/tum-fr1-rpy/rgb/*.png", tum);
    for (std::size_t i = 0; i < tum.size(); i += std::max<std::size_t>(1, tum.size() / 3))
        frames.push_back(cv::imread(tum[i]));
    for (int i = 1; i <= 5; ++i)
        frames.push_back(cv::imread(fmt::format("{}/rgbd-dining/color/{}.png", SMQL_SHARED_DATA, i)));
    for (const auto& f : frames) REQUIRE(!f.empty());
    return frames;
}

// A small ONNX graph, built node by node.
class Graph {
public:
    explicit Graph(std::vector<std::int64_t> input, int opset = 11) {
        model_.set_ir_version(7);
        model_.add_opset_import()->set_version(opset);
        auto* in = model_.mutable_graph()->add_input();
        in->set_name("x");
        auto* type = in->mutable_type()->mutable_tensor_type();
        type->set_elem_type(onnx::TensorProto::FLOAT);
        for (auto d : input) type->mutable_shape()->add_dim()->set_dim_value(d);
    }
    void floats(const std::string& name, std::vector<std::int64_t> shape, std::vector<float> values) {
        auto* t = model_.mutable_graph()->add_initializer();
        t->set_name(name);
        t->set_data_type(onnx::TensorProto::FLOAT);
        for (auto d : shape) t->add_dims(d);
        for (float v : values) t->add_float_data(v);
    }
    void integers(const std::string& name, std::vector<std::int64_t> values) {
        auto* t = model_.mutable_graph()->add_initializer();
        t->set_name(name);
        t->set_data_type(onnx::TensorProto::INT64);
        t->add_dims(static_cast<std::int64_t>(values.size()));
        for (auto v : values) t->add_int64_data(v);
    }
    onnx::NodeProto& node(const std::string& op, std::vector<std::string> inputs, std::vector<std::string> outputs) {
        auto* n = model_.mutable_graph()->add_node();
        n->set_op_type(op);
        n->set_name(outputs.front());
        for (const auto& i : inputs) n->add_input(i);
        for (const auto& o : outputs) n->add_output(o);
        return *n;
    }
    static void ints(onnx::NodeProto& n, const std::string& name, std::vector<std::int64_t> values) {
        auto* a = n.add_attribute();
        a->set_name(name);
        a->set_type(onnx::AttributeProto::INTS);
        for (auto v : values) a->add_ints(v);
    }
    static void integer(onnx::NodeProto& n, const std::string& name, std::int64_t value) {
        auto* a = n.add_attribute();
        a->set_name(name);
        a->set_type(onnx::AttributeProto::INT);
        a->set_i(value);
    }
    static void real(onnx::NodeProto& n, const std::string& name, float value) {
        auto* a = n.add_attribute();
        a->set_name(name);
        a->set_type(onnx::AttributeProto::FLOAT);
        a->set_f(value);
    }
    static void text(onnx::NodeProto& n, const std::string& name, const std::string& value) {
        auto* a = n.add_attribute();
        a->set_name(name);
        a->set_type(onnx::AttributeProto::STRING);
        a->set_s(value);
    }
    void output(const std::string& name) {
        auto* out = model_.mutable_graph()->add_output();
        out->set_name(name);
        out->mutable_type()->mutable_tensor_type()->set_elem_type(onnx::TensorProto::FLOAT);
        out->mutable_type()->mutable_tensor_type()->mutable_shape();  // OpenCV reads that it has one
    }
    fs::path write(const fs::path& path) const {
        std::ofstream out(path, std::ios::binary);
        REQUIRE(model_.SerializeToOstream(&out));
        return path;
    }

private:
    onnx::ModelProto model_;
};

std::vector<float> ramp(std::size_t n, float step) {
    std::vector<float> values(n);
    for (std::size_t i = 0; i < n; ++i) values[i] = std::sin(0.7f * static_cast<float>(i)) * step;
    return values;
}

// The packaged models' graphs, with their inputs' sizes, the outputs the ingest reads and their blobs.
struct PackagedGraph {
    std::string_view name;
    cv::Size input;
    std::vector<std::string> outputs;
    std::function<cv::Mat(const cv::Mat&, cv::Size)> blob;
};
std::vector<PackagedGraph> packagedGraphs() {
    const auto signedUnit = [](const cv::Mat& bgr, cv::Size size) {
        return cv::dnn::blobFromImage(bgr, 1 / 127.5, size, cv::Scalar(127.5, 127.5, 127.5), true, false);
    };
    return {
        {"nanodet",
         {416, 416},
         {},
         [](const cv::Mat& bgr, cv::Size size) {
             return cv::dnn::blobFromImage(bgr, 1 / 57.5, size, cv::Scalar(103.53, 116.28, 123.675), false, false);
         }},
        {"oid", {300, 300}, {"boxes", "scores"}, signedUnit},
        {"deeplab", {513, 385}, {"logits_lowres"}, signedUnit},
    };
}

}  // namespace

TEST_CASE("the packaged models give OpenCV's DNN's outputs on XNNPACK, on real frames") {
    const std::vector<PackagedGraph> models = packagedGraphs();
    const std::vector<cv::Mat> frames = realFrames();
    for (const auto& m : models) {
        INFO(m.name);
        auto files = installedModel(m.name);
        if (!files) {
            WARN(fmt::format("skipped: no {} model (run scripts/detector/setup.sh)", m.name));
            continue;
        }
        std::string whyNot;
        auto xnnpack = loadXnnpackNetwork(files->model, m.outputs, &whyNot);
        INFO(whyNot);
        REQUIRE(xnnpack);
        CHECK(xnnpack->engine() == "XNNPACK");
        auto opencv = loadOpenCvNetwork(files->model, xnnpack->outputs());
        CHECK(xnnpack->outputs().size() == (m.outputs.empty() ? 6 : m.outputs.size()));
        // And on a pool of two threads, as a stream runs them on a machine of four cores.
        auto pooled = loadXnnpackNetwork(files->model, m.outputs, nullptr, {2, nullptr});
        REQUIRE(pooled);
        for (const auto& frame : frames) {
            const cv::Mat blob = m.blob(frame, m.input);
            CHECK(xnnpack->inputShape() == std::vector<int>(blob.size.p, blob.size.p + blob.dims));
            requireSameOutputs(*xnnpack, *opencv, blob);
            requireSameOutputs(*pooled, *opencv, blob);
        }
        // The loader picks XNNPACK for them.
        CHECK(loadNetwork(files->model, m.outputs)->engine() == "XNNPACK");
    }
}

TEST_CASE("a stream's packaged models planned into one arena run in turns as each planned alone, in less memory") {
    // As a stream of the ingest holds them: DeepLab, then NanoDet and the SSD, one arena for their tensors.
    const auto shared = std::make_shared<TensorArena>();
    std::size_t alone = 0, largest = 0;
    struct Pair {
        PackagedGraph graph;
        std::unique_ptr<Network> inShared, inOwn;
    };
    std::vector<Pair> pairs;
    std::vector<PackagedGraph> graphs = packagedGraphs();
    std::rotate(graphs.begin(), graphs.end() - 1, graphs.end());
    REQUIRE(graphs.front().name == "deeplab");
    for (const auto& m : graphs) {
        auto files = installedModel(m.name);
        if (!files) {
            WARN(fmt::format("skipped: no {} model (run scripts/detector/setup.sh)", m.name));
            return;
        }
        const auto own = std::make_shared<TensorArena>();
        pairs.push_back({m, loadXnnpackNetwork(files->model, m.outputs, nullptr, {1, shared}),
                         loadXnnpackNetwork(files->model, m.outputs, nullptr, {1, own})});
        REQUIRE(pairs.back().inShared);
        REQUIRE(pairs.back().inOwn);
        alone += own->floats();
        largest = std::max(largest, own->floats());
    }
    INFO(fmt::format("{} floats shared, {} alone, the largest graph's {}", shared->floats(), alone, largest));
    // The detectors plan into the buffers DeepLab, the largest, left: the arena holds little more than
    // DeepLab's tensors and the detectors' constants.
    CHECK(shared->floats() < largest * 11 / 10);
    CHECK(shared->floats() < alone * 6 / 10);
    // Each frame through every graph in turn, each overwriting the buffers of the ones before it: the
    // same outputs as the graphs with buffers of their own.
    for (const auto& frame : realFrames())
        for (auto& [graph, inShared, inOwn] : pairs) {
            INFO(graph.name);
            const cv::Mat blob = graph.blob(frame, graph.input);
            const std::vector<cv::Mat> ours = inShared->run(blob), theirs = inOwn->run(blob);
            REQUIRE(ours.size() == theirs.size());
            for (std::size_t o = 0; o < ours.size(); ++o) CHECK(largestDifference(ours[o], theirs[o]) == 0);
        }
}

TEST_CASE("operators and layouts the packaged models do not reach agree with OpenCV's DNN") {
    ScratchDir dir;
    // 1 x 4 x 6 x 8 in: a strided, unevenly padded, grouped convolution with a Clip folded in, a channel
    // split, a transpose of height and width, a broadcast product, a nearest and a linear resize, a channel
    // slice, a padded max pooling, concatenations along the width and the channels, a global average of a
    // tensor not kept as an image, a flatten.
    Graph g({1, 4, 6, 8});
    g.floats("w", {8, 2, 3, 3}, ramp(8 * 2 * 3 * 3, 0.3f));
    g.floats("b", {8}, ramp(8, 0.1f));
    auto& conv = g.node("Conv", {"x", "w", "b"}, {"c"});
    Graph::integer(conv, "group", 2);
    Graph::ints(conv, "kernel_shape", {3, 3});
    Graph::ints(conv, "strides", {1, 2});
    Graph::ints(conv, "pads", {1, 0, 2, 1});
    auto& clip = g.node("Clip", {"c"}, {"clipped"});  // its bounds as attributes, as OpenCV reads them
    Graph::real(clip, "min", -0.5f);
    Graph::real(clip, "max", 0.8f);
    auto& split = g.node("Split", {"clipped"}, {"s0", "s1"});
    Graph::integer(split, "axis", 1);
    Graph::ints(split, "split", {3, 5});
    Graph::ints(g.node("Transpose", {"s0"}, {"t"}), "perm", {0, 1, 3, 2});
    g.floats("scale", {1, 3, 1, 1}, {0.5f, -1.5f, 2.0f});
    g.node("Mul", {"t", "scale"}, {"m"});
    g.floats("twice", {4}, {1, 1, 2, 2});
    auto& nearest = g.node("Resize", {"s1", "", "twice"}, {"up"});
    Graph::text(nearest, "mode", "nearest");
    Graph::text(nearest, "coordinate_transformation_mode", "asymmetric");
    Graph::text(nearest, "nearest_mode", "floor");
    g.floats("smaller", {4}, {1, 1, 0.75f, 0.75f});  // 14 x 8 -> 10 x 6, across the nearest resize's blocks
    auto& linear = g.node("Resize", {"up", "", "smaller"}, {"down"});
    Graph::text(linear, "mode", "linear");
    Graph::text(linear, "coordinate_transformation_mode", "align_corners");
    g.integers("starts", {1});
    g.integers("ends", {3});
    g.integers("axes", {1});
    g.node("Slice", {"down", "starts", "ends", "axes"}, {"sl"});
    auto& pool = g.node("MaxPool", {"sl"}, {"p"});
    Graph::ints(pool, "kernel_shape", {2, 2});
    Graph::ints(pool, "pads", {1, 1, 1, 1});
    Graph::integer(g.node("Concat", {"m", "m"}, {"wide"}), "axis", 3);
    Graph::integer(g.node("Concat", {"sl", "sl"}, {"deep"}), "axis", -3);
    g.node("GlobalAveragePool", {"wide"}, {"avg"});
    Graph::integer(g.node("Flatten", {"p"}, {"flat"}), "axis", 2);
    g.node("Sigmoid", {"flat"}, {"sig"});
    for (const auto* o : {"wide", "avg", "sig", "deep", "clipped"}) g.output(o);
    const fs::path path = g.write(dir.path / "small.onnx");

    std::string whyNot;
    auto xnnpack = loadXnnpackNetwork(path, {}, &whyNot);
    INFO(whyNot);
    REQUIRE(xnnpack);
    auto opencv = loadOpenCvNetwork(path, xnnpack->outputs());
    cv::Mat blob(std::vector<int>{1, 4, 6, 8}, CV_32F);
    cv::randu(blob, -2, 2);
    requireSameOutputs(*xnnpack, *opencv, blob);
}

TEST_CASE("a graph with an operator the runner lacks runs on OpenCV's DNN, which says why") {
    ScratchDir dir;
    Graph g({1, 3, 4, 4});
    g.floats("w", {2, 3, 1, 1}, ramp(6, 1));
    Graph::ints(g.node("Conv", {"x", "w"}, {"c"}), "kernel_shape", {1, 1});
    Graph::integer(g.node("Softmax", {"c"}, {"y"}), "axis", 1);
    g.output("y");
    const fs::path path = g.write(dir.path / "softmax.onnx");
    std::string whyNot;
    CHECK(!loadXnnpackNetwork(path, {}, &whyNot));
    CHECK_THAT(whyNot, Catch::Contains("Softmax"));
    auto network = loadNetwork(path);
    CHECK(network->engine() == "OpenCV DNN");
    CHECK(network->inputShape().empty());  // it takes any size
    cv::Mat blob(std::vector<int>{1, 3, 4, 4}, CV_32F, cv::Scalar(1));
    const cv::Mat y = network->run(blob).front();
    REQUIRE(y.dims == 4);
    CHECK(y.size[1] == 2);

    // Planned into a shared arena, the plan that fails at the Softmax leaves the buffers it took (the input's
    // 48 floats, the convolution's 32) to the graphs planned after it.
    const auto arena = std::make_shared<TensorArena>();
    CHECK(!loadXnnpackNetwork(path, {}, nullptr, {1, arena}));
    const std::size_t held = arena->floats();
    CHECK(held >= 48 + 32);
    arena->acquire(48);
    arena->acquire(32);
    CHECK(arena->floats() == held);

    // A blob of another shape is an input error, not a read past the buffers.
    Graph h({1, 3, 4, 4});
    h.node("Sigmoid", {"x"}, {"y"});
    h.output("y");
    auto sigmoid = loadXnnpackNetwork(h.write(dir.path / "sigmoid.onnx"));
    REQUIRE(sigmoid);
    cv::Mat wrong(std::vector<int>{1, 3, 4, 5}, CV_32F, cv::Scalar(0));
    CHECK_THROWS_AS(sigmoid->run(wrong), smql::Error);
    // A file that is not a graph is refused by both, with OpenCV's words.
    std::ofstream(dir.path / "junk.onnx") << "not a graph";
    CHECK(!loadXnnpackNetwork(dir.path / "junk.onnx"));
    CHECK_THROWS_AS(loadNetwork(dir.path / "junk.onnx"), smql::Error);
}

TEST_CASE("graphs whose numbers make no tensor are refused by the runner, not run") {
    ScratchDir dir;
    struct Broken {
        std::string what;
        std::function<void(Graph&)> build;
    };
    const std::vector<Broken> broken{
        {"a convolution of stride 0",
         [](Graph& g) {
             g.floats("w", {2, 3, 1, 1}, ramp(6, 1));
             Graph::ints(g.node("Conv", {"x", "w"}, {"y"}), "strides", {0, 1});
         }},
        {"a convolution of no groups",
         [](Graph& g) {
             g.floats("w", {2, 3, 1, 1}, ramp(6, 1));
             Graph::integer(g.node("Conv", {"x", "w"}, {"y"}), "group", 0);
         }},
        {"a convolution larger than its input",
         [](Graph& g) {
             g.floats("w", {2, 3, 5, 5}, ramp(150, 1));
             g.node("Conv", {"x", "w"}, {"y"});
         }},
        {"a convolution of integer weights",
         [](Graph& g) {
             g.integers("w", {1, 2, 3, 4, 5, 6});
             g.node("Conv", {"x", "w"}, {"y"});
         }},
        {"a split into a negative part",
         [](Graph& g) {
             auto& split = g.node("Split", {"x"}, {"y", "z"});
             Graph::integer(split, "axis", 1);
             Graph::ints(split, "split", {4, -1});
         }},
        {"a transpose naming an axis twice",
         [](Graph& g) {
             Graph::ints(g.node("Transpose", {"x"}, {"y"}), "perm", {0, 1, 1, 3});
         }},
        {"an addition of one operand", [](Graph& g) { g.node("Add", {"x"}, {"y"}); }},
        {"a resize by ten thousand",
         [](Graph& g) {
             g.floats("scales", {4}, {1, 1, 10000, 10000});
             Graph::text(g.node("Resize", {"x", "", "scales"}, {"y"}), "mode", "nearest");
         }},
        {"a reshape to no size",
         [](Graph& g) {
             g.integers("shape", {-1, -1, 0, -2});
             g.node("Reshape", {"x", "shape"}, {"y"});
         }},
    };
    for (const auto& b : broken) {
        INFO(b.what);
        Graph g({1, 3, 4, 4});
        b.build(g);
        g.output("y");
        std::string whyNot;
        CHECK(!loadXnnpackNetwork(g.write(dir.path / "broken.onnx"), {}, &whyNot));
        CHECK(!whyNot.empty());
    }
}

TEST_CASE("an arena's large buffers are zeroed pages of their own, advised for 2 MiB pages") {
    TensorArena arena;
    const std::size_t small = arena.acquire(1000), large = arena.acquire(4 << 20);  // 4 KB, 16 MB
    for (std::size_t b : {small, large}) CHECK(arena.data(b)[0] == 0.0f);
    CHECK(arena.data(large)[(4 << 20) - 1] == 0.0f);
    // /proc/self/smaps: the mapping that holds the large buffer may take huge pages (THPeligible) wherever
    // the kernel gives them to mappings that ask (madvise) or to all.
    std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string setting((std::istreambuf_iterator<char>(mode)), std::istreambuf_iterator<char>());
    if (setting.empty() || setting.find("[never]") != std::string::npos) {
        WARN("skipped the huge pages' check: the kernel gives none");
        return;
    }
    std::ifstream smaps("/proc/self/smaps");
    const auto address = reinterpret_cast<std::uintptr_t>(arena.data(large));
    std::string line;
    bool inside = false;
    std::optional<bool> eligible;
    while (std::getline(smaps, line)) {
        std::uintptr_t from = 0, to = 0;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &from, &to) == 2) {
            inside = from <= address && address < to;
        } else if (inside && line.rfind("THPeligible:", 0) == 0) {
            eligible = line.find('1') != std::string::npos;
            break;
        }
    }
    REQUIRE(eligible.has_value());
    CHECK(*eligible);
}
