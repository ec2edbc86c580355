#!/usr/bin/python3
"""Checks the ONNX conversion against the original model: runs the TF.js graph
(Node, @tensorflow/tfjs on its pure JavaScript CPU backend) and the ONNX graph
(OpenCV's DNN, which smql's XNNPACK runner is held to) on the same input blobs made from real images,
and prints the largest absolute difference of every raw output.

Usage: verify.py MODEL.json MODEL.onnx TFJS_DIR IMAGE...
TFJS_DIR is a folder where `npm install @tensorflow/tfjs` was run (verify.sh makes one).
"""
import os
import subprocess
import sys
import tempfile

import cv2
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
# The pre-processing of ingest/pipeline/detector.cpp: 416x416, BGR, NanoDet's mean and deviation.
MEAN = np.array([103.53, 116.28, 123.675], np.float32)
STD = np.array([57.375, 57.12, 58.395], np.float32)


def blob(image_path):
    image = cv2.imread(image_path)
    if image is None:
        raise SystemExit(f"{image_path}: not an image")
    resized = cv2.resize(image, (416, 416), interpolation=cv2.INTER_LINEAR).astype(np.float32)
    return np.ascontiguousarray(((resized - MEAN) / STD).transpose(2, 0, 1)[None])


def main():
    if len(sys.argv) < 5:
        raise SystemExit(__doc__)
    model_json, model_onnx, tfjs_dir, images = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    net = cv2.dnn.readNetFromONNX(model_onnx)
    names = net.getUnconnectedOutLayersNames()
    worst = 0.0
    with tempfile.TemporaryDirectory() as work:
        for image in images:
            x = blob(image)
            x.tofile(os.path.join(work, "input.bin"))
            subprocess.run(["node", os.path.join(HERE, "run_tfjs.mjs"), os.path.abspath(model_json),
                            os.path.join(work, "input.bin"), work], cwd=tfjs_dir, check=True, stdout=subprocess.DEVNULL)
            net.setInput(x)
            outputs = net.forward(names)
            diffs = []
            for name, mine in zip(names, outputs):
                reference = np.fromfile(os.path.join(work, f"{name}.bin"), np.float32).reshape(mine.shape)
                diffs.append((name, list(mine.shape), float(np.abs(mine - reference).max()),
                              float(np.abs(reference).max())))
            for name, shape, diff, scale in diffs:
                print(f"{os.path.basename(image)}  {name:10s} {str(shape):16s} max |onnx - tfjs| = {diff:.2e}"
                      f"  (max |tfjs| = {scale:.2f})")
            worst = max(worst, max(d[2] for d in diffs))
    print(f"largest difference over {len(images)} images: {worst:.2e}")


if __name__ == "__main__":
    main()
