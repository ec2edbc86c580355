#!/usr/bin/python3
"""A minimal reader of TensorFlow Lite flatbuffers (written from the public
schema, only the tables and fields the OID SSD detector needs), used by
oid_tflite_to_onnx.py and oid_verify.py.

Flatbuffer layout: a table starts with an int32 offset back to its vtable;
the vtable holds uint16 sizes then one uint16 offset per field (0 = absent).
References (tables, vectors, strings) are uint32 offsets from where they are
stored. A union takes two fields: its type (uint8) then its table.
"""
import struct

import numpy as np

# BuiltinOperator codes (schema.fbs)
OPS = {0: "ADD", 1: "AVERAGE_POOL_2D", 2: "CONCATENATION", 3: "CONV_2D", 4: "DEPTHWISE_CONV_2D",
       6: "DEQUANTIZE", 9: "FULLY_CONNECTED", 14: "LOGISTIC", 17: "MAX_POOL_2D", 18: "MUL",
       19: "RELU", 21: "RELU6", 22: "RESHAPE", 23: "RESIZE_BILINEAR", 25: "SOFTMAX", 28: "TANH",
       32: "CUSTOM", 34: "PAD", 39: "TRANSPOSE", 40: "MEAN", 41: "SUB", 49: "SQUEEZE",
       77: "HARD_SWISH"}
# TensorType
DTYPES = {0: np.float32, 1: np.float16, 2: np.int32, 3: np.uint8, 4: np.int64, 9: np.int8}
# ActivationFunctionType
ACTIVATIONS = {0: None, 1: "RELU", 3: "RELU6"}


class Table:
    def __init__(self, buf, pos):
        self.buf, self.pos = buf, pos
        vt = pos - struct.unpack_from("<i", buf, pos)[0]
        self.vt_size = struct.unpack_from("<H", buf, vt)[0]
        self.vt = vt

    def _field(self, index):
        entry = 4 + 2 * index
        if entry >= self.vt_size:
            return None
        off = struct.unpack_from("<H", self.buf, self.vt + entry)[0]
        return self.pos + off if off else None

    def scalar(self, index, fmt, default=0):
        p = self._field(index)
        return default if p is None else struct.unpack_from("<" + fmt, self.buf, p)[0]

    def _ref(self, index):
        p = self._field(index)
        return None if p is None else p + struct.unpack_from("<I", self.buf, p)[0]

    def table(self, index):
        p = self._ref(index)
        return None if p is None else Table(self.buf, p)

    def vector_pos(self, index):
        """(start of the elements, length) or None."""
        p = self._ref(index)
        if p is None:
            return None
        return p + 4, struct.unpack_from("<I", self.buf, p)[0]

    def string(self, index):
        v = self.vector_pos(index)
        return None if v is None else bytes(self.buf[v[0]:v[0] + v[1]]).decode()

    def scalars(self, index, dtype):
        v = self.vector_pos(index)
        if v is None:
            return np.zeros(0, dtype)
        return np.frombuffer(self.buf, dtype, v[1], v[0])

    def tables(self, index):
        v = self.vector_pos(index)
        if v is None:
            return []
        out = []
        for i in range(v[1]):
            p = v[0] + 4 * i
            out.append(Table(self.buf, p + struct.unpack_from("<I", self.buf, p)[0]))
        return out


class Tensor:
    def __init__(self, index, shape, dtype, name, data):
        self.index, self.shape, self.dtype, self.name, self.data = index, shape, dtype, name, data


class Op:
    def __init__(self, kind, inputs, outputs, options):
        self.kind, self.inputs, self.outputs, self.options = kind, inputs, outputs, options

    def __repr__(self):
        return "%s(%s -> %s %s)" % (self.kind, self.inputs, self.outputs, self.options)


def _options(kind, t):
    """The builtin options of an operator as a dict (defaults when absent)."""
    g = (lambda i, fmt="i", d=0: d if t is None else t.scalar(i, fmt, d))
    if kind == "CONV_2D":  # padding, stride_w, stride_h, activation, dilation_w, dilation_h
        return dict(padding=g(0, "b"), stride=(g(2, "i", 1), g(1, "i", 1)),
                    activation=ACTIVATIONS[g(3, "b")], dilation=(g(5, "i", 1), g(4, "i", 1)))
    if kind == "DEPTHWISE_CONV_2D":  # padding, stride_w, stride_h, multiplier, activation, dil_w, dil_h
        return dict(padding=g(0, "b"), stride=(g(2, "i", 1), g(1, "i", 1)), multiplier=g(3, "i", 1),
                    activation=ACTIVATIONS[g(4, "b")], dilation=(g(6, "i", 1), g(5, "i", 1)))
    if kind in ("AVERAGE_POOL_2D", "MAX_POOL_2D"):  # padding, stride_w, stride_h, fw, fh, activation
        return dict(padding=g(0, "b"), stride=(g(2, "i", 1), g(1, "i", 1)),
                    kernel=(g(4, "i", 1), g(3, "i", 1)), activation=ACTIVATIONS[g(5, "b")])
    if kind == "CONCATENATION":  # axis, activation
        return dict(axis=g(0, "i"), activation=ACTIVATIONS[g(1, "b")])
    if kind in ("ADD", "MUL", "SUB"):  # activation
        return dict(activation=ACTIVATIONS[g(0, "b")])
    if kind == "RESHAPE":  # new_shape
        return dict(new_shape=None if t is None else [int(x) for x in t.scalars(0, "<i4")])
    return {}


class Model:
    """The first subgraph of a .tflite file: tensors (constant ones with data
    as float32/int32 numpy arrays), operators in execution order, inputs, outputs."""

    def __init__(self, path):
        buf = open(path, "rb").read()
        if buf[4:8] != b"TFL3":
            raise ValueError("%s: not a TFLite flatbuffer" % path)
        model = Table(buf, struct.unpack_from("<I", buf, 0)[0])
        codes = []
        for oc in model.tables(1):
            code = max(oc.scalar(0, "b"), oc.scalar(3, "i"))  # deprecated_builtin_code, builtin_code
            codes.append(OPS.get(code, "OP%d" % code) if code != 32 else "CUSTOM:" + oc.string(1))
        buffers = model.tables(4)
        graph = model.tables(2)[0]
        self.tensors = []
        for i, t in enumerate(graph.tables(0)):
            shape = [int(x) for x in t.scalars(0, "<i4")]
            dtype = DTYPES[t.scalar(1, "b")]
            data = None
            b = buffers[t.scalar(2, "I")].vector_pos(0)
            if b is not None and b[1]:
                data = np.frombuffer(buf, dtype, b[1] // np.dtype(dtype).itemsize, b[0]).reshape(shape)
            self.tensors.append(Tensor(i, shape, dtype, t.string(3), data))
        self.inputs = [int(x) for x in graph.scalars(1, "<i4")]
        self.outputs = [int(x) for x in graph.scalars(2, "<i4")]
        self.ops = []
        for o in graph.tables(3):
            kind = codes[o.scalar(0, "I")]
            self.ops.append(Op(kind, [int(x) for x in o.scalars(1, "<i4")],
                               [int(x) for x in o.scalars(2, "<i4")], _options(kind, o.table(4))))
