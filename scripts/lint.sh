#!/usr/bin/env bash
# `make lint` (and ctest's `lint`): the house format (.clang-format) and clang-tidy's short list of
# checks (.clang-tidy) over the project's own C and C++ sources.
#
#   scripts/lint.sh [BUILD_DIR]     BUILD_DIR holds compile_commands.json (default: build)
#
# Exits 1 on any finding (each printed with its file and line), 77 when clang-format or clang-tidy
# is missing (ctest shows the test as skipped), 0 when clean. `make format` rewrites the files.
set -uo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
jobs=${JOBS:-$(nproc)}

format=$(command -v clang-format-14 || command -v clang-format || true)
# clang-tidy 22 no longer matches its checks over the system headers' code (the standard library,
# OpenCV, Eigen, JSON), which was most of clang-tidy 14's time on a unit.
tidy=$(command -v clang-tidy-22 || command -v clang-tidy || true)
if [[ -z $format || -z $tidy ]]; then
  echo "lint: skipped: clang-format or clang-tidy is not installed (scripts/setup.sh installs them)"
  exit 77
fi
if [[ ! -f $build/compile_commands.json ]]; then
  echo "lint: $build/compile_commands.json is missing: configure with CMake first (make build)"
  exit 1
fi

cd "$root"
mapfile -t sources < <(scripts/sources.sh)
failed=0

# The format: every file as clang-format would write it.
unformatted=$("$format" --dry-run "${sources[@]}" 2>&1 | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: .*-Wclang-format-violations.*/\1/p' | sort -u)
if [[ -n $unformatted ]]; then
  echo "lint: not in the house format (run make format):"
  sed 's/^/    /' <<<"$unformatted"
  failed=1
fi

# clang-tidy on every translation unit of ours (headers are checked through them), in parallel.
mapfile -t units < <(printf '%s\n' "${sources[@]}" | grep -E '\.(cpp|c)$' |
  while read -r f; do grep -q "\"file\": \"$root/$f\"" "$build/compile_commands.json" && echo "$f"; done)
out=$(mktemp -d)
printf '%s\n' "${units[@]}" |
  xargs -P "$jobs" -I{} sh -c '"$1" -p "$2" --quiet "$3" >"$4/$(echo "$3" | tr / _).log" 2>&1' _ "$tidy" "$build" {} "$out"
findings=$(cat "$out"/*.log 2>/dev/null | grep -E '(warning|error): ' | sed "s#^$root/##; s#^$build/include-roots/[^/]*/##" | sort -u)
rm -rf "$out"
if [[ -n $findings ]]; then
  echo "lint: clang-tidy findings:"
  sed 's/^/    /' <<<"$findings"
  failed=1
fi
echo "lint: ${#sources[@]} files in the house format check, ${#units[@]} translation units through clang-tidy: $( ((failed)) && echo findings || echo clean)"
exit $failed
