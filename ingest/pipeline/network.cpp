#include "ingest/pipeline/network.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <onnx/onnx_pb.h>
#include <xnnpack.h>
#include <opencv2/dnn.hpp>

#include "model/error.hpp"

namespace smql::ingest {

namespace fs = std::filesystem;

namespace {

using Shape = std::vector<std::int64_t>;

// What a graph could not be planned for; the planner's way out to OpenCV's DNN.
struct Unsupported {
    std::string why;
};

std::int64_t elements(const Shape& shape) {
    std::int64_t n = 1;
    for (const std::int64_t d : shape)
        if (d < 0 || __builtin_mul_overflow(n, d, &n)) throw Unsupported{"a tensor of a size past counting"};
    return n;
}

// The floats a plan's buffers may hold together: the packaged models' take 16-41 MiB, and a graph asking for
// more than 128 MiB is not a detector this machine runs (a resize by thousands, say). Planning a graph near the
// bound zeroes its tensors and builds its operators' indirection: a fuzzed graph of 1 GiB took 8 s to plan.
constexpr std::int64_t kMaxPlannedFloats = std::int64_t{1} << 25;

// The extent along one axis of a sliding window's output (a convolution's, a pooling's); a window that
// makes no output, or whose numbers are not a window's, is refused.
std::int64_t windowExtent(std::int64_t size, std::int64_t padBefore, std::int64_t padAfter, std::int64_t kernel,
                          std::int64_t stride, std::int64_t dilation) {
    if (kernel < 1 || stride < 1 || dilation < 1 || padBefore < 0 || padAfter < 0)
        throw Unsupported{"a window whose size, stride or dilation is under 1, or a negative pad"};
    const std::int64_t span = size + padBefore + padAfter - ((kernel - 1) * dilation + 1);
    if (span < 0) throw Unsupported{"a window larger than its padded input"};
    return span / stride + 1;
}

// A tensor the graph holds (initializers, Constant nodes): floats, or integers (shapes, axes, sizes).
struct Constant {
    Shape shape;
    std::vector<float> floats;
    std::vector<std::int64_t> integers;
};

template <typename T>
std::vector<T> rawValues(const std::string& raw) {
    std::vector<T> values(raw.size() / sizeof(T));
    if (!values.empty()) std::memcpy(values.data(), raw.data(), values.size() * sizeof(T));  // null when empty
    return values;
}

Constant constantOf(const onnx::TensorProto& tensor) {
    Constant constant;
    constant.shape.assign(tensor.dims().begin(), tensor.dims().end());
    switch (tensor.data_type()) {
        case onnx::TensorProto::FLOAT:
            constant.floats = tensor.has_raw_data()
                                  ? rawValues<float>(tensor.raw_data())
                                  : std::vector<float>(tensor.float_data().begin(), tensor.float_data().end());
            break;
        case onnx::TensorProto::INT64:
            constant.integers = tensor.has_raw_data()
                                    ? rawValues<std::int64_t>(tensor.raw_data())
                                    : std::vector<std::int64_t>(tensor.int64_data().begin(), tensor.int64_data().end());
            break;
        case onnx::TensorProto::INT32: {
            const std::vector<std::int32_t> values =
                tensor.has_raw_data()
                    ? rawValues<std::int32_t>(tensor.raw_data())
                    : std::vector<std::int32_t>(tensor.int32_data().begin(), tensor.int32_data().end());
            constant.integers.assign(values.begin(), values.end());
            break;
        }
        default:
            throw Unsupported{fmt::format("a constant '{}' of ONNX type {}", tensor.name(), tensor.data_type())};
    }
    const std::size_t held = constant.floats.empty() ? constant.integers.size() : constant.floats.size();
    if (static_cast<std::int64_t>(held) != elements(constant.shape))
        throw Unsupported{fmt::format("the constant '{}' holds {} values for its shape", tensor.name(), held)};
    return constant;
}

const onnx::AttributeProto* attribute(const onnx::NodeProto& node, std::string_view name) {
    for (const auto& a : node.attribute())
        if (a.name() == name) return &a;
    return nullptr;
}
std::int64_t intAttribute(const onnx::NodeProto& node, std::string_view name, std::int64_t otherwise) {
    const auto* a = attribute(node, name);
    return a ? a->i() : otherwise;
}
float floatAttribute(const onnx::NodeProto& node, std::string_view name, float otherwise) {
    const auto* a = attribute(node, name);
    return a ? a->f() : otherwise;
}
std::string stringAttribute(const onnx::NodeProto& node, std::string_view name, std::string otherwise) {
    const auto* a = attribute(node, name);
    return a ? a->s() : otherwise;
}
std::vector<std::int64_t> intsAttribute(const onnx::NodeProto& node, std::string_view name,
                                        std::vector<std::int64_t> otherwise = {}) {
    const auto* a = attribute(node, name);
    return a ? std::vector<std::int64_t>(a->ints().begin(), a->ints().end()) : otherwise;
}

struct PoolDeleter {
    void operator()(pthreadpool_t pool) const { pthreadpool_destroy(pool); }
};
struct OperatorDeleter {
    void operator()(xnn_operator_t op) const { xnn_delete_operator(op); }
};
using Operator = std::unique_ptr<xnn_operator, OperatorDeleter>;

void check(xnn_status status, std::string_view what) {
    if (status != xnn_status_success) throw Unsupported{fmt::format("XNNPACK refused {} (status {})", what, status)};
}

bool xnnpackReady() {
    static const bool ready = xnn_initialize(nullptr) == xnn_status_success;
    return ready;
}

// A tensor as the plan holds it. An image is a 4-d tensor N x C x H x W kept as N x H x W x C, the layout
// XNNPACK's convolutions take; any other tensor is kept row-major in its own shape ("plain").
enum class Layout { Image, Plain };
// The names of a tensor's copy in the other layout.
constexpr const char* kAsImage = "#image";
constexpr const char* kAsPlain = "#plain";
struct Value {
    Shape shape;  // ONNX's: an image's is N, C, H, W
    Layout layout = Layout::Plain;
    std::size_t buffer = 0;
};

// The graph planned once for its input's shape: each step an XNNPACK operator bound to its buffers, or a
// loop of ours for what moves data between layouts. Buffers are shared by tensors whose lives do not
// overlap, as the steps run in order.
class XnnpackNetwork : public Network {
public:
    XnnpackNetwork(const onnx::ModelProto& model, const std::string& file, const std::vector<std::string>& wanted,
                   const GraphPlacement& placement)
        : leases_{placement.tensors ? placement.tensors : std::make_shared<TensorArena>(), {}, {}} {
        if (placement.threads > 1) pool_.reset(pthreadpool_create(static_cast<std::size_t>(placement.threads)));
        const auto& graph = model.graph();
        for (const auto& o : model.opset_import())
            if (o.domain().empty() || o.domain() == "ai.onnx") opset_ = o.version();
        readConstants(graph);
        for (const auto& n : graph.node())
            if (n.op_type() == "Identity" && n.input_size() == 1 && n.output_size() == 1)
                same_[n.output(0)] = n.input(0);
        outputs_ = wanted;
        if (outputs_.empty())
            for (const auto& o : graph.output()) outputs_.push_back(o.name());
        const std::vector<const onnx::NodeProto*> nodes = neededNodes(graph, file);

        // The last node that reads each tensor; the outputs live to the end.
        std::map<std::string, int> readers;
        for (std::size_t k = 0; k < nodes.size(); ++k)
            for (const auto& i : nodes[k]->input()) {
                lastUse_[resolve(i)] = k;
                ++readers[resolve(i)];
            }
        for (const auto& o : outputs_) lastUse_[resolve(o)] = std::numeric_limits<std::size_t>::max();

        planInput(graph);
        std::set<const onnx::NodeProto*> folded;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
            const onnx::NodeProto& node = *nodes[k];
            if (folded.count(&node)) continue;
            std::vector<std::string> inputs;
            for (const auto& i : node.input()) inputs.push_back(i.empty() ? i : resolve(i));
            // A Clip or Relu that alone reads a convolution's output (not itself an output) bounds it.
            const onnx::NodeProto* activation = nullptr;
            if (node.op_type() == "Conv" && readers[node.output(0)] == 1 &&
                lastUse_[node.output(0)] != std::numeric_limits<std::size_t>::max())
                for (std::size_t j = k + 1; j < nodes.size() && !activation; ++j)
                    if ((nodes[j]->op_type() == "Clip" || nodes[j]->op_type() == "Relu") &&
                        resolve(nodes[j]->input(0)) == node.output(0))
                        activation = nodes[j];
            plan(node, inputs, activation);
            if (activation) folded.insert(activation);
            for (const auto& i : inputs) {
                release(i, k);
                release(i + kAsImage, k);
                release(i + kAsPlain, k);
            }
        }
        for (const auto& o : outputs_) {
            const std::string name = resolve(o);
            if (!values_.count(name)) materializeConstant(name);
            resolvedOutputs_.push_back(name);
        }
        constants_.clear();
        // The graphs planned after this one into the same arena may use its tensors' buffers: it runs alone.
        for (const std::size_t b : leases_.tensors) leases_.arena->release(b);
        leases_.planned = true;
    }

