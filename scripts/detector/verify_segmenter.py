#!/usr/bin/python3
"""Checks the ONNX conversion of the DeepLab VOC segmenter against the original:
runs the TF.js graph (Node, @tensorflow/tfjs on its pure JavaScript CPU
backend) and each ONNX model (OpenCV's DNN, 2 threads, which smql's XNNPACK runner is held to) on real
frames, and prints per frame and model:
  - max |onnx - tfjs| of the logits, where the ONNX model's grid is the TF.js one;
  - agree: the share of the frame's pixels whose arg max agrees (both sets of
    logits resized bilinearly to the frame's size first);
  - objects: the same over the pixels that either side labels other than background;
  - the time of one forward pass.

The reference is the TF.js graph on the frame resized to 513x513 (what the
converter's default model takes). With --aspect, a second reference is the
TF.js graph on the frame resized to a longest side of 513 (e.g. 385x513 for
640x480), which the graph pads to 513x513 itself: ONNX models whose input has
the frame's aspect are compared with that one.

Usage: verify_segmenter.py [--aspect] [--overlays DIR] [--cache DIR] [--names voc.names] MODEL.json TFJS_DIR ONNX[,ONNX...] IMAGE...
TFJS_DIR is a folder where `npm install @tensorflow/tfjs` was run (verify.sh makes one). With
--overlays, the label maps of each ONNX model and of its reference are drawn over each frame into
DIR as PNG (FOLDER_FRAME_MODEL.png, FOLDER being the frame's folder's parent). With --cache, the
TF.js outputs are kept in DIR and taken from there when present.
"""
import os
import subprocess
import sys
import tempfile
import time

import cv2
import numpy as np
import onnx

HERE = os.path.dirname(os.path.abspath(__file__))
NATIVE = 513
CLASSES = 21


def palette():
    """PASCAL VOC's colour map (BGR)."""
    colours = np.zeros((256, 3), np.uint8)
    for label in range(256):
        c, r, g, b = label, 0, 0, 0
        for shift in range(7, -1, -1):
            r |= ((c >> 0) & 1) << shift
            g |= ((c >> 1) & 1) << shift
            b |= ((c >> 2) & 1) << shift
            c >>= 3
        colours[label] = (b, g, r)
    return colours


def input_size(path):
    dims = onnx.load(path).graph.input[0].type.tensor_type.shape.dim
    return dims[2].dim_value, dims[3].dim_value  # height, width


