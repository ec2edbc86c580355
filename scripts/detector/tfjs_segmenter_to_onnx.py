#!/usr/bin/python3
"""Converts the DeepLab v3 (MobileNetV2, PASCAL VOC) TF.js graph model of the
npm package @codait/max-image-segmenter into ONNX for OpenCV's DNN module
(4.6), at a fixed input size.

The TF.js graph is a frozen TensorFlow graph (NHWC). It takes a uint8 image
[1,H,W,3] (RGB, H and W at most 513), normalises it to x/127.5 - 1, pads it to
513x513 (with 127.5, so 0 once normalised), runs the network at output stride 8
(65x65 features), resizes the logits back to 513x513 (bilinear, aligned
corners), takes the arg max and crops it to HxW. The ONNX graph keeps the
network and the logits' resize; the normalisation, the padding and the arg
max are left to the caller. At input height H and width W (the SIZE argument,
S for SxS or HxW) and output stride OS:

  input   "image"          float32 [1,3,H,W], NCHW, RGB, value = pixel/127.5 - 1
                           (OpenCV: blobFromImage(bgr, 1/127.5, Size(W,H),
                           Scalar(127.5,127.5,127.5), swapRB=true, crop=false))
  output  "logits"         float32 [1,21,H,W], per-class scores (before the arg
                           max, no softmax), bilinear with aligned corners from
                           the network's grid, as the TF graph does
  output  "logits_lowres"  float32 [1,21,(H-1)/OS+1,(W-1)/OS+1], the network's
                           own grid (cell (i,j) is input pixel (OS*i, OS*j))

H and W must be OS*k+1 (513, 385, 321, 257, ...): then every stride-2 layer
pads symmetrically as TensorFlow's SAME padding does, and the final resize is
an exact transposed convolution. At another size than 513x513 the constant
sizes of the graph (image pooling's window, the resize targets) follow the
size: it is the same network on a differently sized image, without the TF
graph's padding to 513x513.

OUTPUT_STRIDE is 8 by default, as the TF graph runs. 16 runs the same weights
at output stride 16, DeepLab's other setting: MobileNetV2's block 6 gets its
stride of 2 back and the atrous rates are halved (blocks 7-13 plain, 14-16
rate 2), which takes about 4 times fewer operations in blocks 7-16 (and
OpenCV 4.6's dilated depthwise convolutions are slow) at some loss of detail:
verify_segmenter.py measures it against the TF.js graph.

Mapping: SpaceToBatchND + convolution + BatchToSpaceND (atrous convolution)
become one dilated Conv; each batch norm (Mul/Add by constants, also after an
AddN of a residual) is folded into its convolution's weights and bias; Relu6
becomes Clip with min/max attributes (opset 10: OpenCV 4.6 rejects Clip with
min/max inputs, and takes the attribute form as its ReLU6 layer); the resize of
the 1x1 image pooling back to the feature grid is a nearest Resize (a
broadcast); the aligned-corners resize of the logits is a depthwise
ConvTranspose with a bilinear kernel (opset 10's Resize cannot align corners).

Usage: tfjs_segmenter_to_onnx.py MODEL.json OUT.onnx [SIZE [OUTPUT_STRIDE]]
       (SIZE: S or HxW, default 513; OUTPUT_STRIDE: 8 or 16, default 8)
"""
import json
import os
import sys
from collections import deque

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tfjs_to_onnx import load_weights, node_attr  # noqa: E402  (the shared TF.js graph readers)

NATIVE_SIZE = 513  # the crop size the TF graph was exported at; its constant sizes are for it
NATIVE_STRIDE = 8  # and its output stride
OPSET = 10


class Value:
    """A dynamic tensor of the TF graph as the ONNX graph holds it: ONNX name,
    NCHW shape, and what the folding of constants into convolutions needs."""

    def __init__(self, name, shape, conv=None, terms=None):
        self.name, self.shape = name, list(shape)
        self.conv = conv  # the Conv record whose output this is, while its bias can still change
        self.terms = terms  # for a sum: the summands that are used by nothing else