    std::vector<cv::Mat> run(const cv::Mat& blob) override {
        if (blob.dims != 4 || blob.type() != CV_32F ||
            !std::equal(inputShape_.begin(), inputShape_.end(), blob.size.p,
                        [](std::int64_t a, int b) { return a == b; }))
            throw Error(ErrorKind::Input, fmt::format("the model takes a {} x {} x {} x {} float blob", inputShape_[0],
                                                      inputShape_[1], inputShape_[2], inputShape_[3]));
        toNhwc(blob.ptr<float>(), leases_.arena->data(inputBuffer_), inputShape_);
        for (auto& step : steps_) step();
        std::vector<cv::Mat> results;
        for (const auto& name : resolvedOutputs_) {
            const Value& v = values_.at(name);
            std::vector<int> sizes(v.shape.begin(), v.shape.end());
            if (sizes.empty()) sizes.push_back(1);
            if (sizes.size() == 1) sizes.insert(sizes.begin(), 1);
            cv::Mat out(static_cast<int>(sizes.size()), sizes.data(), CV_32F);
            const float* data = leases_.arena->data(v.buffer);
            if (v.layout == Layout::Image)
                toNchw(data, out.ptr<float>(), v.shape);
            else
                std::memcpy(out.ptr<float>(), data, sizeof(float) * out.total());
            results.push_back(std::move(out));
        }
        return results;
    }

    const std::vector<std::string>& outputs() const override { return outputs_; }
    std::vector<int> inputShape() const override { return {inputShape_.begin(), inputShape_.end()}; }
    std::string_view engine() const override { return "XNNPACK"; }

private:
    // The graph's initializers and Constant nodes.
    void readConstants(const onnx::GraphProto& graph) {
        for (const auto& t : graph.initializer()) constants_[t.name()] = constantOf(t);
        for (const auto& n : graph.node())
            if (n.op_type() == "Constant") {
                const auto* value = attribute(n, "value");
                if (!value || !value->has_t()) throw Unsupported{"a Constant without a tensor value"};
                constants_[n.output(0)] = constantOf(value->t());
            }
    }

    // The tensor an Identity's output copies (the name itself when none does).
    std::string resolve(std::string name) const {
        for (auto it = same_.find(name); it != same_.end(); it = same_.find(name)) name = it->second;
        return name;
    }

    // The nodes the outputs need, in the graph's (topological) order, Identity's left out.
    std::vector<const onnx::NodeProto*> neededNodes(const onnx::GraphProto& graph, const std::string& file) const {
        std::map<std::string, const onnx::NodeProto*> producer;
        for (const auto& n : graph.node())
            for (const auto& o : n.output()) producer[o] = &n;
        std::set<const onnx::NodeProto*> needed;
        std::vector<std::string> open;
        for (const auto& o : outputs_) {
            if (!producer.count(o) && !constants_.count(o))
                throw Error(ErrorKind::Input, fmt::format("{}: the graph has no output '{}'", file, o));
            open.push_back(resolve(o));
        }
        while (!open.empty()) {
            const std::string name = open.back();
            open.pop_back();
            auto p = producer.find(name);
            if (p == producer.end() || p->second->op_type() == "Constant" || !needed.insert(p->second).second) continue;
            for (const auto& i : p->second->input())
                if (!i.empty()) open.push_back(resolve(i));
        }
        std::vector<const onnx::NodeProto*> nodes;
        for (const auto& n : graph.node())
            if (needed.count(&n) && n.op_type() != "Identity") {
                if (n.input_size() < 1 || n.output_size() < 1 || n.input(0).empty())
                    throw Unsupported{fmt::format("the node '{}' without an input or an output", n.name())};
                nodes.push_back(&n);
            }
        return nodes;
    }

    // The one input, an image of a size the graph fixes.
    void planInput(const onnx::GraphProto& graph) {
        for (const auto& i : graph.input()) {
            if (constants_.count(i.name())) continue;
            if (!input_.empty()) throw Unsupported{"more than one input"};
            input_ = i.name();
            for (const auto& d : i.type().tensor_type().shape().dim()) {
                if (!d.has_dim_value() || d.dim_value() <= 0)
                    throw Unsupported{fmt::format("the input '{}' has a size not fixed in the graph", i.name())};
                inputShape_.push_back(d.dim_value());
            }
        }
        if (inputShape_.size() != 4) throw Unsupported{"an input that is not an N x C x H x W image"};
        inputBuffer_ = acquire(elements(inputShape_));
        values_[input_] = Value{inputShape_, Layout::Image, inputBuffer_};
    }

