#!/usr/bin/python3
"""Checks oid_ssd.onnx (made by oid_tflite_to_onnx.py --raw) against a numpy
reference interpreter of the TFLite graph it came from, on real frames, then
runs detection (MediaPipe's decoding, best class per anchor, score threshold,
class-agnostic NMS) and draws the boxes with their labels.

Usage: oid_verify.py [--threshold=S] MODEL.tflite MODEL_RAW.onnx NAMES OUT_DIR FRAME...
  S               score threshold of the drawn detections (default 0.5, MediaPipe's)
  MODEL_RAW.onnx  converted with --raw (so its raw outputs can be compared)
  NAMES           oid.names (23 labels, the ONNX scores' columns)
Prints per frame the max abs difference of raw box encodings, raw class
logits, decoded boxes and sigmoid scores, the detections, and the time per
frame of the OpenCV DNN forward pass (2 threads).
"""
import os
import sys
import time

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import oid_tflite  # noqa: E402
import oid_tflite_to_onnx as conv  # noqa: E402

SCORE_THRESHOLD = 0.5
NMS_IOU = 0.5
MAX_DETECTIONS = 100


# -- numpy reference interpreter of the TFLite graph (float64) ------------------------------------

def _same_pads(size, k, s, d):
    eff = (k - 1) * d + 1
    out = -(-size // s)
    total = max((out - 1) * s + eff - size, 0)
    return total // 2, total - total // 2


def _activate(x, act):
    if act == "RELU":
        return np.maximum(x, 0)
    if act == "RELU6":
        return np.clip(x, 0, 6)
    return x


def _conv(x, w, b, stride, padding, dilation, depthwise):
    """TFLite CONV_2D (w OHWI) / DEPTHWISE_CONV_2D (w 1HWO) on NHWC x."""
    n, h, wd, c = x.shape
    kh, kw = w.shape[1], w.shape[2]
    (sh, sw), (dh, dw) = stride, dilation
    if padding == 0:  # SAME
        pt, pb = _same_pads(h, kh, sh, dh)
        pl, pr = _same_pads(wd, kw, sw, dw)
    else:  # VALID
        pt = pb = pl = pr = 0
    xp = np.pad(x, ((0, 0), (pt, pb), (pl, pr), (0, 0)))
    oh = (h + pt + pb - (kh - 1) * dh - 1) // sh + 1
    ow = (wd + pl + pr - (kw - 1) * dw - 1) // sw + 1
    cout = w.shape[3] if depthwise else w.shape[0]
    out = np.zeros((n, oh, ow, cout), np.float64)
    for i in range(kh):
        for j in range(kw):
            patch = xp[:, i * dh:i * dh + (oh - 1) * sh + 1:sh, j * dw:j * dw + (ow - 1) * sw + 1:sw, :]
            if depthwise:
                out += np.repeat(patch, cout // c, axis=3) * w[0, i, j, :]
            else:
                out += patch @ w[:, i, j, :].T
    return out + b


def run_reference(model, image_nhwc):
    """Runs the TFLite graph on an NHWC float image; returns the graph outputs."""
    values = {}
    for t in model.tensors:
        if t.data is not None:
            values[t.index] = t.data.astype(np.float64) if t.dtype in (np.float32, np.float16) else t.data
    values[model.inputs[0]] = np.asarray(image_nhwc, np.float64)
    for op in model.ops:
        ins = [values.get(i) if i >= 0 else None for i in op.inputs]
        k, o = op.kind, op.options
        if k == "DEQUANTIZE":
            y = ins[0].astype(np.float64)
        elif k in ("CONV_2D", "DEPTHWISE_CONV_2D"):
            b = ins[2] if len(ins) > 2 and ins[2] is not None else 0
            y = _conv(ins[0], ins[1], b, o["stride"], o["padding"], o["dilation"], k == "DEPTHWISE_CONV_2D")
            y = _activate(y, o["activation"])
        elif k == "ADD":
            y = _activate(ins[0] + ins[1], o["activation"])
        elif k == "RESHAPE":
            y = ins[0].reshape(model.tensors[op.outputs[0]].shape)
        elif k == "CONCATENATION":
            y = _activate(np.concatenate(ins, axis=o["axis"]), o["activation"])
        elif k == "LOGISTIC":
            y = 1 / (1 + np.exp(-ins[0]))
        else:
            raise NotImplementedError("reference: operator %s" % k)
        values[op.outputs[0]] = y
    return [values[i] for i in model.outputs]


# -- detection --------------------------------------------------------------------------------------

def preprocess(bgr, size=conv.INPUT_SIZE):
    """The whole frame stretched to size x size, RGB, in [-1,1]: NCHW blob."""
    return cv2.dnn.blobFromImage(bgr, 1 / 127.5, (size, size), (127.5, 127.5, 127.5), swapRB=True, crop=False)


def iou(a, b):
    """a [4], b [M,4] as ymin,xmin,ymax,xmax."""
    y0, x0 = np.maximum(a[0], b[:, 0]), np.maximum(a[1], b[:, 1])
    y1, x1 = np.minimum(a[2], b[:, 2]), np.minimum(a[3], b[:, 3])
    inter = np.clip(y1 - y0, 0, None) * np.clip(x1 - x0, 0, None)
    area = lambda r: (r[..., 2] - r[..., 0]) * (r[..., 3] - r[..., 1])  # noqa: E731
    return inter / np.maximum(area(a) + area(b) - inter, 1e-9)


def detect(boxes, scores, threshold=SCORE_THRESHOLD):
    """MediaPipe's way: best class per anchor, threshold, class-agnostic NMS.
    Returns [(score, label index into oid.names, [ymin,xmin,ymax,xmax])]."""
    boxes, scores = boxes[0], scores[0]
    label = scores.argmax(1)
    best = scores[np.arange(len(scores)), label]
    keep = np.where(best >= threshold)[0]
    keep = keep[np.argsort(-best[keep], kind="stable")]
    out = []
    while len(keep) and len(out) < MAX_DETECTIONS:
        i = keep[0]
        out.append((float(best[i]), int(label[i]), boxes[i]))
        rest = keep[1:]
        keep = rest[iou(boxes[i], boxes[rest]) <= NMS_IOU]
    return out


def draw(bgr, dets, names, path):
    img = bgr.copy()
    h, w = img.shape[:2]
    for score, label, (y0, x0, y1, x1) in dets:
        colour = tuple(int(c) for c in np.random.RandomState(label).randint(60, 255, 3))
        p0 = (int(round(np.clip(x0, 0, 1) * w)), int(round(np.clip(y0, 0, 1) * h)))
        p1 = (int(round(np.clip(x1, 0, 1) * w)), int(round(np.clip(y1, 0, 1) * h)))
        cv2.rectangle(img, p0, p1, colour, 2)
        text = "%s %.2f" % (names[label], score)
        (tw, th), _ = cv2.getTextSize(text, cv2.FONT_HERSHEY_SIMPLEX, 0.5, 1)
        ty = max(p0[1], th + 4)
        cv2.rectangle(img, (p0[0], ty - th - 4), (p0[0] + tw + 2, ty), colour, -1)
        cv2.putText(img, text, (p0[0] + 1, ty - 3), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (0, 0, 0), 1, cv2.LINE_AA)
    cv2.imwrite(path, img)


def main(argv):
    threshold = SCORE_THRESHOLD
    args = []
    for a in argv[1:]:
        if a.startswith("--threshold="):
            threshold = float(a.split("=", 1)[1])
        else:
            args.append(a)
    if len(args) < 5:
        sys.exit(__doc__)
    tflite_path, onnx_path, names_path, out_dir = args[:4]
    frames = args[4:]
    names = [l.rstrip("\n") for l in open(names_path)]
    model = oid_tflite.Model(tflite_path)
    anchors = conv.ssd_anchors()
    cv2.setNumThreads(2)
    net = cv2.dnn.readNetFromONNX(onnx_path)
    net.setPreferableBackend(cv2.dnn.DNN_BACKEND_OPENCV)
    net.setPreferableTarget(cv2.dnn.DNN_TARGET_CPU)
    os.makedirs(out_dir, exist_ok=True)
    worst = np.zeros(4)
    times = []
    for path in frames:
        bgr = cv2.imread(path)
        blob = preprocess(bgr)
        net.setInput(blob)
        t0 = time.perf_counter()
        boxes, scores, raw_boxes, raw_scores = net.forward(["boxes", "scores", "raw_boxes", "raw_scores"])
        times.append(time.perf_counter() - t0)
        ref_boxes, ref_scores = run_reference(model, blob.transpose(0, 2, 3, 1))
        dec_boxes, dec_scores = conv.decode(ref_boxes, ref_scores, anchors)
        diffs = np.array([np.abs(raw_boxes - ref_boxes).max(), np.abs(raw_scores - ref_scores).max(),
                          np.abs(boxes - dec_boxes).max(), np.abs(scores - dec_scores).max()])
        worst = np.maximum(worst, diffs)
        dets = detect(boxes, scores, threshold)
        ref_dets = detect(dec_boxes, dec_scores, threshold)
        same = [d[1] for d in dets] == [d[1] for d in ref_dets]
        name = "%s_%s.png" % (os.path.basename(os.path.dirname(os.path.dirname(path))),
                              os.path.splitext(os.path.basename(path))[0])
        draw(bgr, dets, names, os.path.join(out_dir, name))
        print("%s: max|diff| raw boxes %.2e logits %.2e boxes %.2e scores %.2e; %d detections%s: %s" % (
            path, *diffs, len(dets), "" if same else " (reference differs!)",
            ", ".join("%s %.2f" % (names[l], s) for s, l, _ in dets)))
    # timing: repeat forward passes on the last blob
    for _ in range(3):
        net.forward(["boxes", "scores"])
    t0 = time.perf_counter()
    runs = 20
    for _ in range(runs):
        net.forward(["boxes", "scores"])
    per = (time.perf_counter() - t0) / runs
    print("worst max|diff| over %d frames: raw boxes %.2e logits %.2e decoded boxes %.2e scores %.2e" % (
        len(frames), *worst))
    print("OpenCV %s DNN CPU, 2 threads, %dx%d: %.1f ms per forward (mean of %d)" % (
        cv2.__version__, conv.INPUT_SIZE, conv.INPUT_SIZE, per * 1000, runs))


if __name__ == "__main__":
    main(sys.argv)
