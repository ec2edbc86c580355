#!/usr/bin/python3
"""Converts a TF.js graph model made by onnx-tf (a GraphDef as JSON plus a
weights manifest over .bin shards) back into ONNX for OpenCV's DNN module.

Such graphs keep activations in NCHW and wrap every convolution, pooling and
resize in transposes to NHWC. OpenCV's importer assumes NCHW for those layers,
so the converter tracks each tensor's layout instead of copying the
transposes: every 4-D activation stays NCHW in the ONNX graph, a transpose
between NCHW and NHWC only relabels it, and the NHWC layers become their NCHW
ONNX counterparts. Explicit pads before a convolution or pooling are folded
into the layer. Constant sub-graphs (shape arithmetic) are evaluated here.

Usage: tfjs_to_onnx.py MODEL.json OUT.onnx
Only the operators these detector graphs use are supported; any other one is
an error that names it.
"""
import base64
import json
import os
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

TO_NHWC = [0, 2, 3, 1]
TO_NCHW = [0, 3, 1, 2]
NHWC_AXIS_IN_NCHW = {0: 0, 1: 2, 2: 3, 3: 1, -1: 1}


def node_attr(node, key, default=None):
    """A TF graph node's attribute as Python: a list of ints, a string, a bool, float or int."""
    a = node.get("attr", {}).get(key)
    if a is None:
        return default
    if "list" in a:
        return [int(i) for i in a["list"].get("i", [])]
    if "s" in a:
        return base64.b64decode(a["s"]).decode()
    for kind in ("b", "f", "i"):
        if kind in a:
            return a[kind]
    return default


def load_weights(model_path, model):
    """name -> numpy array for every weight in the manifest (dequantized)."""
    weights = {}
    folder = os.path.dirname(model_path)
    for group in model["weightsManifest"]:
        data = b"".join(open(os.path.join(folder, p), "rb").read() for p in group["paths"])
        offset = 0
        for spec in group["weights"]:
            shape = spec["shape"]
            count = int(np.prod(shape)) if shape else 1
            quant = spec.get("quantization")
            if quant and quant["dtype"] == "float16":
                raw = np.frombuffer(data, np.float16, count, offset)
                offset += 2 * count
                value = raw.astype(np.float32)
            elif quant:
                dtype = {"uint8": np.uint8, "uint16": np.uint16}[quant["dtype"]]
                raw = np.frombuffer(data, dtype, count, offset)
                offset += raw.itemsize * count
                value = raw.astype(np.float32) * quant["scale"] + quant["min"]
            else:
                dtype = {"float32": np.float32, "int32": np.int32, "bool": np.bool_}[spec["dtype"]]
                value = np.frombuffer(data, dtype, count, offset).copy()
                offset += value.itemsize * count
            weights[spec["name"]] = value.reshape(shape)
    return weights


class Tensor:
    """A TF tensor as the ONNX graph holds it: its ONNX name and TF layout
    ('NCHW' also stands for "as in TF" for tensors that are not 4-D
    activations). A pending pad is a Pad not yet emitted, for the next layer to fold."""

    def __init__(self, name, layout="NCHW", pad=None):
        self.name, self.layout, self.pad = name, layout, pad


