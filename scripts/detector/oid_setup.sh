#!/usr/bin/env bash
# Prepares the Open Images detector: MediaPipe Objectron's SSD MobileNetV2 (OIDv4, 23 labels:
# Chair, Table, Desk, Computer monitor, Book, ...) from the npm package @mediapipe/objectron
# (Apache-2.0). The model is a TFLite flatbuffer (fp16 weights) packed with its label map in an
# emscripten file-packager blob; it is cut out by the offsets the package's loader lists, converted
# to ONNX with the SSD box decoding folded in by oid_tflite_to_onnx.py, and installed as oid_ssd.onnx
# with oid.names (the label of each score column, one a line) in SMQL_MODEL_DIR.
# Idempotent: nothing is done when both are installed. Needs npm, python3-onnx, python3-numpy.
set -euo pipefail

model_dir=${SMQL_MODEL_DIR:-/usr/local/share/smql/models}
package=@mediapipe/objectron@0.4.1675468480
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

if [[ -f $model_dir/oid_ssd.onnx && -f $model_dir/oid.names ]]; then
  exit 0
fi

echo "smql setup: preparing the OID detector in $model_dir"
work=$(mktemp -d /tmp/smql-oid-XXXXXX)
trap 'rm -rf "$work"' EXIT

(cd "$work" && npm pack --silent "$package" >/dev/null)
tar -xzf "$work"/mediapipe-objectron-*.tgz -C "$work" \
  package/objectron_solution_packed_assets.data package/objectron_solution_packed_assets_loader.js \
  package/package.json

# Cut the two files out of the packed blob by the offsets in the loader's file list.
/usr/bin/python3 - "$work/package" "$work" <<'EOF'
import json, os, re, sys
src, dst = sys.argv[1], sys.argv[2]
loader = open(os.path.join(src, "objectron_solution_packed_assets_loader.js")).read()
files = json.loads(re.search(r'loadPackage\((\{"files".*?\})\)', loader).group(1))["files"]
blob = open(os.path.join(src, "objectron_solution_packed_assets.data"), "rb").read()
wanted = {"object_detection_oidv4_labelmap.txt": "labelmap.txt",
          "object_detection_ssd_mobilenetv2_oidv4_fp16.tflite": "oid.tflite"}
for f in files:
    name = os.path.basename(f["filename"])
    if name in wanted:
        open(os.path.join(dst, wanted.pop(name)), "wb").write(blob[f["start"]:f["end"]])
if wanted:
    sys.exit("oid_setup: not in the packed assets: %s" % ", ".join(wanted))
EOF

/usr/bin/python3 "$here/oid_tflite_to_onnx.py" "$work/oid.tflite" "$work/oid_ssd.onnx" \
  "$work/labelmap.txt" "$work/oid.names"
cat >"$work/NOTICE" <<EOF
oid_ssd.onnx and oid.names are converted from object_detection_ssd_mobilenetv2_oidv4_fp16.tflite and
object_detection_oidv4_labelmap.txt of the npm package $package (MediaPipe Objectron, by Google),
licensed under the Apache License, Version 2.0 (the "license" field of its package.json).
EOF

SUDO=
if ! mkdir -p "$model_dir" 2>/dev/null || [[ ! -w $model_dir ]]; then
  SUDO=sudo
fi
$SUDO install -d "$model_dir"
$SUDO install -m 644 "$work/oid_ssd.onnx" "$model_dir/oid_ssd.onnx"
$SUDO install -m 644 "$work/oid.names" "$model_dir/oid.names"
$SUDO install -m 644 "$work/NOTICE" "$model_dir/NOTICE.objectron"
echo "smql setup: OID detector installed: $model_dir/oid_ssd.onnx"
