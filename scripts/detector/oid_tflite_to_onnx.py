#!/usr/bin/python3
"""Converts MediaPipe's Objectron object detector (SSD MobileNetV2 trained on
Open Images v4, 24 labels, a TFLite flatbuffer with fp16 weights) into an
ONNX graph for OpenCV 4.6's DNN module, with the SSD box decoding folded in.

The TFLite graph is NHWC; the ONNX graph keeps every 4-D activation NCHW
(weights are transposed), so its input is [1,3,300,300]. fp16 weights behind
DEQUANTIZE operators are folded into float32 initializers. ReLU6 is a Clip
with min/max attributes (opset 10): OpenCV 4.6 reads that as its ReLU6 layer
and fuses it into the convolution, and rejects the opset-11 Clip whose
bounds are inputs.

ONNX contract (see also oid_verify.py):
  input  "image"  [1,3,300,300] float, RGB, (pixel / 127.5) - 1, i.e. in [-1,1],
                  the whole frame stretched to 300x300 (no letterbox)
  output "boxes"  [1,1917,4] ymin,xmin,ymax,xmax normalised to the input [0,1]
                  (not clipped), one per anchor
  output "scores" [1,1917,23] sigmoid class probabilities for labels 1..23 of
                  the label map (the background/"???" label 0 is dropped);
                  column j is line j of oid.names
Decoding is MediaPipe's TensorsToDetectionsCalculator (box order y,x,h,w;
x/y scale 10, w/h scale 5, exponential sizes, sigmoid scores) over the anchors
of its SsdAnchorsCalculator, both with the options of MediaPipe's
ObjectDetectionOidV4Subgraph (a CalculatorGraphConfig serialised inside the
package's objectron_solution_wasm_bin.wasm; objectron.binarypb only holds the
top graph). MediaPipe then keeps per anchor the best class, score >= 0.5, and
runs class-agnostic NMS (IoU 0.5, at most 100).

Usage: oid_tflite_to_onnx.py MODEL.tflite OUT.onnx [LABELMAP.txt OUT.names] [--raw]
  LABELMAP.txt  the model's label map (24 lines, "???" first); OUT.names gets
                the labels of the "scores" columns, one a line (23)
  --raw  also exposes the model's raw outputs "raw_boxes" [1,1917,4] and
         "raw_scores" [1,1917,24] (logits) as graph outputs (for verification)
"""
import math
import os
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import oid_tflite  # noqa: E402

OPSET = 10
INPUT_SIZE = 300

# MediaPipe ObjectDetectionOidV4Subgraph: SsdAnchorsCalculatorOptions
ANCHORS = dict(num_layers=6, min_scale=0.2, max_scale=0.95, input_size_height=300,
               input_size_width=300, anchor_offset_x=0.5, anchor_offset_y=0.5,
               strides=[16, 32, 64, 128, 256, 512],
               aspect_ratios=[1.0, 2.0, 0.5, 3.0, 0.3333],
               reduce_boxes_in_lowest_layer=True, interpolated_scale_aspect_ratio=1.0)
# TensorsToDetectionsCalculatorOptions
DECODE = dict(num_classes=24, num_boxes=1917, x_scale=10.0, y_scale=10.0, w_scale=5.0,
              h_scale=5.0, sigmoid_score=True, ignore_classes=[0], min_score_thresh=0.5)


def ssd_anchors(o=ANCHORS):
    """MediaPipe's SsdAnchorsCalculator: [N,4] as y_center, x_center, h, w (normalised)."""
    def scale(i, n):
        return (o["min_scale"] + o["max_scale"]) / 2 if n == 1 else \
            o["min_scale"] + (o["max_scale"] - o["min_scale"]) * i / (n - 1.0)

    n, strides = o["num_layers"], o["strides"]
    anchors = []
    layer = 0
    while layer < n:
        ratios, scales = [], []
        last = layer
        while last < len(strides) and strides[last] == strides[layer]:
            s = scale(last, n)
            if last == 0 and o["reduce_boxes_in_lowest_layer"]:
                ratios += [1.0, 2.0, 0.5]
                scales += [0.1, s, s]
            else:
                ratios += list(o["aspect_ratios"])
                scales += [s] * len(o["aspect_ratios"])
                if o["interpolated_scale_aspect_ratio"] > 0:
                    s_next = 1.0 if last == n - 1 else scale(last + 1, n)
                    scales.append(math.sqrt(s * s_next))
                    ratios.append(o["interpolated_scale_aspect_ratio"])
            last += 1
        hs = [s / math.sqrt(r) for s, r in zip(scales, ratios)]
        ws = [s * math.sqrt(r) for s, r in zip(scales, ratios)]
        stride = strides[layer]
        fh = math.ceil(o["input_size_height"] / stride)
        fw = math.ceil(o["input_size_width"] / stride)
        for y in range(fh):
            for x in range(fw):
                for h, w in zip(hs, ws):
                    anchors.append(((y + o["anchor_offset_y"]) / fh, (x + o["anchor_offset_x"]) / fw, h, w))
        layer = last
    return np.array(anchors, np.float32)