    // The smallest free buffer of the arena that holds n floats, or a new one. A constant's is always new
    // and kept while the graph lives: the steps before it would overwrite a shared one.
    std::size_t acquire(std::int64_t n, bool shared = true) {
        if (n < 0 || n > kMaxPlannedFloats - planned_)
            throw Unsupported{
                fmt::format("tensors of more than {} MiB together", kMaxPlannedFloats * sizeof(float) >> 20)};
        TensorArena& arena = *leases_.arena;
        const std::size_t before = arena.floats();
        const std::size_t buffer = arena.acquire(static_cast<std::size_t>(n), /*reuse=*/shared);
        planned_ += static_cast<std::int64_t>(arena.floats() - before);
        (shared ? leases_.tensors : leases_.constants).push_back(buffer);
        return buffer;
    }
    void release(const std::string& name, std::size_t node) {
        auto use = lastUse_.find(name);
        auto v = values_.find(name);
        if (use == lastUse_.end() || use->second != node || v == values_.end() || constantBuffers_.count(name)) return;
        leases_.arena->release(v->second.buffer);
        values_.erase(v);
    }
    float* data(const Value& v) { return leases_.arena->data(v.buffer); }

    // A constant read as a tensor (a Mul's factor): a buffer of its own, never shared.
    const Value& materializeConstant(const std::string& name) {
        const Constant& c = constant(name);
        if (c.floats.empty()) throw Unsupported{fmt::format("the integer constant '{}' read as a tensor", name)};
        Value v{c.shape, Layout::Plain, acquire(static_cast<std::int64_t>(c.floats.size()), /*shared=*/false)};
        std::copy(c.floats.begin(), c.floats.end(), data(v));
        constantBuffers_.insert(name);
        return values_[name] = v;
    }
    const Constant& constant(const std::string& name) const {
        auto c = constants_.find(name);
        if (c == constants_.end()) throw Unsupported{fmt::format("'{}' is not a constant of the graph", name)};
        return c->second;
    }
    Value input(const std::string& name) {
        auto v = values_.find(name);
        if (v != values_.end()) return v->second;
        if (constants_.count(name)) return materializeConstant(name);
        throw Unsupported{fmt::format("the tensor '{}' is made by nothing planned", name)};
    }
    Value output(const std::string& name, Shape shape, Layout layout) {
        return values_[name] = Value{shape, layout, acquire(elements(shape))};
    }

    static void toNhwc(const float* nchw, float* nhwc, const Shape& s) {
        const std::int64_t c = s[1], hw = s[2] * s[3];
        for (std::int64_t n = 0; n < s[0]; ++n)
            for (std::int64_t k = 0; k < c; ++k)
                for (std::int64_t p = 0; p < hw; ++p) nhwc[(n * hw + p) * c + k] = nchw[(n * c + k) * hw + p];
    }
    static void toNchw(const float* nhwc, float* nchw, const Shape& s) {
        const std::int64_t c = s[1], hw = s[2] * s[3];
        for (std::int64_t n = 0; n < s[0]; ++n)
            for (std::int64_t p = 0; p < hw; ++p)
                for (std::int64_t k = 0; k < c; ++k) nchw[(n * c + k) * hw + p] = nhwc[(n * hw + p) * c + k];
    }

    // The tensor in the layout an operator takes: converted by a step of its own when it is not, the copy
    // kept as long as the tensor for the other nodes that read it so.
    Value asImage(const std::string& name) { return inLayout(name, Layout::Image); }
    Value asPlain(const std::string& name) { return inLayout(name, Layout::Plain); }
    Value inLayout(const std::string& name, Layout layout) {
        const Value v = input(name);
        if (v.layout == layout) return v;
        if (layout == Layout::Image && v.shape.size() != 4)
            throw Unsupported{fmt::format("'{}' is not 4-d where an image is read", name)};
        const std::string copyName = name + (layout == Layout::Image ? kAsImage : kAsPlain);
        if (auto copy = values_.find(copyName); copy != values_.end()) return copy->second;
        const Value copy = output(copyName, v.shape, layout);
        const auto convert = layout == Layout::Image ? toNhwc : toNchw;
        steps_.push_back([this, v, copy, convert] { convert(data(v), data(copy), v.shape); });
        lastUse_[copyName] = lastUse_[name];
        return copy;
    }

    void add(Operator op) { operators_.push_back(std::move(op)); }
    void run(xnn_operator_t op) {
        steps_.push_back([this, op] {
            if (xnn_run_operator(op, pool_.get()) != xnn_status_success)
                throw Error(ErrorKind::Input, "an XNNPACK operator of the model failed to run");
        });
    }

    // A node as its planner reads it: its inputs' names (an Identity's resolved), the Clip or Relu folded
    // into it, and the name its output takes (the activation's, when one is folded).
    struct NodeToPlan {
        const onnx::NodeProto& node;
        const std::vector<std::string>& inputs;
        const onnx::NodeProto* activation;
        const std::string& out;
    };
    using Planner = void (XnnpackNetwork::*)(const NodeToPlan&);
    // The operators the plan knows (network.hpp lists them), each with its planner.
    static const std::map<std::string_view, Planner>& planners() {
        static const std::map<std::string_view, Planner> table{
            {"Conv", &XnnpackNetwork::planConv},
            {"Clip", &XnnpackNetwork::planClamp},
            {"Relu", &XnnpackNetwork::planClamp},
            {"LeakyRelu", &XnnpackNetwork::planUnary},
            {"Sigmoid", &XnnpackNetwork::planUnary},
            {"Exp", &XnnpackNetwork::planUnary},
            {"MaxPool", &XnnpackNetwork::planMaxPool},
            {"GlobalAveragePool", &XnnpackNetwork::planGlobalAveragePool},
            {"Resize", &XnnpackNetwork::planResize},
            {"Upsample", &XnnpackNetwork::planResize},
            {"Add", &XnnpackNetwork::planBinary},
            {"Sub", &XnnpackNetwork::planBinary},
            {"Mul", &XnnpackNetwork::planBinary},
            {"Concat", &XnnpackNetwork::planConcat},
            {"Split", &XnnpackNetwork::planSplit},
            {"Slice", &XnnpackNetwork::planSlice},
            {"Reshape", &XnnpackNetwork::planReshape},
            {"Flatten", &XnnpackNetwork::planReshape},
            {"Transpose", &XnnpackNetwork::planTranspose},
        };
        return table;
    }

    void plan(const onnx::NodeProto& node, const std::vector<std::string>& inputs, const onnx::NodeProto* activation) {
        auto planner = planners().find(node.op_type());
        if (planner == planners().end())
            throw Unsupported{fmt::format("the operator {} ('{}')", node.op_type(), node.name())};
        (this->*planner->second)({node, inputs, activation, activation ? activation->output(0) : node.output(0)});
    }