class Converter:
    def __init__(self, model_path):
        model = json.load(open(model_path))
        self.nodes = model["modelTopology"]["node"]
        self.weights = load_weights(model_path, model)
        self.consts = {}  # TF name -> numpy value
        self.tensors = {}  # TF name -> Tensor
        self.onnx_nodes, self.initializers, self.outputs = [], [], []
        self.folded_biases = set()  # the Add nodes a convolution took as its bias

    # -- helpers --------------------------------------------------------
    attr = staticmethod(node_attr)

    def source(self, ref):
        return ref.split(":")[0] if ref.endswith(":0") else ref

    def initializer(self, name, value):
        self.initializers.append(numpy_helper.from_array(value, name))
        return name

    def emit(self, op, inputs, output, **attrs):
        self.onnx_nodes.append(helper.make_node(op, inputs, [output], name=output, **attrs))
        return output

    def materialize(self, t):
        """The tensor with any pending pad emitted as an ONNX Pad."""
        if t.pad is None:
            return t.name
        pads, value = t.pad
        name = self.emit("Pad", [t.name, self.initializer(t.name + "/pads", np.array(pads, np.int64)),
                                 self.initializer(t.name + "/value", np.array(value, np.float32))],
                         t.name + "/padded", mode="constant")
        t.name, t.pad = name, None
        return name

    def spatial_pads(self, t):
        """Pending pads of a 4-D NCHW tensor as ONNX [top, left, bottom, right]."""
        if t.pad is None:
            return [0, 0, 0, 0], t.name, None
        pads, value = t.pad
        begin, end = pads[:4], pads[4:]
        if begin[0] or begin[1] or end[0] or end[1]:
            raise SystemExit("a pad over batch or channels cannot be folded")
        return [begin[2], begin[3], end[2], end[3]], t.name, value

    # -- the graph -------------------------------------------------------
    def convert(self):
        consumers = {}
        for node in self.nodes:
            for ref in node.get("input", []):
                consumers.setdefault(self.source(ref), []).append(node)
        for node in self.nodes:
            self.convert_node(node, consumers)
        return self.outputs

    def convert_node(self, node, consumers):
        op, name = node["op"], node["name"]
        inputs = [self.source(i) for i in node.get("input", [])]
        if op == "Const":
            self.consts[name] = self.weights[name]
            return
        if all(i in self.consts for i in inputs) and inputs:
            self.consts[name] = self.fold(op, [self.consts[i] for i in inputs])
            return
        if op == "Placeholder":
            dims = [int(d["size"]) for d in node["attr"]["shape"]["shape"]["dim"]]
            self.input = helper.make_tensor_value_info(name, TensorProto.FLOAT, dims)
            self.tensors[name] = Tensor(name)
            return
        x = self.tensors[inputs[0]]
        if op == "Transpose":
            perm = list(self.consts[inputs[1]])
            if len(perm) == 4 and x.layout == "NCHW" and perm == TO_NHWC:
                self.tensors[name] = Tensor(x.name, "NHWC", x.pad)
            elif len(perm) == 4 and x.layout == "NHWC" and perm == TO_NCHW:
                self.tensors[name] = Tensor(x.name, "NCHW", x.pad)
            elif x.layout == "NCHW":
                self.tensors[name] = Tensor(self.emit("Transpose", [self.materialize(x)], name, perm=perm))
            else:
                raise SystemExit(f"{name}: transpose {perm} of an NHWC tensor is not supported")
        elif op in ("Pad", "PadV2"):
            pads = np.array(self.consts[inputs[1]]).reshape(-1, 2)
            if x.layout == "NHWC":
                pads = pads[TO_NCHW]
            value = float(self.consts[inputs[2]]) if op == "PadV2" else 0.0
            if x.pad is not None:
                self.materialize(x)
            self.tensors[name] = Tensor(x.name, x.layout, (list(pads[:, 0]) + list(pads[:, 1]), value))
        elif op == "Conv2D":
            self.require_nhwc(node, x)
            pads, src, value = self.spatial_pads(x)
            if value not in (None, 0.0):
                raise SystemExit(f"{name}: a convolution over a non-zero pad")
            kernel = self.consts[inputs[1]]  # H W I O
            strides, dilations = self.attr(node, "strides"), self.attr(node, "dilations", [1, 1, 1, 1])
            if self.attr(node, "padding") != "VALID":
                raise SystemExit(f"{name}: only VALID padding (with explicit pads) is supported")
            weight = self.initializer(name + "/W", np.ascontiguousarray(kernel.transpose(3, 2, 0, 1)))
            inputs_onnx = [src, weight]
            # A bias Add that follows is folded into the convolution.
            after = consumers.get(name, [])
            if len(after) == 1 and after[0]["op"] in ("Add", "AddV2", "BiasAdd"):
                bias_ref = [self.source(i) for i in after[0]["input"] if self.source(i) != name]
                if len(bias_ref) == 1 and bias_ref[0] in self.consts and self.consts[bias_ref[0]].ndim == 1:
                    inputs_onnx.append(self.initializer(name + "/B", self.consts[bias_ref[0]].astype(np.float32)))
                    self.folded_biases.add(after[0]["name"])
            out = self.emit("Conv", inputs_onnx, name, kernel_shape=list(kernel.shape[:2]), strides=strides[1:3],
                            dilations=dilations[1:3], pads=pads)
            self.tensors[name] = Tensor(out, "NHWC")
        elif op in ("Add", "AddV2", "BiasAdd") and name in self.folded_biases:
            self.tensors[name] = self.tensors[inputs[0]] if inputs[0] in self.tensors else self.tensors[inputs[1]]
        elif op in ("Add", "AddV2"):
            a, b = (self.tensors.get(i) for i in inputs)
            if a is None or b is None:
                raise SystemExit(f"{name}: an Add with a constant that is not a convolution's bias")
            if a.layout != b.layout:
                raise SystemExit(f"{name}: an Add of tensors in different layouts")
            self.tensors[name] = Tensor(self.emit("Add", [self.materialize(a), self.materialize(b)], name), a.layout)
        elif op == "MaxPool":
            self.require_nhwc(node, x)
            pads, src, _ = self.spatial_pads(x)  # the pad value (-inf or similar) is what pooling pads mean
            ksize, strides = self.attr(node, "ksize"), self.attr(node, "strides")
            if self.attr(node, "padding") != "VALID":
                raise SystemExit(f"{name}: only VALID padding (with explicit pads) is supported")
            out = self.emit("MaxPool", [src], name, kernel_shape=ksize[1:3], strides=strides[1:3], pads=pads)
            self.tensors[name] = Tensor(out, "NHWC")
        elif op == "ResizeBilinear":
            self.require_nhwc(node, x)
            size = np.array(self.consts[inputs[1]], np.int64)
            if self.attr(node, "align_corners", False):
                mode = "align_corners"
            elif self.attr(node, "half_pixel_centers", False):
                mode = "pytorch_half_pixel"
            else:
                mode = "asymmetric"
            shape = self.shape_of(x)
            sizes = self.initializer(name + "/sizes", np.array([shape[0], shape[1], size[0], size[1]], np.int64))
            empty = self.initializer(name + "/empty", np.zeros(0, np.float32))  # no roi, no scales: the sizes rule
            out = self.emit("Resize", [self.materialize(x), empty, empty, sizes], name, mode="linear",
                            coordinate_transformation_mode=mode)
            self.tensors[name] = Tensor(out, "NHWC")
        elif op == "LeakyRelu":
            out = self.emit("LeakyRelu", [self.materialize(x)], name, alpha=float(self.attr(node, "alpha", 0.2)))
            self.tensors[name] = Tensor(out, x.layout)
        elif op in ("Sigmoid", "Relu", "Identity"):
            out = self.emit(op, [self.materialize(x)], name)
            self.tensors[name] = Tensor(out, x.layout)
            if op == "Identity" and not consumers.get(name):
                self.outputs.append(name)
        elif op == "ConcatV2":
            parts = [self.tensors[i] for i in inputs[:-1]]
            axis = int(self.consts[inputs[-1]])
            if any(p.layout != parts[0].layout for p in parts):
                raise SystemExit(f"{name}: a concatenation of tensors in different layouts")
            if parts[0].layout == "NHWC":
                axis = NHWC_AXIS_IN_NCHW[axis]
            out = self.emit("Concat", [self.materialize(p) for p in parts], name, axis=axis)
            self.tensors[name] = Tensor(out, parts[0].layout)
        elif op == "SplitV":
            sizes = [int(s) for s in self.consts[inputs[1]]]
            axis = int(self.consts[inputs[2]])
            if x.layout == "NHWC":
                axis = NHWC_AXIS_IN_NCHW[axis]
            outs = [name] + [f"{name}:{k}" for k in range(1, len(sizes))]
            self.onnx_nodes.append(helper.make_node("Split", [self.materialize(x)], outs, name=name, axis=axis,
                                                    split=sizes))
            for out in outs:
                self.tensors[out] = Tensor(out, x.layout)
        elif op == "Reshape":
            if x.layout != "NCHW":
                raise SystemExit(f"{name}: a reshape of an NHWC tensor is not supported")
            shape = self.initializer(name + "/shape", np.array(self.consts[inputs[1]], np.int64))
            self.tensors[name] = Tensor(self.emit("Reshape", [self.materialize(x), shape], name))
        else:
            raise SystemExit(f"{name}: TF operator {op} is not supported by this converter")

    def require_nhwc(self, node, x):
        if x.layout != "NHWC":
            raise SystemExit(f"{node['name']}: {node['op']} expects an NHWC input")

    def shape_of(self, t):
        """Batch and channels of a 4-D tensor, from ONNX shape inference so far."""
        graph = helper.make_graph(self.onnx_nodes, "partial", [self.input], [], self.initializers)
        inferred = onnx.shape_inference.infer_shapes(helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)]))
        for info in inferred.graph.value_info:
            if info.name == t.name:
                return [d.dim_value for d in info.type.tensor_type.shape.dim][:2]
        raise SystemExit(f"no shape known for {t.name}")

    def fold(self, op, args):
        """Evaluates an operator whose inputs are all constants."""
        if op == "SparseToDense":
            indices, shape, values, default = args
            dense = np.full(shape, default, dtype=np.asarray(values).dtype)
            for index, value in zip(np.asarray(indices).reshape(len(values), -1) if len(values) else [],
                                    np.broadcast_to(values, (len(indices),))):
                dense[tuple(index)] = value
            return dense
        if op in ("Add", "AddV2"):
            return args[0] + args[1]
        if op == "Identity":
            return args[0]
        raise SystemExit(f"cannot evaluate constant {op}")


def main():
    if len(sys.argv) != 3:
        raise SystemExit("usage: tfjs_to_onnx.py MODEL.json OUT.onnx")
    converter = Converter(sys.argv[1])
    outputs = converter.convert()
    graph = helper.make_graph(converter.onnx_nodes, "tfjs", [converter.input],
                              [helper.make_tensor_value_info(o, TensorProto.FLOAT, None) for o in outputs],
                              converter.initializers)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)], producer_name="smql tfjs_to_onnx")
    model = onnx.shape_inference.infer_shapes(model)
    onnx.checker.check_model(model)
    onnx.save(model, sys.argv[2])
    shapes = {i.name: [d.dim_value for d in i.type.tensor_type.shape.dim] for i in model.graph.output}
    print(f"{sys.argv[2]}: {len(model.graph.node)} nodes; outputs {shapes}")


if __name__ == "__main__":
    main()