def tfjs(model_json, tfjs_dir, work, rgb, cache=None):
    """The TF.js graph's logits ([21, 513, 513] grid, cropped to the image) and label map."""
    if cache and os.path.exists(cache):
        with np.load(cache) as saved:
            return saved["logits"], saved["labels"]
    h, w = rgb.shape[:2]
    rgb.astype(np.int32).tofile(os.path.join(work, "input.bin"))
    outputs = ["ResizeBilinear_3", "SemanticPredictions"]
    subprocess.run(["node", os.path.join(HERE, "run_tfjs.mjs"), os.path.abspath(model_json),
                    os.path.join(work, "input.bin"), work, "--shape", f"1,{h},{w},3", "--dtype", "int32",
                    "--outputs", ",".join(outputs)], cwd=tfjs_dir, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    logits = np.fromfile(os.path.join(work, "ResizeBilinear_3.bin"), np.float32).reshape(NATIVE, NATIVE, CLASSES)
    labels = np.fromfile(os.path.join(work, "SemanticPredictions.bin"), np.float32).reshape(h, w).astype(np.int64)
    logits = np.ascontiguousarray(logits[:h, :w].transpose(2, 0, 1))
    if cache:
        np.savez(cache, logits=logits, labels=labels)
    return logits, labels


def to_frame(logits, shape):
    """Per-class logits [21, h, w] resized to the frame, and their arg max."""
    resized = cv2.resize(np.ascontiguousarray(logits.transpose(1, 2, 0)), (shape[1], shape[0]),
                         interpolation=cv2.INTER_LINEAR)
    return resized.argmax(2)


def overlay(frame, labels, names, colours, title):
    out = (0.5 * frame + 0.5 * colours[labels]).astype(np.uint8)
    cv2.putText(out, title, (8, 22), cv2.FONT_HERSHEY_SIMPLEX, 0.6, (255, 255, 255), 2, cv2.LINE_AA)
    present = [(k, n) for k, n in zip(*np.unique(labels, return_counts=True)) if k != 0 and n > 0.002 * labels.size]
    for row, (label, count) in enumerate(sorted(present, key=lambda p: -p[1])):
        y = 48 + 24 * row
        cv2.rectangle(out, (8, y - 14), (26, y + 4), colours[label].tolist(), -1)
        cv2.putText(out, f"{names[label]} {100 * count / labels.size:.0f}%", (32, y), cv2.FONT_HERSHEY_SIMPLEX,
                    0.55, (255, 255, 255), 2, cv2.LINE_AA)
    return out


def main():
    args = sys.argv[1:]
    aspect, overlays, cache, names = False, None, None, [str(i) for i in range(CLASSES)]
    while args and args[0].startswith("--"):
        flag = args.pop(0)
        if flag == "--aspect":
            aspect = True
        elif flag == "--overlays":
            overlays = args.pop(0)
        elif flag == "--cache":
            cache = args.pop(0)
            os.makedirs(cache, exist_ok=True)
        elif flag == "--names":
            names = open(args.pop(0)).read().split("\n")[:CLASSES]
        else:
            raise SystemExit(__doc__)
    if len(args) < 4:
        raise SystemExit(__doc__)
    model_json, tfjs_dir, models, images = args[0], args[1], args[2].split(","), args[3:]
    cv2.setNumThreads(2)
    nets = []
    for path in models:
        net = cv2.dnn.readNetFromONNX(path)
        nets.append((os.path.basename(path), input_size(path), net))
    colours = palette()
    if overlays:
        os.makedirs(overlays, exist_ok=True)
    summary = {name: {"agree": [], "objects": [], "diff": [], "ms": [], "counts": np.zeros(4)} for name, _, _ in nets}
    with tempfile.TemporaryDirectory() as work:
        for image in images:
            frame = cv2.imread(image)
            if frame is None:
                raise SystemExit(f"{image}: not an image")
            references = {}
            stem = os.path.basename(os.path.dirname(os.path.dirname(os.path.abspath(image))))
            stem += "_" + os.path.splitext(os.path.basename(image))[0]
            cached = (lambda key: os.path.join(cache, f"{stem}_{key}.npz")) if cache else (lambda key: None)
            square = cv2.resize(frame, (NATIVE, NATIVE), interpolation=cv2.INTER_LINEAR)
            references["square"] = tfjs(model_json, tfjs_dir, work, cv2.cvtColor(square, cv2.COLOR_BGR2RGB),
                                        cached("square"))
            fh, fw = frame.shape[:2]
            scale = NATIVE / max(fh, fw)
            kept = (round(fh * scale), round(fw * scale))
            if aspect:
                resized = cv2.resize(frame, (kept[1], kept[0]), interpolation=cv2.INTER_LINEAR)
                references["aspect"] = tfjs(model_json, tfjs_dir, work, cv2.cvtColor(resized, cv2.COLOR_BGR2RGB),
                                            cached("aspect"))
            frame_labels = {key: to_frame(logits, frame.shape) for key, (logits, _) in references.items()}
            # The graph's own arg max is the one of its logits (a check of the reading of the outputs).
            for key, (logits, labels) in references.items():
                if not np.array_equal(logits.argmax(0), labels):
                    print(f"{os.path.basename(image)}: tfjs {key}: its label map is not the arg max of its logits")
            for name, (h, w), net in nets:
                blob = cv2.dnn.blobFromImage(frame, 1 / 127.5, (w, h), (127.5, 127.5, 127.5), swapRB=True, crop=False)
                net.setInput(blob)
                logits = net.forward("logits")[0]
                times = []
                for _ in range(3):
                    started = time.perf_counter()
                    net.setInput(blob)
                    net.forward("logits")
                    times.append(1000 * (time.perf_counter() - started))
                key = "aspect" if aspect and abs(w / h - fw / fh) < 0.05 and (h, w) != (NATIVE, NATIVE) else "square"
                ref_logits, ref_labels = references[key]
                diff = ""
                if ref_logits.shape[1:] == logits.shape[1:]:
                    d = float(np.abs(logits - ref_logits).max())
                    diff = f"max |onnx - tfjs| = {d:.2e} (max |tfjs| = {np.abs(ref_logits).max():.1f}), " \
                           f"label agreement on the {h}x{w} grid {np.mean(logits.argmax(0) == ref_labels):.5f}; "
                    summary[name]["diff"].append(d)
                mine = to_frame(logits, frame.shape)
                theirs = frame_labels[key]
                agree = float(np.mean(mine == theirs))
                either = (mine != 0) | (theirs != 0)
                objects = float(np.mean(mine[either] == theirs[either])) if either.any() else 1.0
                summary[name]["agree"].append(agree)
                summary[name]["objects"].append(objects)
                summary[name]["ms"].append(np.median(times))
                summary[name]["counts"] += [np.sum(mine == theirs), mine.size,
                                            np.sum(mine[either] == theirs[either]), np.sum(either)]
                print(f"{os.path.basename(image)}  {name} [{h}x{w}] vs tfjs {key}: {diff}"
                      f"agree {agree:.4f}, objects {objects:.4f}; {np.median(times):.0f} ms")
                if overlays:
                    panels = [overlay(frame, theirs, names, colours, f"tfjs {key}"),
                              overlay(frame, mine, names, colours, f"{name} {h}x{w}")]
                    cv2.imwrite(os.path.join(overlays, f"{stem}_{os.path.splitext(name)[0]}.png"), np.hstack(panels))
    print("summary (agree, objects: over all the frames' pixels, and the lowest frame; time: median):")
    for name, s in summary.items():
        diff = f"largest |onnx - tfjs| {max(s['diff']):.2e}, " if s["diff"] else ""
        same, pixels, objects_same, objects = s["counts"]
        print(f"  {name}: {diff}agree {same / pixels:.4f} (lowest {min(s['agree']):.4f}), "
              f"objects {objects_same / max(objects, 1):.4f} (lowest {min(s['objects']):.4f}), "
              f"{np.median(s['ms']):.0f} ms")


if __name__ == "__main__":
    main()
