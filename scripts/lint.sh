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

# clang-tidy on every translation unit the build compiles from our files, in parallel (headers are
# checked through them). The unity build (CMakeLists.txt) compiles most files in chunks that include
# several of them (<target>.dir/Unity/unity_N_cxx.cxx), and clang-tidy parses such a chunk once for all
# it includes: the standard library's and the other common headers' 100,000 lines once a chunk, not
# once a file. Every file of ours that the build compiles is checked, alone or in its chunk.
ours=$(printf '%s\n' "${sources[@]}" | grep -E '\.(cpp|c)$' | sed "s#^#$root/#")
out=$(mktemp -d)
# A unit is checked with the configuration of its files' folder, as `clang-tidy FILE` there reads it
# (the libraries' .clang-tidy adds the function-size limit to the root's list): a chunk lies in the
# build folder, where clang-tidy would find no configuration or the root's. A target's files, and so
# a chunk's, share one folder's configuration.
declare -A configs=()
config=
configure_for() {
  local dir=${1%/*}
  config=${configs[$dir]:-}
  if [[ -z $config ]]; then
    config=$out/config-${#configs[@]}.yaml
    "$tidy" --dump-config "$1" >"$config" 2>/dev/null
    configs[$dir]=$config
  fi
}
units=()
checked=()
while read -r file; do
  if [[ $file == */Unity/unity_*_c*.c* ]]; then
    mapfile -t included < <(sed -n 's/^#include "\(.*\)"$/\1/p' "$file" | grep -Fx -f <(printf '%s\n' "$ours"))
    ((${#included[@]} > 0)) || continue
    configure_for "${included[0]}"
    checked+=("${included[@]}")
  elif grep -Fxq "$file" <<<"$ours"; then
    configure_for "$file"
    checked+=("$file")
  else
    continue
  fi
  units+=("$config" "$file")
done < <(sed -n 's/^ *"file": "\(.*\)",\{0,1\}$/\1/p' "$build/compile_commands.json" | sort -u)
if ((${#units[@]} == 0)); then
  echo "lint: no file of ours among the units of $build/compile_commands.json: configure and build first (make build)"
  exit 1
fi
# A run that fails without a finding (a unit that does not parse, a bad option) is a finding too.
printf '%s\n' "${units[@]}" |
  xargs -d '\n' -n 2 -P "$jobs" sh -c 'log="$2/$(echo "$5" | tr / _).log"
    "$1" --config-file="$4" -p "$3" --quiet "$5" >"$log" 2>&1 ||
      grep -Eq "(warning|error): " "$log" || echo "$5: error: clang-tidy failed without a finding" >>"$log"' \
    _ "$tidy" "$out" "$build"
findings=$(cat "$out"/*.log 2>/dev/null | grep -E '(warning|error): ' | sed "s#^$root/##; s#^$build/include-roots/[^/]*/##" | sort -u)
rm -rf "$out"
if [[ -n $findings ]]; then
  echo "lint: clang-tidy findings:"
  sed 's/^/    /' <<<"$findings"
  failed=1
fi
echo "lint: ${#sources[@]} files in the house format check, $(printf '%s\n' "${checked[@]}" | sort -u | wc -l) through clang-tidy in $((${#units[@]} / 2)) translation units: $( ((failed)) && echo findings || echo clean)"
exit $failed