    void planConv(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        const Value x = asImage(inputs.at(0));
        const Constant& w = constant(inputs.at(1));
        if (w.shape.size() != 4 || w.floats.empty())
            throw Unsupported{"a convolution whose weights are not 2-d floats"};
        const std::int64_t groups = intAttribute(node, "group", 1), outC = w.shape[0], groupIn = w.shape[1];
        const std::int64_t kh = w.shape[2], kw = w.shape[3], inC = x.shape[1];
        if (groups < 1 || groupIn * groups != inC || outC % groups)
            throw Unsupported{"a convolution's groups do not fit"};
        const auto strides = intsAttribute(node, "strides", {1, 1}),
                   dilations = intsAttribute(node, "dilations", {1, 1});
        if (strides.size() != 2 || dilations.size() != 2 || *std::min_element(strides.begin(), strides.end()) < 1)
            throw Unsupported{"a convolution's strides or dilations"};
        auto pads = intsAttribute(node, "pads", {0, 0, 0, 0});  // top, left, bottom, right
        const std::string autoPad = stringAttribute(node, "auto_pad", "NOTSET");
        const std::int64_t h = x.shape[2], wd = x.shape[3];
        if (autoPad == "VALID")
            pads = {0, 0, 0, 0};
        else if (autoPad == "SAME_UPPER" || autoPad == "SAME_LOWER") {
            const auto same = [&](std::int64_t size, std::int64_t kernel, std::int64_t stride, std::int64_t dilation) {
                const std::int64_t outSize = (size + stride - 1) / stride;
                return std::max<std::int64_t>(0, (outSize - 1) * stride + (kernel - 1) * dilation + 1 - size);
            };
            const std::int64_t ph = same(h, kh, strides[0], dilations[0]), pw = same(wd, kw, strides[1], dilations[1]);
            const bool upper = autoPad == "SAME_UPPER";
            pads = {upper ? ph / 2 : ph - ph / 2, upper ? pw / 2 : pw - pw / 2, upper ? ph - ph / 2 : ph / 2,
                    upper ? pw - pw / 2 : pw / 2};
        } else if (autoPad != "NOTSET")
            throw Unsupported{"a convolution's auto_pad " + autoPad};
        if (pads.size() != 4) throw Unsupported{"a convolution's pads"};
        const std::int64_t oh = windowExtent(h, pads[0], pads[2], kh, strides[0], dilations[0]);
        const std::int64_t ow = windowExtent(wd, pads[1], pads[3], kw, strides[1], dilations[1]);
        // ONNX's kernel is out x in x h x w; XNNPACK's out x h x w x in.
        std::vector<float> kernel(w.floats.size());
        for (std::int64_t o = 0; o < outC; ++o)
            for (std::int64_t i = 0; i < groupIn; ++i)
                for (std::int64_t y = 0; y < kh; ++y)
                    for (std::int64_t z = 0; z < kw; ++z)
                        kernel[((o * kh + y) * kw + z) * groupIn + i] = w.floats[((o * groupIn + i) * kh + y) * kw + z];
        std::vector<float> bias(static_cast<std::size_t>(outC), 0.f);
        if (inputs.size() > 2 && !inputs[2].empty()) bias = constant(inputs[2]).floats;
        if (static_cast<std::int64_t>(bias.size()) != outC) throw Unsupported{"a convolution's bias"};
        float low = -std::numeric_limits<float>::infinity(), high = std::numeric_limits<float>::infinity();
        if (activation) std::tie(low, high) = clampBounds(*activation);
        xnn_operator_t conv = nullptr;
        check(xnn_create_convolution2d_nhwc_f32(
                  static_cast<std::uint32_t>(pads[0]), static_cast<std::uint32_t>(pads[3]),
                  static_cast<std::uint32_t>(pads[2]), static_cast<std::uint32_t>(pads[1]),
                  static_cast<std::uint32_t>(kh), static_cast<std::uint32_t>(kw),
                  static_cast<std::uint32_t>(strides[0]), static_cast<std::uint32_t>(strides[1]),
                  static_cast<std::uint32_t>(dilations[0]), static_cast<std::uint32_t>(dilations[1]),
                  static_cast<std::uint32_t>(groups), static_cast<std::size_t>(groupIn),
                  static_cast<std::size_t>(outC / groups), static_cast<std::size_t>(inC),
                  static_cast<std::size_t>(outC), kernel.data(), bias.data(), low, high, 0, &conv),
              "a convolution");
        add(Operator(conv));
        const Value y = output(out, {x.shape[0], outC, oh, ow}, Layout::Image);
        check(xnn_setup_convolution2d_nhwc_f32(conv, static_cast<std::size_t>(x.shape[0]), static_cast<std::size_t>(h),
                                               static_cast<std::size_t>(wd), data(x), data(y), pool_.get()),
              "a convolution's tensors");
        run(conv);
    }

    // Clip's bounds (attributes before opset 11, inputs since), or Relu's.
    std::pair<float, float> clampBounds(const onnx::NodeProto& node) const {
        float low = -std::numeric_limits<float>::infinity(), high = std::numeric_limits<float>::infinity();
        if (node.op_type() == "Relu") return {0.f, high};
        low = floatAttribute(node, "min", low);
        high = floatAttribute(node, "max", high);
        const auto bound = [&](int i, float& b) {
            if (node.input_size() > i && !node.input(i).empty()) {
                const Constant& c = constant(node.input(i));
                if (c.floats.size() != 1) throw Unsupported{"a Clip bound that is not one number"};
                b = c.floats[0];
            }
        };
        bound(1, low);
        bound(2, high);
        return {low, high};
    }

    void planClamp(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        const Value x = input(inputs.at(0));
        const auto [low, high] = clampBounds(node);
        xnn_operator_t clamp = nullptr;
        check(xnn_create_clamp_nc_f32(1, 1, 1, low, high, 0, &clamp), "a clamp");
        add(Operator(clamp));
        const Value y = output(out, x.shape, x.layout);
        check(xnn_setup_clamp_nc_f32(clamp, static_cast<std::size_t>(elements(x.shape)), data(x), data(y), pool_.get()),
              "a clamp's tensors");
        run(clamp);
    }

    void planUnary(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        const Value x = input(inputs.at(0));
        const Value y = output(out, x.shape, x.layout);
        const auto n = static_cast<std::size_t>(elements(x.shape));
        xnn_operator_t unary = nullptr;
        if (node.op_type() == "Exp") {
            steps_.push_back([this, x, y, n] {
                const float* in = data(x);
                float* result = data(y);
                for (std::size_t i = 0; i < n; ++i) result[i] = std::exp(in[i]);
            });
            return;
        }
        if (node.op_type() == "LeakyRelu") {
            check(xnn_create_leaky_relu_nc_f32(1, 1, 1, floatAttribute(node, "alpha", 0.01f), 0, &unary),
                  "a leaky ReLU");
            add(Operator(unary));
            check(xnn_setup_leaky_relu_nc_f32(unary, n, data(x), data(y), pool_.get()), "a leaky ReLU's tensors");
        } else {
            check(xnn_create_sigmoid_nc_f32(1, 1, 1, 0, &unary), "a sigmoid");
            add(Operator(unary));
            check(xnn_setup_sigmoid_nc_f32(unary, n, data(x), data(y), pool_.get()), "a sigmoid's tensors");
        }
        run(unary);
    }