def decode(raw_boxes, raw_scores, anchors):
    """numpy version of the decoding the ONNX graph does (float64)."""
    a = anchors.astype(np.float64)
    r = raw_boxes.reshape(-1, 4).astype(np.float64)
    yc = r[:, 0] / DECODE["y_scale"] * a[:, 2] + a[:, 0]
    xc = r[:, 1] / DECODE["x_scale"] * a[:, 3] + a[:, 1]
    h = np.exp(r[:, 2] / DECODE["h_scale"]) * a[:, 2]
    w = np.exp(r[:, 3] / DECODE["w_scale"]) * a[:, 3]
    boxes = np.stack([yc - h / 2, xc - w / 2, yc + h / 2, xc + w / 2], axis=1)
    scores = 1 / (1 + np.exp(-raw_scores.reshape(len(a), -1).astype(np.float64)))
    return boxes[None], scores[None, :, 1:]


def same_pads(size, k, s, d):
    eff = (k - 1) * d + 1
    out = -(-size // s)
    total = max((out - 1) * s + eff - size, 0)
    return total // 2, total - total // 2


class Converter:
    def __init__(self, model):
        self.m = model
        self.nodes, self.inits = [], []
        self.names = {}  # tflite tensor index -> onnx name
        self.layout = {}  # tflite tensor index -> "NCHW" (a 4-D NHWC activation held NCHW) or "plain"
        self.consts = {}  # tflite tensor index -> float32/int32 numpy (constants, DEQUANTIZE folded)
        self.count = 0
        for t in model.tensors:
            if t.data is not None:
                self.consts[t.index] = t.data.astype(np.float32) if t.dtype in (np.float16, np.float32) else t.data

    def fresh(self, base):
        self.count += 1
        return "%s_%d" % (base, self.count)

    def init(self, base, value):
        name = self.fresh(base)
        self.inits.append(numpy_helper.from_array(np.ascontiguousarray(value), name))
        return name

    def node(self, op, inputs, base, **attrs):
        out = self.fresh(base)
        self.nodes.append(helper.make_node(op, inputs, [out], name=out, **attrs))
        return out

    def activation(self, x, act):
        if act is None:
            return x
        if act == "RELU":
            return self.node("Relu", [x], "relu")
        if act == "RELU6":
            return self.node("Clip", [x], "relu6", min=0.0, max=6.0)
        raise NotImplementedError("activation %s" % act)

    def as_plain(self, i):
        """ONNX name of tensor i in TFLite's own layout."""
        if self.layout[i] == "NCHW":
            return self.node("Transpose", [self.names[i]], "to_nhwc", perm=[0, 2, 3, 1])
        return self.names[i]

    def convert(self, raw_outputs=False):
        m = self.m
        inp = m.inputs[0]
        n, h, w, c = m.tensors[inp].shape
        self.names[inp], self.layout[inp] = "image", "NCHW"
        for op in m.ops:
            self.convert_op(op)
        box_i, score_i = m.outputs
        if m.tensors[box_i].shape != [1, DECODE["num_boxes"], 4] or \
                m.tensors[score_i].shape != [1, DECODE["num_boxes"], DECODE["num_classes"]]:
            raise ValueError("unexpected output shapes %s %s" % (m.tensors[box_i].shape, m.tensors[score_i].shape))
        raw_boxes, raw_scores = self.as_plain(box_i), self.as_plain(score_i)
        outputs = self.decode(raw_boxes, raw_scores)
        graph_outputs = [helper.make_tensor_value_info("boxes", TensorProto.FLOAT, [1, DECODE["num_boxes"], 4]),
                         helper.make_tensor_value_info("scores", TensorProto.FLOAT,
                                                       [1, DECODE["num_boxes"], DECODE["num_classes"] - 1])]
        if raw_outputs:
            self.nodes.append(helper.make_node("Identity", [raw_boxes], ["raw_boxes"], name="raw_boxes"))
            self.nodes.append(helper.make_node("Identity", [raw_scores], ["raw_scores"], name="raw_scores"))
            graph_outputs += [helper.make_tensor_value_info("raw_boxes", TensorProto.FLOAT, [1, DECODE["num_boxes"], 4]),
                              helper.make_tensor_value_info("raw_scores", TensorProto.FLOAT,
                                                            [1, DECODE["num_boxes"], DECODE["num_classes"]])]
        # rename the decoded outputs
        for node in self.nodes:
            for k, o in enumerate(node.output):
                if o in outputs:
                    node.output[k] = outputs[o]
                    node.name = outputs[o]
        graph = helper.make_graph(
            self.nodes, "oid_ssd_mobilenetv2",
            [helper.make_tensor_value_info("image", TensorProto.FLOAT, [n, c, h, w])],
            graph_outputs, self.inits)
        model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", OPSET)],
                                  producer_name="smql oid_tflite_to_onnx.py")
        model.doc_string = (
            "MediaPipe Objectron SSD MobileNetV2 OIDv4 detector; input image [1,3,300,300] RGB in [-1,1]; "
            "outputs boxes [1,1917,4] ymin,xmin,ymax,xmax normalised and scores [1,1917,23] sigmoid "
            "(labels 1..23 of the label map, background dropped)")
        onnx.checker.check_model(model)
        return model

    def decode(self, raw_boxes, raw_scores):
        """Adds the SSD decoding; returns {onnx name: graph output name}."""
        a = ssd_anchors()
        if len(a) != DECODE["num_boxes"]:
            raise ValueError("%d anchors for %d boxes" % (len(a), DECODE["num_boxes"]))
        i64 = lambda v: np.array(v, np.int64)  # noqa: E731
        yx = self.node("Slice", [raw_boxes, self.init("s", i64([0])), self.init("e", i64([2])),
                                 self.init("ax", i64([2]))], "raw_yx")
        hw = self.node("Slice", [raw_boxes, self.init("s", i64([2])), self.init("e", i64([4])),
                                 self.init("ax", i64([2]))], "raw_hw")
        anchor_hw = a[None, :, 2:4]
        centre_scale = anchor_hw / np.array([DECODE["y_scale"], DECODE["x_scale"]], np.float32)
        centre = self.node("Mul", [yx, self.init("centre_scale", centre_scale.astype(np.float32))], "centre")
        centre = self.node("Add", [centre, self.init("anchor_yx", a[None, :, 0:2].copy())], "centre")
        size = self.node("Mul", [hw, self.init("size_scale", np.array(
            [1 / DECODE["h_scale"], 1 / DECODE["w_scale"]], np.float32).reshape(1, 1, 2) * np.ones_like(anchor_hw))],
            "size_log")
        size = self.node("Exp", [size], "size_exp")
        half = self.node("Mul", [size, self.init("anchor_half_hw", (anchor_hw / 2).astype(np.float32))], "half")
        lo = self.node("Sub", [centre, half], "box_min")
        hi = self.node("Add", [centre, half], "box_max")
        boxes = self.node("Concat", [lo, hi], "boxes", axis=2)
        scores = self.node("Slice", [raw_scores, self.init("s", i64([1])), self.init("e", i64([DECODE["num_classes"]])),
                                     self.init("ax", i64([2]))], "raw_labels")
        scores = self.node("Sigmoid", [scores], "scores")
        return {boxes: "boxes", scores: "scores"}

    def convert_op(self, op):
        m, k, o = self.m, op.kind, op.options
        out = op.outputs[0]
        if k == "DEQUANTIZE":
            if op.inputs[0] not in self.consts:
                raise NotImplementedError("DEQUANTIZE of a non-constant tensor %s" % m.tensors[op.inputs[0]].name)
            self.consts[out] = self.consts[op.inputs[0]].astype(np.float32)
            return
        if all(i in self.consts for i in op.inputs if i >= 0):
            raise NotImplementedError("constant operator %s" % k)
        if k in ("CONV_2D", "DEPTHWISE_CONV_2D"):
            x, wi = op.inputs[0], op.inputs[1]
            if self.layout[x] != "NCHW":
                raise NotImplementedError("%s on a non-activation tensor" % k)
            wt = self.consts[wi]
            _, hh, ww, cin = m.tensors[x].shape
            if k == "CONV_2D":
                weight = wt.transpose(0, 3, 1, 2)  # OHWI -> OIHW
                group = 1
            else:
                weight = wt.transpose(3, 0, 1, 2)  # 1HWO -> O1HW
                group = cin
                if wt.shape[3] != cin * o["multiplier"]:
                    raise ValueError("depthwise channels")
            kh, kw = weight.shape[2], weight.shape[3]
            (sh, sw), (dh, dw) = o["stride"], o["dilation"]
            if o["padding"] == 0:
                pt, pb = same_pads(hh, kh, sh, dh)
                pl, pr = same_pads(ww, kw, sw, dw)
            else:
                pt = pb = pl = pr = 0
            ins = [self.names[x], self.init("w", weight.astype(np.float32))]
            if len(op.inputs) > 2 and op.inputs[2] >= 0:
                ins.append(self.init("b", self.consts[op.inputs[2]].astype(np.float32)))
            y = self.node("Conv", ins, "conv", kernel_shape=[kh, kw], strides=[sh, sw], dilations=[dh, dw],
                          pads=[pt, pl, pb, pr], group=group)
            self.names[out], self.layout[out] = self.activation(y, o["activation"]), "NCHW"
        elif k == "ADD":
            a, b = op.inputs
            if self.layout[a] != self.layout[b] or a in self.consts or b in self.consts:
                raise NotImplementedError("ADD of mixed tensors")
            y = self.node("Add", [self.names[a], self.names[b]], "add")
            self.names[out], self.layout[out] = self.activation(y, o["activation"]), self.layout[a]
        elif k == "RESHAPE":
            shape = m.tensors[out].shape
            x = self.as_plain(op.inputs[0])
            self.names[out] = self.node("Reshape", [x, self.init("shape", np.array(shape, np.int64))], "reshape")
            self.layout[out] = "plain"
        elif k == "CONCATENATION":
            layouts = {self.layout[i] for i in op.inputs}
            axis = o["axis"]
            if layouts == {"NCHW"}:
                axis = {0: 0, 1: 2, 2: 3, 3: 1, -1: 1}[axis]
                layout = "NCHW"
            elif layouts == {"plain"}:
                layout = "plain"
            else:
                raise NotImplementedError("CONCATENATION of mixed layouts")
            y = self.node("Concat", [self.names[i] for i in op.inputs], "concat", axis=axis)
            self.names[out], self.layout[out] = self.activation(y, o["activation"]), layout
        elif k == "LOGISTIC":
            self.names[out], self.layout[out] = self.node("Sigmoid", [self.names[op.inputs[0]]], "sigmoid"), \
                self.layout[op.inputs[0]]
        else:
            raise NotImplementedError("TFLite operator %s" % k)


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    if len(args) not in (2, 4):
        sys.exit(__doc__)
    model = oid_tflite.Model(args[0])
    onnx_model = Converter(model).convert(raw_outputs="--raw" in argv)
    if len(args) == 4:
        labels = [line.strip() for line in open(args[2]) if line.strip()]
        if len(labels) != DECODE["num_classes"]:
            sys.exit("%s: %d labels, the model has %d classes" % (args[2], len(labels), DECODE["num_classes"]))
        kept = [l for i, l in enumerate(labels) if i not in DECODE["ignore_classes"]]
        with open(args[3], "w") as f:
            f.write("".join(l + "\n" for l in kept))
    onnx.save(onnx_model, args[1])
    print("oid_tflite_to_onnx: %s: %d nodes, %d initializers" % (
        args[1], len(onnx_model.graph.node), len(onnx_model.graph.initializer)))


if __name__ == "__main__":
    main(sys.argv)
