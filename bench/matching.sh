#!/usr/bin/env bash
# The ingest's feature matching against COLMAP's matcher (bench/matching_bench.cpp) on ../shared's real
# photos: each photo set's features extracted as the ingest extracts them (`smql ingest PHOTOS --colmap-dir
# DIR`, whose work folder is kept; the ingest itself may refuse the capture), then matched all against all.
# Usage: bench/matching.sh [BUILD] [ROUNDS]   (defaults: build, 3)
set -euo pipefail
build=${1:-build}
rounds=${2:-3}
data=$(dirname "$0")/../../shared/data/captures
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# photos, images matched all against all, name
while read -r photos images name; do
  "$build/shell/smql" ingest "$data/$photos" --db "$work/$photos.db" --colmap-dir "$work/$photos" >"$work/$photos.log" 2>&1 ||
    true  # refused or stored: the features are in the work folder either way
  "$build/bench/smql_bench_matching" "$work/$photos/database.db" --images "$images" --rounds "$rounds" \
    --name "$name"
  echo
done <<'CAPTURES'
tum-fr3-office-photos 17 TUM fr3 office photos
mipnerf360-kitchen 8 Mip-NeRF 360 kitchen
CAPTURES