    void planMaxPool(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        const Value x = asImage(inputs.at(0));
        const auto kernel = intsAttribute(node, "kernel_shape"), strides = intsAttribute(node, "strides", {1, 1});
        const auto pads = intsAttribute(node, "pads", {0, 0, 0, 0}),
                   dilations = intsAttribute(node, "dilations", {1, 1});
        if (kernel.size() != 2 || strides.size() != 2 || pads.size() != 4 || dilations.size() != 2 ||
            intAttribute(node, "ceil_mode", 0) != 0 || stringAttribute(node, "auto_pad", "NOTSET") != "NOTSET" ||
            node.output_size() > 1)
            throw Unsupported{"a max pooling other than 2-d, explicitly padded, rounding down"};
        const std::int64_t oh = windowExtent(x.shape[2], pads[0], pads[2], kernel[0], strides[0], dilations[0]);
        const std::int64_t ow = windowExtent(x.shape[3], pads[1], pads[3], kernel[1], strides[1], dilations[1]);
        const auto channels = static_cast<std::size_t>(x.shape[1]);
        xnn_operator_t pool = nullptr;
        check(
            xnn_create_max_pooling2d_nhwc_f32(
                static_cast<std::uint32_t>(pads[0]), static_cast<std::uint32_t>(pads[3]),
                static_cast<std::uint32_t>(pads[2]), static_cast<std::uint32_t>(pads[1]),
                static_cast<std::uint32_t>(kernel[0]), static_cast<std::uint32_t>(kernel[1]),
                static_cast<std::uint32_t>(strides[0]), static_cast<std::uint32_t>(strides[1]),
                static_cast<std::uint32_t>(dilations[0]), static_cast<std::uint32_t>(dilations[1]), channels, channels,
                channels, -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(), 0, &pool),
            "a max pooling");
        add(Operator(pool));
        const Value y = output(out, {x.shape[0], x.shape[1], oh, ow}, Layout::Image);
        check(xnn_setup_max_pooling2d_nhwc_f32(pool, static_cast<std::size_t>(x.shape[0]),
                                               static_cast<std::size_t>(x.shape[2]),
                                               static_cast<std::size_t>(x.shape[3]), data(x), data(y), pool_.get()),
              "a max pooling's tensors");
        run(pool);
    }

    void planGlobalAveragePool(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        const Value x = asImage(inputs.at(0));
        const auto channels = static_cast<std::size_t>(x.shape[1]);
        xnn_operator_t pool = nullptr;
        check(xnn_create_global_average_pooling_nwc_f32(channels, channels, channels,
                                                        -std::numeric_limits<float>::infinity(),
                                                        std::numeric_limits<float>::infinity(), 0, &pool),
              "an average pooling");
        add(Operator(pool));
        const Value y = output(out, {x.shape[0], x.shape[1], 1, 1}, Layout::Image);
        check(xnn_setup_global_average_pooling_nwc_f32(pool, static_cast<std::size_t>(x.shape[0]),
                                                       static_cast<std::size_t>(x.shape[2] * x.shape[3]), data(x),
                                                       data(y), pool_.get()),
              "an average pooling's tensors");
        run(pool);
    }

    // The output's size from `sizes`, else from `scales` (opset 11 on: X, roi, scales, sizes; before: X, scales).
    void planResize(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        const Value x = asImage(inputs.at(0));
        const std::size_t scalesAt = opset_ >= 11 && node.op_type() == "Resize" ? 2 : 1;
        Shape shape;
        std::vector<double> scale;  // output over input, a dimension
        if (inputs.size() > 3 && !inputs[3].empty() && !constant(inputs[3]).integers.empty()) {
            shape = constant(inputs[3]).integers;
            for (std::size_t d = 0; d < shape.size() && d < 4; ++d) scale.push_back(double(shape[d]) / x.shape[d]);
        } else if (inputs.size() > scalesAt && !inputs[scalesAt].empty()) {
            const Constant& scales = constant(inputs[scalesAt]);
            if (scales.floats.size() != 4) throw Unsupported{"a resize's scales"};
            for (std::size_t d = 0; d < 4; ++d) {
                const double size = std::floor(double(x.shape[d]) * scales.floats[d]);
                if (!(scales.floats[d] > 0) || !(size < double(kMaxPlannedFloats)))  // NaN and infinities too
                    throw Unsupported{"a resize's scales"};
                scale.push_back(scales.floats[d]);
                shape.push_back(static_cast<std::int64_t>(size));
            }
        }
        if (shape.size() != 4 || shape[0] != x.shape[0] || shape[1] != x.shape[1] || shape[2] < 1 || shape[3] < 1 ||
            std::any_of(scale.begin(), scale.end(), [](double f) { return !(f > 0); }))
            throw Unsupported{"a resize other than of an image's height and width to a size of its own"};
        const std::string mode = stringAttribute(node, "mode", "nearest");
        const std::string transform =
            stringAttribute(node, "coordinate_transformation_mode", opset_ >= 11 ? "half_pixel" : "asymmetric");
        const Value y = output(out, shape, Layout::Image);
        if (mode == "linear") {
            std::uint32_t flags = 0;
            if (transform == "align_corners")
                flags = XNN_FLAG_ALIGN_CORNERS;
            else if (transform == "asymmetric")
                flags = XNN_FLAG_TENSORFLOW_LEGACY_MODE;
            else if (!(transform == "half_pixel" ||
                       (transform == "pytorch_half_pixel" && shape[2] > 1 && shape[3] > 1)))
                throw Unsupported{"a linear resize's coordinates " + transform};
            const auto channels = static_cast<std::size_t>(x.shape[1]);
            xnn_operator_t resize = nullptr;
            check(xnn_create_resize_bilinear2d_nhwc_f32(channels, channels, channels, flags, &resize), "a resize");
            add(Operator(resize));
            check(xnn_setup_resize_bilinear2d_nhwc_f32(
                      resize, static_cast<std::size_t>(x.shape[0]), static_cast<std::size_t>(x.shape[2]),
                      static_cast<std::size_t>(x.shape[3]), static_cast<std::size_t>(shape[2]),
                      static_cast<std::size_t>(shape[3]), data(x), data(y), pool_.get()),
                  "a resize's tensors");
            run(resize);
            return;
        }
        if (mode != "nearest") throw Unsupported{"a resize of mode " + mode};
        // Each output row and column's source, as ONNX defines them.
        const std::string rounding =
            stringAttribute(node, "nearest_mode", opset_ >= 11 ? "round_prefer_floor" : "floor");
        const auto sources = [&](std::int64_t in, std::int64_t outSize, double scale) {
            std::vector<std::int64_t> from(static_cast<std::size_t>(outSize));
            for (std::int64_t i = 0; i < outSize; ++i) {
                double at = 0;
                if (transform == "asymmetric")
                    at = i / scale;
                else if (transform == "half_pixel")
                    at = (i + 0.5) / scale - 0.5;
                else if (transform == "pytorch_half_pixel")
                    at = outSize > 1 ? (i + 0.5) / scale - 0.5 : 0;
                else if (transform == "align_corners")
                    at = outSize > 1 ? i * double(in - 1) / double(outSize - 1) : 0;
                else
                    throw Unsupported{"a nearest resize's coordinates " + transform};
                double picked = 0;
                if (rounding == "floor")
                    picked = std::floor(at);
                else if (rounding == "ceil")
                    picked = std::ceil(at);
                else if (rounding == "round_prefer_ceil")
                    picked = std::floor(at + 0.5);
                else if (rounding == "round_prefer_floor")
                    picked = std::ceil(at - 0.5);
                else
                    throw Unsupported{"a nearest resize's rounding " + rounding};
                from[static_cast<std::size_t>(i)] =
                    std::clamp<std::int64_t>(static_cast<std::int64_t>(picked), 0, in - 1);
            }
            return from;
        };
        const auto rows = sources(x.shape[2], shape[2], scale[2]), columns = sources(x.shape[3], shape[3], scale[3]);
        steps_.push_back([this, x, y, rows, columns] {
            const std::int64_t c = x.shape[1];
            const float* in = data(x);
            float* result = data(y);
            for (std::int64_t n = 0; n < x.shape[0]; ++n)
                for (std::size_t r = 0; r < rows.size(); ++r)
                    for (std::size_t q = 0; q < columns.size(); ++q)
                        std::memcpy(result + ((n * y.shape[2] + std::int64_t(r)) * y.shape[3] + std::int64_t(q)) * c,
                                    in + ((n * x.shape[2] + rows[r]) * x.shape[3] + columns[q]) * c,
                                    sizeof(float) * static_cast<std::size_t>(c));
        });
    }

