#!/usr/bin/env bash
# Ingest throughput and memory: a synthetic RGB-D capture of FRAMES 640x480 frames, ingested
# end to end, with the per-stage times the ingest reports and the peak resident memory.
# Usage: bench/ingest.sh [FRAMES] [SMQL]   (defaults: 300, build/shell/smql)
set -euo pipefail
frames=${1:-300}
smql=${2:-build/shell/smql}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$smql" synth --out "$work/capture" --seed 5 --frames "$frames" >/dev/null
/usr/bin/time -f 'peak_rss_kib %M' "$smql" ingest "$work/capture" --db "$work/memory" --log json \
  >"$work/out" 2>"$work/log"

python3 - "$work/log" "$work/out" "$frames" <<'PY'
import json, sys
log, out, frames = sys.argv[1], sys.argv[2], int(sys.argv[3])
stages, rss = [], 0
for line in open(log):
    if line.startswith("peak_rss_kib"):
        rss = int(line.split()[1])
        continue
    event = json.loads(line)
    if event.get("event") == "stage_finished":
        stages.append((event["stage"], event["seconds"], event["summary"]))
total = sum(s for _, s, _ in stages)
print(f"| frames | all stages | frames/s | peak memory |")
print(f"|---:|---:|---:|---:|")
print(f"| {frames} | {total:.1f} s | {frames / total:.1f} | {rss / 1024:.0f} MiB |")
print()
print("| stage | seconds | share | what |")
print("|---|---:|---:|---|")
for name, seconds, summary in stages:
    print(f"| {name} | {seconds:.2f} | {100 * seconds / total:.0f}% | {summary} |")
PY
