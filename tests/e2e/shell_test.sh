#!/usr/bin/env bash
# The smql command as a user runs it. Usage: shell_test.sh SMQL_BINARY SHARED_DATA_DIR
set -u
smql=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0
failed=0

check() {  # check NAME COMMAND...: passes when the command succeeds
  local name=$1
  shift
  if "$@" >"$work/out" 2>"$work/err"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $name"
    sed 's/^/  out: /' "$work/out" | head -20
    sed 's/^/  err: /' "$work/err" | head -20
  fi
}

db=$work/r0
replica=$data/replica-room0/info_semantic.json

check "import replica" "$smql" import replica "$replica" --db "$db" --scene room0
check "FIND with PATH lists cushions with their paths" \
  bash -c "'$smql' '$db' -c 'FIND cushion WHERE on(sofa) PATH' | grep -q 'room0 / .*sofa#.* / cushion#'"
check "--format json is valid JSON with ids, categories, boxes and paths" \
  bash -c "'$smql' '$db' --format json -c 'FIND cushion WHERE on(sofa) PATH' | python3 -c '
import json, sys
r = json.load(sys.stdin)
assert len(r[\"rows\"]) == 7, r
for row in r[\"rows\"]:
    assert isinstance(row[\"id\"], int) and row[\"category\"] == \"cushion\"
    assert len(row[\"box\"][\"center\"]) == 3 and all(s > 0 for s in row[\"box\"][\"size\"])
    assert row[\"path\"].startswith(\"room0 / \")
'"
check "csv output has a header" bash -c "'$smql' '$db' --format csv -c 'FIND sofa' | head -1 | grep -qx 'id,category,source_id,box'"
check "RELATE answers in words" bash -c "'$smql' '$db' -c 'RELATE src#35 TO src#55' | grep -q 'is in plant-stand#'"

# Errors: non-zero exit, line and column, a caret, a hint; JSON errors for programs.
check "a syntax error exits non-zero" bash -c "! '$smql' '$db' -c 'FIND cushion WHER on(sofa)'"
check "a syntax error shows line, column and caret" \
  bash -c "'$smql' '$db' -c 'FIND cushion WHER on(sofa)' 2>&1 | grep -q 'line 1, column' && '$smql' '$db' -c 'FIND cushion WHER on(sofa)' 2>&1 | grep -q '\^'"
check "an unknown category gets a hint" bash -c "'$smql' '$db' -c 'FIND cushon' 2>&1 | grep -q 'did you mean cushion'"
check "errors in json format are JSON" \
  bash -c "'$smql' '$db' --format json -c 'FIND cushon' 2>&1 >/dev/null | python3 -c 'import json,sys; e=json.load(sys.stdin)[\"error\"]; assert e[\"column\"] == 6 and \"cushion\" in e[\"hint\"]'"

# Scripts: -f and standard input; statements before a failing one still print.
printf 'USE SCENE %s;\n-- a comment\nCOUNT cushion\n  WHERE on(sofa);\n' "'room0'" >"$work/script.smql"
check "-f runs a script" bash -c "'$smql' '$db' -f '$work/script.smql' | grep -qx '7'"
check "piped statements run" bash -c "printf 'COUNT sofa;' | '$smql' '$db' | grep -qx '2'"
check "statements before an error are printed" bash -c "'$smql' '$db' -c 'COUNT sofa; FIND nope' 2>/dev/null | grep -qx '2'"

# Bad input leaves the database as it was.
before=$("$smql" "$db" --format json -c 'SHOW SCENES')
head -c 3000 "$replica" >"$work/truncated.json"
check "a truncated file is rejected naming the file" \
  bash -c "! '$smql' import replica '$work/truncated.json' --db '$db' --scene broken 2>'$work/e' && grep -q 'truncated.json' '$work/e'"
printf 'wall_0=Wall(0,0,0,4,0,0,2.7,0.1)\nbbox_0=Bbox(chair,1,nan,0.4,0,0.5,0.5,0.9)\n' >"$work/layout.txt"
check "NaN in a SpatialLM line is rejected with file:line" \
  bash -c "! '$smql' import spatiallm '$work/layout.txt' --db '$db' 2>'$work/e' && grep -q 'layout.txt:2' '$work/e'"
check "an existing scene name is refused" bash -c "! '$smql' import replica '$replica' --db '$db' --scene room0"
after=$("$smql" "$db" --format json -c 'SHOW SCENES')
check "the database is unchanged after rejected imports" test "$before" = "$after"

# JSON export round trip.
check "export json" "$smql" export json --db "$db" --scene room0 -o "$work/room0.json"
check "import json" "$smql" import json "$work/room0.json" --db "$work/copy"
check "the copy answers the same" bash -c "diff <('$smql' '$db' -c 'FIND cushion WHERE on(sofa) PATH' | cut -c1-200 | awk '{print \$2, \$3}') <('$smql' '$work/copy' -c 'FIND cushion WHERE on(sofa) PATH' | awk '{print \$2, \$3}')"

# Ingest from the command line: a small synthetic capture, progress as JSON lines, the quality report,
# evidence crops, and the real rgbd-dining frames.
check "synth writes a capture" "$smql" synth --out "$work/capture" --seed 2 --frames 12
check "ingest logs stages as JSON lines" bash -c "'$smql' ingest '$work/capture' --db '$work/memory' --log json 2>'$work/log' >/dev/null && python3 -c '
import json, sys
stages = [json.loads(l) for l in open(sys.argv[1])]
names = [e[\"stage\"] for e in stages if e[\"event\"] == \"stage_finished\"]
assert names == [\"frames\", \"align\", \"anchors\", \"objects\", \"relations\", \"write\"], names
' '$work/log'"
check "check-ingest reports F1 as JSON" bash -c "'$smql' check-ingest '$work/memory' --truth '$work/capture/truth.json' --format json | python3 -c '
import json, sys
r = json.load(sys.stdin)
assert r[\"objects\"][\"f1\"] > 0.5 and 0 <= r[\"color_accuracy\"] <= 1, r
assert r[\"scale_error\"] is not None and r[\"scale_error\"] < 0.01, r
'"
check "ingested objects have scene-level text" bash -c "'$smql' '$work/memory' --format json -c \"FIND object WHERE text LIKE '% on the %' LIMIT 1\" | grep -q '\"id\"'"
check "DESCRIBE lists evidence" bash -c "'$smql' '$work/memory' -c 'DESCRIBE (FIND object LIMIT 1)' | grep -q 'evidence.*image/jpeg'"
node=$("$smql" "$work/memory" --format csv -c 'FIND object LIMIT 1' | sed -n 2p | cut -d, -f1)
check "export evidence writes JPEG crops" bash -c "'$smql' export evidence '#$node' '$work/crops' --db '$work/memory' >/dev/null && python3 -c '
import glob, sys
crops = glob.glob(sys.argv[1] + \"/*.jpg\")
assert crops and all(open(c, \"rb\").read(2) == bytes([0xff, 0xd8]) for c in crops), crops
' '$work/crops'"
check "evidence survives a JSON export and import" bash -c "'$smql' export json --db '$work/memory' -o '$work/memory.json' 2>/dev/null && '$smql' import json '$work/memory.json' --db '$work/copied' --scene copied >/dev/null && '$smql' '$work/copied' -c 'DESCRIBE (FIND object LIMIT 1)' | grep -q 'evidence.*image/jpeg'"
check "--update refreshes the objects seen again" bash -c "'$smql' ingest '$work/capture' --db '$work/memory' --update capture 2>/dev/null | grep -q 'objects seen again' && '$smql' '$work/memory' -c 'USE SCENE capture; COUNT object WHERE captures = 2' | tail -1 | grep -qv '^0$'"
check "--update of a missing scene is refused before any work" bash -c "! '$smql' ingest '$work/capture' --db '$work/memory' --update nowhere 2>&1 | grep -q frames"
# Ctrl-C during an ingest: it stops, says so, exits non-zero, and writes nothing.
check "a longer capture" "$smql" synth --out "$work/long" --seed 4 --frames 150
check "Ctrl-C stops an ingest with nothing written" bash -c "
  '$smql' ingest '$work/long' --db '$work/interrupted' --quiet 2>'$work/int.err' &
  pid=\$!; sleep 1.5; kill -INT \$pid; wait \$pid; status=\$?
  [ \$status -ne 0 ] && grep -q cancelled '$work/int.err' && ! '$smql' '$work/interrupted' -c 'SHOW SCENES' | grep -q long"
check "a second ingest of the same place is a new scene" bash -c "'$smql' ingest '$work/capture' --db '$work/memory' --scene again --quiet && '$smql' '$work/memory' -c 'SHOW SCENES' | grep -q again"
check "an ingest into a taken scene name is refused" bash -c "! '$smql' ingest '$work/capture' --db '$work/memory' --scene again --quiet"
check "rgbd-dining ingests without labels" bash -c "'$smql' ingest '$data/rgbd-dining' --db '$work/dining' --quiet && '$smql' '$work/dining' -c 'COUNT object' | sed -n 3p | grep -qv '^0$'"
check "a capture that is not one is refused naming it" bash -c "mkdir -p '$work/empty' && ! '$smql' ingest '$work/empty' --db '$work/x' 2>'$work/e' && grep -q empty '$work/e'"

check "smql demo runs every example" bash -c "'$smql' demo --db '$work/demo' >'$work/demo.out' && grep -q 'Explore it yourself' '$work/demo.out'"
check "an empty suite fails, with a closing line" bash -c "! '$smql' test /dev/null >'$work/t.out' && tail -1 '$work/t.out' | grep -qx '0 passed, 1 failed'"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
