#!/usr/bin/env bash
# Start-up: the wall time of one query in a fresh process, smql next to sqlite3, as a shell user
# or a script pays it. Prints a Markdown table (docs/benchmarks.md, "Start-up").
# Usage: bench/startup.sh [SMQL] [SHARED_DATA_DIR]   (defaults: build/shell/smql, ../shared/data)
# RUNS=N sets the runs per command (default 300).
set -euo pipefail
smql=$(realpath "${1:-build/shell/smql}")
data=${2:-../shared/data}
runs=${RUNS:-300}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$smql" import replica "$data/replica-room0/info_semantic.json" --db "$work/smql" --scene room0 >/dev/null
# The same nodes in SQLite, so its query reads a real table too.
"$smql" "$work/smql" -csv -noheader -c 'FIND node' | cut -d, -f1-2 >"$work/nodes.csv"
sqlite3 "$work/sqlite.db" 'CREATE TABLE nodes(id INTEGER PRIMARY KEY, category TEXT)' \
  ".import --csv $work/nodes.csv nodes" 'CREATE INDEX nodes_category ON nodes(category)'

commands=(
  "$smql $work/smql -c 'COUNT chair'"
  "$smql --version"
  "sqlite3 $work/sqlite.db 'select 1'"
  "sqlite3 $work/sqlite.db \"select count(*) from nodes where category = 'chair'\""
)
names=("smql DB -c 'COUNT chair'" "smql --version" "sqlite3 DB 'select 1'" "sqlite3 DB 'select count(*) ... chair'")

# The commands take turns, run after run, so that load from elsewhere on the machine falls on all
# of them alike rather than on whichever ran while it lasted.
python3 - "$runs" "$work/times.json" "${commands[@]}" <<'PY'
import json, os, shlex, statistics, sys, time
runs, out, commands = int(sys.argv[1]), sys.argv[2], sys.argv[3:]
argvs = [shlex.split(c) for c in commands]
samples = [{"wall": [], "cpu": []} for _ in commands]
devnull = os.open(os.devnull, os.O_WRONLY)
for round in range(20 + runs):
    for argv, sample in zip(argvs, samples):
        start = time.perf_counter()
        pid = os.posix_spawnp(argv[0], argv, os.environ, file_actions=[(os.POSIX_SPAWN_DUP2, devnull, 1)])
        _, status, usage = os.wait4(pid, 0)
        wall = time.perf_counter() - start
        if os.waitstatus_to_exitcode(status) != 0:
            sys.exit(f"failed: {shlex.join(argv)}")
        if round >= 20:
            sample["wall"].append(wall)
            sample["cpu"].append(usage.ru_utime + usage.ru_stime)
json.dump([{"median": statistics.median(s["wall"]), "min": min(s["wall"]), "cpu": statistics.median(s["cpu"])}
           for s in samples], open(out, "w"))
PY

libraries() { ldd "$1" | wc -l; }
python3 - "$work/times.json" "$runs" "$(libraries "$smql")" "$(libraries "$(command -v sqlite3)")" "${names[@]}" <<'PY'
import json, sys
times, runs, smql_libs, sqlite_libs, names = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]
results = json.load(open(times))
ms = lambda s: f"{s * 1000:.1f}"
base = results[2]["median"]
print(f"{runs} runs of each command, taking turns, after 20 warm-up rounds; wall time from spawn to exit, "
      f"CPU time user + system. Shared libraries loaded (ldd): smql {smql_libs}, sqlite3 {sqlite_libs}.")
print()
print("| command | wall, median | wall, fastest | CPU, median | wall / sqlite3 select 1 |")
print("|---|---:|---:|---:|---:|")
for name, r in zip(names, results):
    print(f"| `{name}` | {ms(r['median'])} ms | {ms(r['min'])} ms | {ms(r['cpu'])} ms | {r['median'] / base:.1f}x |")
query = results[0]["median"]
met = query < 0.020 and query <= 3 * base
print()
print(f"Target: `smql DB -c 'COUNT chair'` under 20 ms and within 3x of `sqlite3 DB 'select 1'`: "
      f"{ms(query)} ms, {query / base:.1f}x: {'met' if met else '**missed**'}.")
PY