class Conv:
    """A convolution's weights and bias, still open to folding; made initializers at the end."""

    def __init__(self, name, weight, bias):
        self.name, self.weight, self.bias = name, weight, bias


class Converter:
    def __init__(self, model_path, size, output_stride=NATIVE_STRIDE):
        if output_stride not in (8, 16):
            raise SystemExit(f"output stride {output_stride}: it must be 8 or 16")
        if any(s <= output_stride or (s - 1) % output_stride for s in size):
            raise SystemExit(f"input size {size}: height and width must be {output_stride}k+1 at output stride "
                             f"{output_stride} (513, 385, 321, 257, ...)")
        self.size = list(size)  # height, width
        self.output_stride = output_stride
        self.strided = None  # at output stride 16, the convolution that strides again
        model = json.load(open(model_path))
        self.nodes = {n["name"]: n for n in model["modelTopology"]["node"]}
        self.weights = load_weights(model_path, model)
        self.consumers = {}
        for node in self.nodes.values():
            for ref in node.get("input", []):
                self.consumers.setdefault(self.source(ref), []).append(node["name"])
        self.values = {}  # TF name -> Value
        self.onnx_nodes, self.convs, self.initializers = [], [], []

    # -- helpers ----------------------------------------------------------
    @staticmethod
    def source(ref):
        if ref.startswith("^"):
            raise SystemExit(f"control input {ref} is not supported")
        return ref[:-2] if ref.endswith(":0") else ref

    def inputs(self, node):
        return [self.source(r) for r in node.get("input", [])]

    attr = staticmethod(node_attr)

    def const(self, name):
        node = self.nodes[name]
        if node["op"] != "Const":
            raise SystemExit(f"{name}: a constant was expected, found {node['op']}")
        return self.weights[name]

    def single_use(self, name):
        return len(self.consumers.get(name, [])) == 1

    def initializer(self, name, value):
        self.initializers.append(numpy_helper.from_array(np.ascontiguousarray(value), name))
        return name

    def emit(self, op, inputs, output, **attrs):
        self.onnx_nodes.append(helper.make_node(op, inputs, [output], name=output, **attrs))
        return output

    def scaled(self, native, axis):
        """A constant spatial size of the graph (axis 0: height, 1: width): the image's or the
        features' at NATIVE_SIZE and NATIVE_STRIDE, here the image's or the features' at this size and
        output stride."""
        if native == NATIVE_SIZE:
            return self.size[axis]
        if native == (NATIVE_SIZE - 1) // NATIVE_STRIDE + 1:
            return (self.size[axis] - 1) // self.output_stride + 1
        raise SystemExit(f"a constant size {native} that is neither the image's nor the features'")

    # -- the graph ----------------------------------------------------------
    def ancestors(self, name):
        seen, todo = set(), [name]
        while todo:
            n = todo.pop()
            if n not in seen:
                seen.add(n)
                todo.extend(self.inputs(self.nodes[n]))
        return seen

    def image_node(self):
        """The normalised image: the input of the first convolution. Checks
        that the pre-processing before it is x * (1/127.5) - 1 of the (padded)
        uint8 image, which the caller then does."""
        first = next(n for n in self.order() if n["op"] == "Conv2D")
        image = self.inputs(first)[0]
        sub = self.nodes[image]
        if sub["op"] != "Sub":
            raise SystemExit(f"{image}: the first convolution's input is not x*a - b")
        mul, one = self.inputs(sub)
        scale = [self.const(i) for i in self.inputs(self.nodes[mul]) if self.nodes[i]["op"] == "Const"]
        if (self.nodes[mul]["op"] != "Mul" or len(scale) != 1 or abs(float(scale[0]) - 1 / 127.5) > 1e-7
                or float(self.const(one)) != 1.0):
            raise SystemExit(f"{image}: the pre-processing is not x/127.5 - 1")
        return image

    def restride(self):
        """At output stride 16: the stride-1 depthwise convolution just before the first atrous one,
        which had stride 2 in MobileNetV2 and lost it for output stride 8 (the atrous rates then
        doubled: they are halved here)."""
        last = None
        for node in self.order():
            if node["op"] == "SpaceToBatchND":
                break
            if node["op"] == "DepthwiseConv2dNative":
                last = node
        if (last is None or self.attr(last, "strides") != [1, 1, 1, 1] or self.attr(last, "padding") != "SAME"
                or "expanded_conv_6/" not in last["name"]):
            raise SystemExit("no stride-1 depthwise convolution of block 6 before the atrous ones")
        return last["name"]

    def order(self):
        """The nodes in a topological order."""
        pending = {name: len(self.inputs(n)) for name, n in self.nodes.items()}
        ready = deque(name for name, count in pending.items() if count == 0)
        out = []
        while ready:
            name = ready.popleft()
            out.append(self.nodes[name])
            for c in self.consumers.get(name, []):
                pending[c] -= 1
                if pending[c] == 0:
                    ready.append(c)
        return out

    def convert(self):
        argmax = [n for n in self.nodes.values() if n["op"] == "ArgMax"]
        if len(argmax) != 1:
            raise SystemExit("the graph does not end in one ArgMax")
        logits = self.inputs(argmax[0])[0]
        lowres = [n["name"] for n in self.nodes.values() if n["op"] == "BiasAdd"]
        if len(lowres) != 1:
            raise SystemExit("the graph does not have one BiasAdd (the logits' layer)")
        image = self.image_node()
        self.values[image] = Value("image", [1, 3] + self.size)
        if self.output_stride != NATIVE_STRIDE:
            self.strided = self.restride()
        needed = self.ancestors(logits)
        for node in self.order():
            name = node["name"]
            if name in self.values or name not in needed or node["op"] == "Const":
                continue  # the image, a constant, or the convolution of an atrous one (done with it)
            if not any(i in self.values for i in self.inputs(node)):
                continue  # shape arithmetic and pre-processing before the image
            self.convert_node(node)
        return self.values[logits], self.values[lowres[0]]

    def dynamic(self, node):
        """The node's dynamic inputs (Values) and constant ones (arrays)."""
        dyn, const = [], []
        for i in self.inputs(node):
            if i in self.values:
                dyn.append((i, self.values[i]))
            else:
                const.append(self.const(i))
        return dyn, const

    def convert_node(self, node):
        op, name = node["op"], node["name"]
        dyn, const = self.dynamic(node)
        if op in ("Conv2D", "DepthwiseConv2dNative"):
            self.values[name] = self.convolution(node, dyn[0][1], const[0])
        elif op == "SpaceToBatchND":
            self.values[name] = self.atrous(node, dyn[0][1], const)
        elif op == "BatchToSpaceND":
            self.values[name] = self.alias(*dyn[0])  # done with its SpaceToBatchND (see atrous)
        elif op == "Mul" and len(dyn) == 1:
            src, x = dyn[0]
            scale = np.asarray(const[0], np.float32).reshape(-1)
            if x.conv is None or not self.single_use(src) or scale.size not in (1, x.shape[1]):
                raise SystemExit(f"{name}: a Mul by a constant that is not a batch norm after a convolution")
            x.conv.weight *= scale.reshape(-1, 1, 1, 1)
            x.conv.bias *= scale
            self.values[name] = x
        elif op in ("Add", "AddV2", "BiasAdd") and len(dyn) == 1:
            src, x = dyn[0]
            offset = np.asarray(const[0], np.float32).reshape(-1)
            if not self.single_use(src) or not self.absorb(x, offset):
                raise SystemExit(f"{name}: an Add of a constant that cannot be folded into a convolution")
            self.values[name] = Value(x.name, x.shape)
        elif op in ("Add", "AddV2", "AddN"):
            if const:
                raise SystemExit(f"{name}: an {op} of constants and tensors")
            shapes = {tuple(v.shape) for _, v in dyn}
            if len(shapes) != 1:
                raise SystemExit(f"{name}: an {op} of tensors of different shapes {shapes}")
            out = self.emit("Sum" if len(dyn) > 2 else "Add", [v.name for _, v in dyn], name)
            terms = [v for src, v in dyn if self.single_use(src)]
            self.values[name] = Value(out, dyn[0][1].shape, terms=terms)
        elif op == "Relu6":
            x = dyn[0][1]
            self.values[name] = Value(self.emit("Clip", [x.name], name, min=0.0, max=6.0), x.shape)
        elif op == "Relu":
            x = dyn[0][1]
            self.values[name] = Value(self.emit("Relu", [x.name], name), x.shape)
        elif op == "AvgPool":
            x = dyn[0][1]
            ksize, strides = self.attr(node, "ksize"), self.attr(node, "strides")
            if (self.attr(node, "padding") != "VALID" or ksize != strides
                    or [self.scaled(k, axis) for axis, k in enumerate(ksize[1:3])] != x.shape[2:]):
                raise SystemExit(f"{name}: only a global average pooling is supported")
            self.values[name] = Value(self.emit("GlobalAveragePool", [x.name], name), x.shape[:2] + [1, 1])
        elif op == "ResizeBilinear":
            size = [self.scaled(int(s), axis) for axis, s in enumerate(const[0])]
            self.values[name] = self.resize(node, *dyn[0], size)
        elif op == "ConcatV2":
            axis = int(const[0])
            parts = [v for _, v in dyn]
            if axis not in (3, -1) or any(p.shape[2:] != parts[0].shape[2:] for p in parts):
                raise SystemExit(f"{name}: only a concatenation of channels is supported")
            shape = [1, sum(p.shape[1] for p in parts)] + parts[0].shape[2:]
            self.values[name] = Value(self.emit("Concat", [p.name for p in parts], name, axis=1), shape)
        else:
            raise SystemExit(f"{name}: TF operator {op} is not supported by this converter")

    def alias(self, src, x):
        """x passed on unchanged by an operator whose input is the TF tensor src."""
        return Value(x.name, x.shape, conv=x.conv if self.single_use(src) else None)

    def absorb(self, x, offset):
        """Adds a per-channel constant to x by changing a convolution's bias."""
        if offset.size not in (1, x.shape[1]):
            return False
        if x.conv is not None:
            x.conv.bias += offset
            return True
        return any(self.absorb(t, offset) for t in (x.terms or []))

    def convolution(self, node, x, kernel, dilation=1, pads=None):
        """Conv2D (kernel H W I O) or DepthwiseConv2dNative (H W C M), NHWC."""
        name = node["name"]
        if self.attr(node, "data_format", "NHWC") != "NHWC":
            raise SystemExit(f"{name}: only NHWC is supported")
        if self.attr(node, "dilations", [1, 1, 1, 1]) != [1, 1, 1, 1]:
            raise SystemExit(f"{name}: dilations given as an attribute are not supported")
        strides = self.attr(node, "strides")
        stride = strides[1]
        if strides != [1, stride, stride, 1]:
            raise SystemExit(f"{name}: strides {strides} are not supported")
        if name == self.strided:
            stride = 2
        kh, kw = kernel.shape[:2]
        if node["op"] == "Conv2D":
            weight = kernel.transpose(3, 2, 0, 1)
            group, cout = 1, kernel.shape[3]
            if kernel.shape[2] != x.shape[1]:
                raise SystemExit(f"{name}: {kernel.shape[2]} input channels, the input has {x.shape[1]}")
        else:
            c, m = kernel.shape[2:]
            weight = kernel.reshape(kh, kw, c * m, 1).transpose(2, 3, 0, 1)
            group, cout = c, c * m
            if c != x.shape[1]:
                raise SystemExit(f"{name}: {c} input channels, the input has {x.shape[1]}")
        padding = self.attr(node, "padding")
        h, w = x.shape[2:]
        if pads is None:
            if padding == "VALID":
                pads = [0, 0, 0, 0]
            elif padding == "SAME":
                pads = []
                for size, k in ((h, kh), (w, kw)):
                    out = -(-size // stride)
                    total = max((out - 1) * stride + (k - 1) * dilation + 1 - size, 0)
                    pads.append((total // 2, total - total // 2))
                pads = [pads[0][0], pads[1][0], pads[0][1], pads[1][1]]
            else:
                raise SystemExit(f"{name}: padding {padding} is not supported")
        if pads[0] != pads[2] or pads[1] != pads[3]:
            raise SystemExit(f"{name}: asymmetric padding {pads} at input size {self.size} (use a size 8k+1)")
        out_h = (h + pads[0] + pads[2] - (kh - 1) * dilation - 1) // stride + 1
        out_w = (w + pads[1] + pads[3] - (kw - 1) * dilation - 1) // stride + 1
        conv = Conv(name, np.array(weight, np.float32), np.zeros(cout, np.float32))
        self.convs.append(conv)
        out = self.emit("Conv", [x.name, name + "/W", name + "/B"], name, kernel_shape=[kh, kw],
                        strides=[stride, stride], dilations=[dilation, dilation], pads=pads, group=group)
        return Value(out, [1, cout, out_h, out_w], conv=conv)

    def atrous(self, node, x, const):
        """SpaceToBatchND -> convolution (VALID) -> BatchToSpaceND: a dilated
        convolution. Its pads are those of the pair at the native size, which
        do not depend on the size (SAME padding of the dilated kernel)."""
        block, paddings = np.asarray(const[0]).tolist(), np.asarray(const[1]).tolist()
        conv_name = self.consumers.get(node["name"], [])
        if len(conv_name) != 1 or self.nodes[conv_name[0]]["op"] not in ("Conv2D", "DepthwiseConv2dNative"):
            raise SystemExit(f"{node['name']}: a SpaceToBatchND not followed by one convolution")
        conv = self.nodes[conv_name[0]]
        b2s = self.consumers.get(conv["name"], [])
        if len(b2s) != 1 or self.nodes[b2s[0]]["op"] != "BatchToSpaceND":
            raise SystemExit(f"{conv['name']}: an atrous convolution without its BatchToSpaceND")
        b2s = self.nodes[b2s[0]]
        block2, crops = (np.asarray(self.const(i)).tolist() for i in self.inputs(b2s)[1:])
        if (block != block2 or block[0] != block[1] or self.attr(conv, "padding") != "VALID"
                or self.attr(conv, "strides") != [1, 1, 1, 1]):
            raise SystemExit(f"{node['name']}: an unexpected atrous convolution")
        rate = block[0] * NATIVE_STRIDE // self.output_stride
        kernel = self.const(self.inputs(conv)[1])
        pads = []
        for axis in range(2):
            (p0, p1), (c0, c1) = paddings[axis], crops[axis]
            begin = p0 - c0
            end = p0 + p1 - c0 - c1 - begin
            if c0 != 0 or begin != end or begin != block[0] * (kernel.shape[axis] - 1) // 2:
                raise SystemExit(f"{node['name']}: paddings {paddings} and crops {crops} are not SAME padding")
            pads.append(rate * (kernel.shape[axis] - 1) // 2)
        # The convolution is converted here; its node and the BatchToSpaceND then pass the value on.
        value = self.convolution(conv, x, kernel, dilation=rate, pads=[pads[0], pads[1], pads[0], pads[1]])
        self.values[conv["name"]] = value
        return value

    def resize(self, node, src, x, size):
        name = node["name"]
        if self.attr(node, "half_pixel_centers", False):
            raise SystemExit(f"{name}: half-pixel resize is not supported")
        h, w = x.shape[2:]
        if [h, w] == size:
            return self.alias(src, x)  # a resize to the same size is the identity (aligned corners or not)
        if [h, w] == [1, 1]:
            scales = self.initializer(name + "/scales", np.array([1, 1, size[0], size[1]], np.float32))
            return Value(self.emit("Resize", [x.name, scales], name, mode="nearest"), x.shape[:2] + size)
        factor = (size[0] - 1) // (h - 1) if h > 1 else 0
        if (not self.attr(node, "align_corners", False) or factor < 1
                or (h - 1) * factor + 1 != size[0] or (w - 1) * factor + 1 != size[1]):
            raise SystemExit(f"{name}: a resize from {[h, w]} to {size} is not supported")
        # Bilinear with aligned corners by an integer factor: each input pixel
        # spreads over its neighbours with the weights 1 - |d|/factor.
        k = 2 * factor - 1
        tent = 1 - np.abs(np.arange(k) - (factor - 1)) / factor
        kernel = np.tile((tent[:, None] * tent[None, :])[None, None], (x.shape[1], 1, 1, 1)).astype(np.float32)
        weight = self.initializer(name + "/W", kernel)
        out = self.emit("ConvTranspose", [x.name, weight], name, kernel_shape=[k, k], strides=[factor, factor],
                        pads=[factor - 1] * 4, group=x.shape[1])
        return Value(out, x.shape[:2] + size)

    def model(self):
        logits, lowres = self.convert()
        for conv in self.convs:
            self.initializer(conv.name + "/W", conv.weight)
            self.initializer(conv.name + "/B", conv.bias)
        renames = {logits.name: "logits", lowres.name: "logits_lowres"}
        for n in self.onnx_nodes:
            n.input[:] = [renames.get(i, i) for i in n.input]
            n.output[:] = [renames.get(o, o) for o in n.output]
        graph = helper.make_graph(
            self.onnx_nodes, "deeplab_v3_mobilenet_v2_voc",
            [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 3] + self.size)],
            [helper.make_tensor_value_info("logits", TensorProto.FLOAT, logits.shape),
             helper.make_tensor_value_info("logits_lowres", TensorProto.FLOAT, lowres.shape)],
            self.initializers)
        model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", OPSET)],
                                  producer_name="smql tfjs_segmenter_to_onnx")
        h, w = self.size
        model.doc_string = (f"DeepLab v3 MobileNetV2 PASCAL VOC (21 classes) from npm @codait/max-image-segmenter "
                            f"(Apache-2.0), output stride {self.output_stride}. image: float32 [1,3,{h},{w}] NCHW "
                            f"RGB, pixel/127.5 - 1. logits: float32 {logits.shape} scores before the arg max; "
                            f"logits_lowres: {lowres.shape}.")
        model = onnx.shape_inference.infer_shapes(model)
        onnx.checker.check_model(model)
        return model, logits.shape, lowres.shape


def main():
    if len(sys.argv) not in (3, 4, 5):
        raise SystemExit(__doc__)
    size = sys.argv[3] if len(sys.argv) > 3 else str(NATIVE_SIZE)
    try:
        size = [int(s) for s in size.split("x")] * (2 if "x" not in size else 1)
        output_stride = int(sys.argv[4]) if len(sys.argv) > 4 else NATIVE_STRIDE
    except ValueError:
        raise SystemExit(__doc__) from None
    if len(size) != 2:
        raise SystemExit(f"{sys.argv[3]}: not a size (S or HxW)")
    model, logits, lowres = Converter(sys.argv[1], size, output_stride).model()
    onnx.save(model, sys.argv[2])
    print(f"{sys.argv[2]}: {len(model.graph.node)} nodes; input image [1, 3, {size[0]}, {size[1]}]; "
          f"output stride {output_stride}; outputs logits {logits}, logits_lowres {lowres}")


if __name__ == "__main__":
    main()
