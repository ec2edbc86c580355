#!/usr/bin/env bash
# Installs the Debian packages smql builds against, only those that are missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ccache
  liblmdb-dev lmdb-utils libboost-dev libeigen3-dev
  antlr4 libantlr4-runtime-dev default-jre-headless
  libfmt-dev nlohmann-json3-dev libcli11-dev libreadline-dev
  wordnet-dev wordnet-base  # ASK and SIMILAR TO: the WordNet library and its dictionary (read at run time)
  libhnswlib-dev  # SIMILAR TO's index on large scenes
  catch2 libsqlite3-dev postgresql-15-postgis-3 libpq-dev python3
  postgresql-server-dev-15  # smql_pg.so, the predicates inside PostgreSQL (docs/fleet.md)
  libopencv-dev libpcl-dev colmap
  libexif-dev  # photos' EXIF focal length for an unknown camera (ingest/capture/camera_source.cpp)
  libdeflate-dev  # cameras' PNG frames (ingest/capture/png_decoder.cpp)
  libturbojpeg0-dev  # the things' crops as JPEG (ingest/capture/media.cpp), without loading OpenCV's imgcodecs
  libxnnpack-dev libpthreadpool-dev libonnx-dev libprotobuf-dev  # the models' graphs run on XNNPACK (ingest/pipeline/network.cpp)
  clang libclang-rt-14-dev llvm  # the fuzzing build (scripts/fuzz.sh): libFuzzer, ASan, UBSan, symbolizer
  clang-format clang-tidy-22  # make format, make lint (scripts/lint.sh); Debian 12's newest clang-tidy, the fastest
  tmux  # the shell's terminal test (Ctrl-C, widths)
  python3-onnx python3-protobuf python3-numpy  # the detector's set-up (scripts/detector/setup.sh)
  python3-opencv  # its verification against TF.js (scripts/detector/verify.sh)
  python3-dev pybind11-dev python3-pytest python3-venv  # the Python package (python/), its tests, pip install
  python3-open3d  # the Python package's Open3D interop, and the reader of exported PLY and GLB in the tests
  libtinygltf-dev gdal-bin  # smql export glb; GDAL's ogrinfo reads the GeoJSON export in the tests
  libcpp-httplib-dev chromium  # smql view's HTTP server; the headless browser of its test
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# npm comes with a Node.js that is already installed (NodeSource's nodejs bundles it and conflicts with
# Debian's npm package), so the package is asked for only when there is no npm command.
command -v npm >/dev/null || missing+=(npm)

if ((${#missing[@]} > 0)); then
  echo "smql setup: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    SUDO=sudo
  else
    SUDO=
  fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

"$(dirname "${BASH_SOURCE[0]}")/detector/setup.sh"

# The npm packages of web/package.json (three.js for `smql view`, the glTF validator and
# playwright-core for the tests), as package-lock.json pins them; again only when the lock changed.
web=$(cd "$(dirname "${BASH_SOURCE[0]}")/../web" && pwd)
if ! cmp -s "$web/package-lock.json" "$web/node_modules/.smql-installed-lock"; then
  echo "smql setup: installing web/package.json's npm packages"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$web/package-lock.json" "$web/node_modules/.smql-installed-lock"
fi