    void planBinary(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        Value a = input(inputs.at(0)), b = input(inputs.at(1));
        std::vector<std::size_t> shapeA, shapeB;
        Shape result;
        Layout layout = Layout::Plain;
        if (a.layout == Layout::Image && b.layout == Layout::Image && a.shape == b.shape) {
            layout = Layout::Image;
            result = a.shape;
            shapeA = shapeB = {std::size_t(a.shape[0]), std::size_t(a.shape[2]), std::size_t(a.shape[3]),
                               std::size_t(a.shape[1])};
        } else {
            a = asPlain(inputs[0]);
            b = asPlain(inputs[1]);
            shapeA.assign(a.shape.begin(), a.shape.end());
            shapeB.assign(b.shape.begin(), b.shape.end());
            // numpy's broadcasting, from the last dimension
            const std::size_t rank = std::max(a.shape.size(), b.shape.size());
            result.assign(rank, 1);
            for (std::size_t d = 0; d < rank; ++d) {
                const std::int64_t da = d < a.shape.size() ? a.shape[a.shape.size() - 1 - d] : 1;
                const std::int64_t db = d < b.shape.size() ? b.shape[b.shape.size() - 1 - d] : 1;
                if (da != db && da != 1 && db != 1) throw Unsupported{"operands that do not broadcast"};
                result[rank - 1 - d] = std::max(da, db);
            }
            if (rank > XNN_MAX_TENSOR_DIMS) throw Unsupported{"operands of more than 6 dimensions"};
        }
        const float inf = std::numeric_limits<float>::infinity();
        xnn_operator_t binary = nullptr;
        const std::string& op = node.op_type();
        if (op == "Add")
            check(xnn_create_add_nd_f32(-inf, inf, 0, &binary), "an addition");
        else if (op == "Sub")
            check(xnn_create_subtract_nd_f32(-inf, inf, 0, &binary), "a subtraction");
        else
            check(xnn_create_multiply_nd_f32(-inf, inf, 0, &binary), "a multiplication");
        add(Operator(binary));
        const Value y = output(out, result, layout);
        const auto setup = op == "Add"   ? xnn_setup_add_nd_f32
                           : op == "Sub" ? xnn_setup_subtract_nd_f32
                                         : xnn_setup_multiply_nd_f32;
        check(setup(binary, shapeA.size(), shapeA.data(), shapeB.size(), shapeB.data(), data(a), data(b), data(y),
                    pool_.get()),
              "an element-wise operation's tensors");
        run(binary);
    }

    static std::size_t axisOf(std::int64_t axis, std::size_t rank) {
        if (axis < 0) axis += static_cast<std::int64_t>(rank);
        if (axis < 0 || axis >= static_cast<std::int64_t>(rank)) throw Unsupported{"an axis outside the tensor"};
        return static_cast<std::size_t>(axis);
    }

    // Pieces along an axis, in a plain tensor's terms: outer x (piece's extent x inner) blocks; an image's
    // channels are its innermost, so its channel axis is cut as a plain N*H*W x C tensor's last.
    struct Blocks {
        std::int64_t outer = 1, inner = 1;
    };
    static Blocks blocksAround(const Value& v, std::size_t axis) {
        if (v.layout == Layout::Image) return {v.shape[0] * v.shape[2] * v.shape[3], 1};
        Blocks b;
        for (std::size_t d = 0; d < axis; ++d) b.outer *= v.shape[d];
        for (std::size_t d = axis + 1; d < v.shape.size(); ++d) b.inner *= v.shape[d];
        return b;
    }

    void planConcat(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        std::vector<Value> parts;
        for (const auto& i : inputs) parts.push_back(input(i));
        const std::size_t axis = axisOf(intAttribute(node, "axis", 0), parts.front().shape.size());
        const bool channels = axis == 1 && std::all_of(parts.begin(), parts.end(),
                                                       [](const Value& v) { return v.layout == Layout::Image; });
        if (!channels)
            for (std::size_t p = 0; p < parts.size(); ++p) parts[p] = asPlain(inputs[p]);
        Shape shape = parts.front().shape;
        shape[axis] = 0;
        for (const auto& p : parts) {
            if (p.shape.size() != shape.size()) throw Unsupported{"a concatenation of tensors of different ranks"};
            for (std::size_t d = 0; d < shape.size(); ++d)
                if (d != axis && p.shape[d] != shape[d]) throw Unsupported{"a concatenation of tensors of other sizes"};
            shape[axis] += p.shape[axis];
        }
        const Value y = output(out, shape, channels ? Layout::Image : Layout::Plain);
        steps_.push_back([this, parts, y, axis] {
            const Blocks blocks = blocksAround(y, axis);
            const std::int64_t total = y.shape[axis] * blocks.inner;
            std::int64_t offset = 0;
            float* result = data(y);
            for (const auto& p : parts) {
                const std::int64_t chunk = p.shape[axis] * blocks.inner;
                const float* in = data(p);
                for (std::int64_t o = 0; o < blocks.outer; ++o)
                    std::memcpy(result + o * total + offset, in + o * chunk, sizeof(float) * std::size_t(chunk));
                offset += chunk;
            }
        });
    }

