#!/usr/bin/env bash
# Installs the Debian packages smql builds against, only those that are missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ccache
  liblmdb-dev lmdb-utils libboost-dev libeigen3-dev
  antlr4 libantlr4-runtime-dev default-jre-headless
  libfmt-dev nlohmann-json3-dev libcli11-dev libreadline-dev
  catch2 libsqlite3-dev python3
  libopencv-dev libpcl-dev colmap
  clang libclang-rt-14-dev llvm  # the fuzzing build (scripts/fuzz.sh): libFuzzer, ASan, UBSan, symbolizer
  tmux  # the shell's terminal test (Ctrl-C, widths)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

echo "smql setup: installing ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  SUDO=sudo
else
  SUDO=
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
