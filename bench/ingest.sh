#!/usr/bin/env bash
# Ingest throughput and memory, end to end, with the per-stage times the ingest reports and the
# peak resident memory: a synthetic RGB-D capture of FRAMES 640x480 frames, or a real capture.
# Usage: bench/ingest.sh [FRAMES | CAPTURE] [SMQL] [INGEST OPTION...]
#        (defaults: 300, build/shell/smql; e.g. bench/ingest.sh ../shared/data/captures/tum-fr1-rpy
#        build/shell/smql --fps 0)
set -euo pipefail
source=${1:-300}
smql=${2:-build/shell/smql}
shift $(($# < 2 ? $# : 2))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [[ -d $source ]]; then
  capture=$source
else
  capture=$work/capture
  "$smql" synth --out "$capture" --seed 5 --frames "$source" >/dev/null
fi
/usr/bin/time -f 'peak_rss_kib %M' "$smql" ingest "$capture" --db "$work/memory" --log json "$@" \
  >"$work/out" 2>"$work/log"

python3 - "$work/log" <<'PY'
import json, sys
stages, rss, frames = [], 0, 0
for line in open(sys.argv[1]):
    if line.startswith("peak_rss_kib"):
        rss = int(line.split()[1])
        continue
    event = json.loads(line)
    if event.get("event") == "stage_finished":
        stages.append((event["stage"], event["seconds"], event["summary"]))
        if event["stage"] == "frames":  # "121 frames, ..."
            frames = int(event["summary"].split()[0])
total = sum(s for _, s, _ in stages)
print(f"| frames | all stages | frames/s | peak memory |")
print(f"|---:|---:|---:|---:|")
print(f"| {frames} | {total:.1f} s | {frames / total:.1f} | {rss / 1024:.0f} MiB |")
print()
print("| stage | seconds | frames/s | share | what |")
print("|---|---:|---:|---:|---|")
for name, seconds, summary in stages:
    rate = f"{frames / seconds:.0f}" if seconds >= 0.01 else ""  # as the log: under 10 ms says nothing
    print(f"| {name} | {seconds:.2f} | {rate} | {100 * seconds / total:.0f}% | {summary} |")
PY