    // A piece [begin, begin + extent) of `x` along `axis` into a tensor of its own.
    void planPiece(const Value& x, std::size_t axis, std::int64_t begin, std::int64_t extent, const std::string& out) {
        Shape shape = x.shape;
        shape[axis] = extent;
        const Value y = output(out, shape, x.layout);
        steps_.push_back([this, x, y, axis, begin, extent] {
            const Blocks blocks = blocksAround(x, axis);
            const std::int64_t total = x.shape[axis] * blocks.inner, chunk = extent * blocks.inner;
            const float* in = data(x) + begin * blocks.inner;
            float* result = data(y);
            for (std::int64_t o = 0; o < blocks.outer; ++o)
                std::memcpy(result + o * chunk, in + o * total, sizeof(float) * std::size_t(chunk));
        });
    }

    void planSplit(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        Value x = input(inputs.at(0));
        const std::size_t axis = axisOf(intAttribute(node, "axis", 0), x.shape.size());
        if (x.layout == Layout::Image && axis != 1) x = asPlain(inputs[0]);
        std::vector<std::int64_t> sizes = intsAttribute(node, "split");
        if (inputs.size() > 1 && !inputs[1].empty()) sizes = constant(inputs[1]).integers;
        if (sizes.empty())
            sizes.assign(static_cast<std::size_t>(node.output_size()), x.shape[axis] / node.output_size());
        if (static_cast<int>(sizes.size()) != node.output_size() ||
            std::any_of(sizes.begin(), sizes.end(), [](std::int64_t size) { return size < 1; }) ||
            std::accumulate(sizes.begin(), sizes.end(), std::int64_t{0}) != x.shape[axis])
            throw Unsupported{"a split whose parts do not add up"};
        std::int64_t begin = 0;
        for (int o = 0; o < node.output_size(); ++o) {
            planPiece(x, axis, begin, sizes[static_cast<std::size_t>(o)], node.output(o));
            begin += sizes[static_cast<std::size_t>(o)];
        }
    }

    void planSlice(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        if (opset_ < 10) throw Unsupported{"a Slice of opset 1 (its bounds as attributes)"};
        Value x = input(inputs.at(0));
        const auto starts = constant(inputs.at(1)).integers, ends = constant(inputs.at(2)).integers;
        std::vector<std::int64_t> axes(starts.size());
        std::iota(axes.begin(), axes.end(), 0);
        if (inputs.size() > 3 && !inputs[3].empty()) axes = constant(inputs[3]).integers;
        if (inputs.size() > 4 && !inputs[4].empty()) {
            const auto steps = constant(inputs[4]).integers;
            if (std::any_of(steps.begin(), steps.end(), [](std::int64_t s) { return s != 1; }))
                throw Unsupported{"a slice with steps"};
        }
        if (axes.size() != 1 || starts.size() != 1 || ends.size() != 1)
            throw Unsupported{"a slice along more than one axis"};
        const std::size_t axis = axisOf(axes[0], x.shape.size());
        if (x.layout == Layout::Image && axis != 1) x = asPlain(inputs[0]);
        const std::int64_t extent = x.shape[axis];
        const auto clampIndex = [&](std::int64_t i) {
            return std::clamp<std::int64_t>(i < 0 ? i + extent : i, 0, extent);
        };
        const std::int64_t begin = clampIndex(starts[0]), end = clampIndex(ends[0]);
        if (end <= begin) throw Unsupported{"an empty slice"};
        planPiece(x, axis, begin, end - begin, out);
    }

    void planReshape(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        const Value x = asPlain(inputs.at(0));
        Shape shape;
        if (node.op_type() == "Flatten") {
            const std::size_t axis = axisOf(intAttribute(node, "axis", 1), x.shape.size() + 1);
            shape = {std::accumulate(x.shape.begin(), x.shape.begin() + std::ptrdiff_t(axis), std::int64_t{1},
                                     std::multiplies<>()),
                     std::accumulate(x.shape.begin() + std::ptrdiff_t(axis), x.shape.end(), std::int64_t{1},
                                     std::multiplies<>())};
        } else {
            shape = constant(inputs.at(1)).integers;
            std::optional<std::size_t> inferred;
            for (std::size_t d = 0; d < shape.size(); ++d) {
                if (shape[d] == 0 && intAttribute(node, "allowzero", 0) == 0 && d < x.shape.size())
                    shape[d] = x.shape[d];
                if (shape[d] == -1 && !inferred) {
                    inferred = d;
                    shape[d] = 1;
                } else if (shape[d] < 1)
                    throw Unsupported{"a reshape to a shape of no size"};
            }
            if (inferred) shape[*inferred] = elements(x.shape) / elements(shape);
        }
        if (elements(shape) != elements(x.shape)) throw Unsupported{"a reshape that changes the count"};
        const Value y = output(out, shape, Layout::Plain);
        const auto n = static_cast<std::size_t>(elements(shape));
        steps_.push_back([this, x, y, n] { std::memcpy(data(y), data(x), sizeof(float) * n); });
    }

    void planTranspose(const NodeToPlan& planned) {
        const auto& [node, inputs, activation, out] = planned;
        Value x = input(inputs.at(0));
        std::vector<std::int64_t> perm = intsAttribute(node, "perm");
        if (perm.empty())
            for (std::size_t d = x.shape.size(); d-- > 0;) perm.push_back(static_cast<std::int64_t>(d));
        std::vector<std::int64_t> sorted = perm;
        std::sort(sorted.begin(), sorted.end());
        for (std::size_t d = 0; d < sorted.size(); ++d)
            if (sorted[d] != static_cast<std::int64_t>(d) || perm.size() != x.shape.size())
                throw Unsupported{"a transpose whose permutation is not one of its axes"};
        Shape shape;
        for (auto p : perm) shape.push_back(x.shape.at(axisOf(p, x.shape.size())));
        // An image to N x H x W x C is the layout it is kept in.
        if (x.layout == Layout::Image && perm == std::vector<std::int64_t>{0, 2, 3, 1}) {
            const Value y = output(out, shape, Layout::Plain);
            const auto n = static_cast<std::size_t>(elements(shape));
            steps_.push_back([this, x, y, n] { std::memcpy(data(y), data(x), sizeof(float) * n); });
            return;
        }
        x = asPlain(inputs[0]);
        const Value y = output(out, shape, Layout::Plain);
        steps_.push_back([this, x, y, perm] {
            const std::size_t rank = x.shape.size();
            std::vector<std::int64_t> stride(rank, 1);  // of x
            for (std::size_t d = rank - 1; d-- > 0;) stride[d] = stride[d + 1] * x.shape[d + 1];
            std::vector<std::int64_t> index(rank, 0);  // in y
            const float* in = data(x);
            float* result = data(y);
            const std::int64_t n = elements(y.shape);
            for (std::int64_t i = 0; i < n; ++i) {
                std::int64_t from = 0;
                for (std::size_t d = 0; d < rank; ++d) from += index[d] * stride[static_cast<std::size_t>(perm[d])];
                result[i] = in[from];
                for (std::size_t d = rank; d-- > 0;) {
                    if (++index[d] < y.shape[d]) break;
                    index[d] = 0;
                }
            }
        });
    }

    std::int64_t opset_ = 1;
    std::map<std::string, Constant> constants_;  // while planning
    std::map<std::string, std::string> same_;    // an Identity's output -> its input
    std::map<std::string, std::size_t> lastUse_;
    std::set<std::string> constantBuffers_;
    std::string input_;
    Shape inputShape_;
    std::vector<std::string> outputs_, resolvedOutputs_;
    std::map<std::string, Value> values_;
    // The arena's buffers this graph holds: its tensors', left to the graphs planned after it once its own
    // plan is done, and its constants', its own while it lives. A plan that fails leaves them all.
    struct Leases {
        std::shared_ptr<TensorArena> arena;
        std::vector<std::size_t> tensors, constants;
        bool planned = false;
        ~Leases() {
            if (!planned)
                for (const std::size_t b : tensors) arena->release(b);
            for (const std::size_t b : constants) arena->release(b);
        }
    };
    Leases leases_;
    std::vector<Operator> operators_;
    std::unique_ptr<pthreadpool, PoolDeleter> pool_;  // null: the calling thread alone
    std::vector<std::function<void()>> steps_;
    std::size_t inputBuffer_ = 0;
    std::int64_t planned_ = 0;  // the floats of the buffers its plan added to the arena
};

class OpenCvNetwork : public Network {
public:
    OpenCvNetwork(const fs::path& model, const std::vector<std::string>& outputs) : outputs_(outputs) {
        try {
            net_ = cv::dnn::readNetFromONNX(model.string());
        } catch (const cv::Exception& e) {
            throw Error(ErrorKind::Input, fmt::format("{}: not a model OpenCV can load: {}", model.string(), e.msg),
                        std::nullopt, "prepare it with scripts/detector/setup.sh");
        }
        net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
        net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
        if (outputs_.empty())
            for (const auto& name : net_.getUnconnectedOutLayersNames()) outputs_.push_back(name);
        // OpenCV runs every layer numbered up to the one asked for; an output that is an Identity is asked
        // for by the layer it copies, so that layers numbered between them (DeepLab's full-size upsampling,
        // which its other output needs) do not run.
        for (const auto& name : outputs_) {
            const int id = net_.getLayerId(name);
            if (id < 0) throw Error(ErrorKind::Input, fmt::format("{}: has no output '{}'", model.string(), name));
            const std::vector<cv::Ptr<cv::dnn::Layer>> inputs = net_.getLayerInputs(id);
            producers_.push_back(net_.getLayer(id)->type == "Identity" && inputs.size() == 1 ? inputs.front()->name
                                                                                             : name);
        }
    }

    std::vector<cv::Mat> run(const cv::Mat& blob) override {
        net_.setInput(blob);
        std::vector<cv::Mat> results;
        net_.forward(results, producers_);
        for (auto& r : results) r = r.clone();
        return results;
    }
    const std::vector<std::string>& outputs() const override { return outputs_; }
    std::vector<int> inputShape() const override { return {}; }
    std::string_view engine() const override { return "OpenCV DNN"; }

private:
    cv::dnn::Net net_;
    std::vector<std::string> outputs_;
    std::vector<cv::String> producers_;
};

}  // namespace

// Buffers this large or larger are pages of their own, in 2 MiB pages where the kernel has them (madvise;
// a 4 KiB page's first touch costs about 11 us on a virtual machine like the one docs/benchmarks.md was
// measured on, and a stream's tensors are 42 MB), zeroed by the kernel as new[]() zeroes the others.
constexpr std::size_t kHugePage = std::size_t{2} << 20;

void detail::TensorPages::operator()(float* data) const {
    if (bytes == 0)
        delete[] data;
    else
        munmap(data, bytes);
}

std::size_t TensorArena::acquire(std::size_t n, bool reuse) {
    std::optional<std::size_t> best;
    for (std::size_t b = 0; b < buffers_.size() && reuse; ++b)
        if (buffers_[b].free && buffers_[b].size >= n && (!best || buffers_[b].size < buffers_[*best].size)) best = b;
    if (best) {
        buffers_[*best].free = false;
        return *best;
    }
    Buffer buffer;
    buffer.size = n;
    const std::size_t floats = n + XNN_EXTRA_BYTES / sizeof(float), bytes = floats * sizeof(float);
    if (bytes < kHugePage) {
        buffer.data.reset(new float[floats]());
    } else {
        void* pages = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (pages == MAP_FAILED) throw std::bad_alloc();
        madvise(pages, bytes, MADV_HUGEPAGE);  // a hint: without it, 4 KiB pages
        buffer.data = std::unique_ptr<float[], detail::TensorPages>(static_cast<float*>(pages), {bytes});
    }
    buffers_.push_back(std::move(buffer));
    floats_ += n;
    return buffers_.size() - 1;
}

std::unique_ptr<Network> loadXnnpackNetwork(const fs::path& model, const std::vector<std::string>& outputs,
                                            std::string* whyNot, const GraphPlacement& placement) {
    const auto refuse = [&](std::string why) -> std::unique_ptr<Network> {
        if (whyNot) *whyNot = std::move(why);
        return nullptr;
    };
    if (!xnnpackReady()) return refuse("XNNPACK does not support this processor");
    onnx::ModelProto proto;
    std::ifstream in(model, std::ios::binary);
    if (!in || !proto.ParseFromIstream(&in)) return refuse(fmt::format("{}: not an ONNX graph", model.string()));
    try {
        return std::make_unique<XnnpackNetwork>(proto, model.string(), outputs, placement);
    } catch (const Unsupported& u) {
        return refuse(u.why);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {  // std::out_of_range
        return refuse(fmt::format("a node without the inputs its operator takes ({})", e.what()));
    }
}

std::unique_ptr<Network> loadOpenCvNetwork(const fs::path& model, const std::vector<std::string>& outputs) {
    return std::make_unique<OpenCvNetwork>(model, outputs);
}

std::unique_ptr<Network> loadNetwork(const fs::path& model, const std::vector<std::string>& outputs,
                                     const GraphPlacement& placement) {
    if (auto network = loadXnnpackNetwork(model, outputs, nullptr, placement)) return network;
    return loadOpenCvNetwork(model, outputs);
}

}  // namespace smql::ingest
