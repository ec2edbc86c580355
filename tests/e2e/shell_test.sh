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
check "LIMIT 0 after NEAREST TO answers no rows" bash -c "'$smql' '$db' -csv -c 'FIND blinds NEAREST TO door LIMIT 0' | wc -l | grep -qx 1"
check "FIND with PATH lists cushions with their paths" \
  bash -c "'$smql' '$db' -c 'FIND cushion WHERE on(sofa) PATH' | grep -q 'room0 / .*sofa#.* / cushion#'"
check "--format json is valid JSON with ids, categories, boxes and paths" \
  bash -c "'$smql' '$db' --format json -c 'FIND cushion WHERE on(sofa) PATH' | python3 -c '
import json, sys
r = json.load(sys.stdin)[0]
assert len(r[\"rows\"]) == 7, r
for row in r[\"rows\"]:
    assert isinstance(row[\"id\"], int) and row[\"category\"] == \"cushion\"
    assert len(row[\"box\"][\"center\"]) == 3 and all(s > 0 for s in row[\"box\"][\"size\"])
    assert row[\"path\"].startswith(\"room0 / \")
'"
check "csv output has a header" bash -c "'$smql' '$db' --format csv -c 'FIND sofa' | head -1 | grep -qx 'id,category,source_id,box'"
check "RELATE answers in words" bash -c "'$smql' '$db' -c 'RELATE src#35 TO src#55' | grep -q 'is in plant-stand#'"

# As sqlite3 users type it: single-dash long options, a statement after the database, output modes.
check "a statement after the database runs" bash -c "'$smql' '$db' 'COUNT sofa' | grep -qx '2'"
check "-csv is CSV (not -c sv)" bash -c "'$smql' '$db' -csv 'FIND sofa' | head -1 | grep -qx 'id,category,source_id,box'"
check "-json prints one array for several statements" bash -c "'$smql' '$db' -json 'COUNT sofa; FIND sofa; SET near = 1 m' | python3 -c '
import json, sys
r = json.load(sys.stdin)
assert [len(x[\"rows\"]) for x in r] == [1, 2, 0] and r[2][\"message\"] == \"near.distance = 1 m\", r
'"
check "--timer goes to stderr, so json stays one document" bash -c "'$smql' '$db' --json --timer -c 'COUNT sofa; COUNT chair' 2>'$work/timer' | python3 -c 'import json,sys; assert len(json.load(sys.stdin)) == 2' && [ \$(grep -c '^time: ' '$work/timer') -eq 2 ]"
check "-jsonl prints one object per line" bash -c "'$smql' '$db' -jsonl 'COUNT sofa; COUNT chair' | python3 -c '
import json, sys
lines = sys.stdin.read().splitlines()
assert len(lines) == 2 and all(json.loads(l)[\"rows\"][0][\"count\"] == 2 for l in lines), lines
'"
check "csv prints one header per result" test "$("$smql" "$db" -csv 'COUNT sofa; COUNT chair' | tr '\n' ' ')" = 'count 2 count 2 '
check "-noheader drops the column names" test "$("$smql" "$db" -noheader -csv 'COUNT sofa')" = 2
check "-tsv separates with tabs" test "$("$smql" "$db" -tsv 'FIND sofa LIMIT 1' | head -1)" = $'id\tcategory\tsource_id\tbox'
check "-list separates with | (sqlite3's list mode)" test "$("$smql" "$db" -list -noheader 'COUNT sofa; FIND sofa RETURN category, kind LIMIT 1')" = $'2\nsofa|object'
check "-separator sets list mode's separator" test "$("$smql" "$db" -list -separator ';' 'FIND sofa RETURN category, kind LIMIT 1' | tail -1)" = 'sofa;object'
check ".separator in a script" test "$("$smql" "$db" -list -noheader -c '.separator "\t"
FIND sofa RETURN category, kind LIMIT 1')" = $'sofa\tobject'
check "-line prints name = value per column" test "$("$smql" "$db" -line 'FIND sofa RETURN category, kind LIMIT 1')" = $'category = sofa\n    kind = object'
check "statements before a syntax error run and print, as sqlite3 runs them" bash -c "
  ! '$smql' '$db' -c 'COUNT sofa; FND lamp' >'$work/before' 2>'$work/e' && grep -qx 2 '$work/before' && grep -q 'did you mean FIND' '$work/e'"
check "sqlite3's .mode column and html, .print, .show, .system" bash -c "
  out=\$('$smql' '$db' -c '.mode column
.print \"a heading\"
COUNT sofa;
.mode html
FIND sofa RETURN category LIMIT 1;
.show
.system echo from-sh') &&
  echo \"\$out\" | grep -qx 'a heading' && echo \"\$out\" | grep -qx '<TR><TD>sofa</TD>' &&
  echo \"\$out\" | grep -qx '     mode: html' && echo \"\$out\" | grep -qx 'from-sh' &&
  ! '$smql' '$db' -safe -c '.system touch $work/ran' 2>'$work/e' && grep -q 'not allowed in safe mode' '$work/e' && test ! -e '$work/ran'"
check "export glb refuses a terminal and writes to a pipe" bash -c "
  ! script -qec \"'$smql' export glb --db '$db'\" /dev/null >'$work/tty' && grep -q 'binary' '$work/tty' &&
  '$smql' export glb --db '$db' | head -c 4 | grep -q glTF"
check "sqlite3's .tables points to .scenes" bash -c "'$smql' '$db' -c '.tables' 2>&1 | grep -q 'hint: .scenes lists the scenes'"
check "a misspelt command gets a did-you-mean" bash -c "'$smql' '$db' -c '.scens' 2>&1 | grep -q 'did you mean .scenes?'"
check "no database: a transient one, removed at exit" bash -c "
  before=\$(ls -d \"\${TMPDIR:-/tmp}\"/smql-?????? 2>/dev/null | wc -l)
  out=\$(echo 'SHOW SCENES;' | '$smql' -csv) && [ \"\$out\" = 'name,id,nodes,source,viewpoint,current' ] &&
  [ \$(ls -d \"\${TMPDIR:-/tmp}\"/smql-?????? 2>/dev/null | wc -l) -eq \$before ]"
check "-box draws a box" bash -c "'$smql' '$db' -box 'COUNT sofa' | head -1 | grep -q '^┌───────┐'"
check "-markdown is a Markdown table" test "$("$smql" "$db" -markdown 'COUNT sofa' | head -2 | tr '\n' ' ')" = '| count | |-------| '
check "-cmd runs before the statements" bash -c "'$smql' '$db' -csv -cmd 'SET near = 1.5 m' 'SHOW SETTINGS' | grep -q '^near.distance,1.500,m,'"
check "a failing -cmd is reported, the rest runs, the status is 1" bash -c "'$smql' '$db' -cmd 'FIND nope' 'COUNT sofa' >'$work/o' 2>'$work/e'; [ \$? -eq 1 ] && grep -qx 2 '$work/o' && grep -q nope '$work/e'"
check "-bail stops at a failing -cmd" bash -c "'$smql' '$db' -bail -cmd 'FIND nope' 'COUNT sofa' >'$work/o' 2>/dev/null; [ \$? -eq 1 ] && ! grep -q 2 '$work/o'"
check "-echo prints each statement before its result" test "$("$smql" "$db" -echo -csv 'COUNT sofa' | tr '\n' ' ')" = 'COUNT sofa count 2 '
status() { "$@" >/dev/null 2>&1; echo $?; }
check "exit status 1 for an unknown option, a bad mode, a bare sub-command; 0 for --help" \
  test "$(status "$smql" "$db" --bogus) $(status "$smql" "$db" --format xml -c 'COUNT sofa') $(status "$smql" import) $(status "$smql" --help)" = "1 1 1 0"
check "-help and -version work with one dash" bash -c "'$smql' -help | grep -q Usage && '$smql' -version | grep -q '^smql '"

# Meta commands in scripts: .mode, .headers, .once, .output, .read, .categories, .scenes, .open.
printf 'COUNT sofa;\n' >"$work/inner.smql"
printf '%s\n' '.mode csv' '.headers off' ".once $work/once.txt" 'COUNT chair;' 'COUNT sofa;' ".output $work/out.txt" \
  ".read $work/inner.smql" '.output' '.categories' '.scenes' ".open $work/empty-db" '.categories' >"$work/meta.smql"
check "meta commands run from a script" bash -c "'$smql' '$db' -f '$work/meta.smql' >'$work/meta.out' &&
  [ \"\$(cat '$work/once.txt')\" = 2 ] && [ \"\$(cat '$work/out.txt')\" = 2 ] && [ \"\$(head -1 '$work/meta.out')\" = 2 ] &&
  grep -qx sofa '$work/meta.out' && grep -q '^room0,' '$work/meta.out' && tail -1 '$work/meta.out' | grep -q '^room0,' &&
  [ \$(grep -cx sofa '$work/meta.out') -eq 1 ]"
# ASK and .mode ask: the acceptance questions on the imported Replica room, then lines as questions.
check "ASK shows the SMQL and lists the cushions on the sofa" bash -c "'$smql' '$db' -c \"ASK 'what is on the sofa?'\" >'$work/ask' &&
  grep -qx 'SMQL: FIND object WHERE on(sofa)' '$work/ask' && [ \$(grep -c ' cushion ' '$work/ask') -ge 5 ]"
check "ASK 'is there a piano?' answers no" bash -c "'$smql' '$db' -c \"ASK 'is there a piano?'\" | grep -qx 'No, there is no piano.'"
check "ASK 'how many cushions are on the sofa?' answers with a number" \
  bash -c "'$smql' '$db' -c \"ASK 'how many cushions are on the sofa?'\" | grep -Eqx '[0-9]+ cushions are on the sofa\.'"
printf '%s\n' '.mode ask' "is there a sofa?" "how many pianos are there?" '.mode' '.mode csv' 'COUNT sofa;' >"$work/ask.smql"
check ".mode ask makes lines questions; .mode csv makes them SMQL again" bash -c "'$smql' '$db' -f '$work/ask.smql' >'$work/ask.out' &&
  grep -q '^Yes, there are 2 sofas' '$work/ask.out' && grep -qx '0 pianos.' '$work/ask.out' &&
  grep -qx 'output mode: table (lines are questions: .mode ask)' '$work/ask.out' && tail -1 '$work/ask.out' | grep -qx 2"
check "a question ASK cannot read is an error with examples" bash -c "! '$smql' '$db' -c \"ASK 'hello'\" 2>'$work/e' && grep -q 'hint: ask as in' '$work/e'"
check "an unknown meta command is an error with a hint" bash -c "! '$smql' '$db' -c '.bogus' 2>'$work/e' && grep -q 'hint: .help' '$work/e'"
check "a script error names its line in the script" bash -c "printf 'COUNT sofa;\n\nFIND\n  nope;\n' | '$smql' '$db' 2>&1 >/dev/null | grep -q 'line 4, column 3'"

# Errors: non-zero exit, line and column, a caret, a hint; JSON errors for programs.
check "a syntax error exits non-zero" bash -c "! '$smql' '$db' -c 'FIND cushion WHER on(sofa)'"
check "a syntax error shows line, column and caret" \
  bash -c "'$smql' '$db' -c 'FIND cushion WHER on(sofa)' 2>&1 | grep -q 'line 1, column' && '$smql' '$db' -c 'FIND cushion WHER on(sofa)' 2>&1 | grep -q '\^'"
check "an unknown category gets a hint" bash -c "'$smql' '$db' -c 'FIND cushon' 2>&1 | grep -q 'did you mean cushion'"
check "errors in json format are JSON" \
  bash -c "'$smql' '$db' --format json -c 'FIND cushon' 2>&1 >/dev/null | python3 -c 'import json,sys; e=json.load(sys.stdin)[\"error\"]; assert e[\"column\"] == 6 and \"cushion\" in e[\"hint\"]'"

# Input the parser must refuse with a clear error rather than crash or accept.
python3 -c "print('FIND cushion WHERE ' + '(' * 6000 + 'on(sofa)' + ')' * 6000)" >"$work/deep.smql"
check "6,000 nested parentheses are refused, not a crash" \
  bash -c "'$smql' '$db' -f '$work/deep.smql' 2>&1; test \$? -eq 1" 
check "the nesting error says so" bash -c "'$smql' '$db' -f '$work/deep.smql' 2>&1 | grep -q 'nests more than 100 levels deep'"
printf "FIND 'caf\xe9'" >"$work/latin1.smql"
check "a byte that is not UTF-8 is named" \
  bash -c "'$smql' '$db' -f '$work/latin1.smql' 2>&1 | grep -q 'not valid UTF-8: byte 10 (0xE9)'"
check "a negative distance is named" \
  bash -c "'$smql' '$db' -c 'FIND cushion WHERE near(sofa, -1 m)' 2>&1 | grep -q 'a distance cannot be negative'"
check "-c with no statement is an error" bash -c "! '$smql' '$db' -c '' 2>'$work/empty.err' && grep -q -- '-c was given no statement' '$work/empty.err'"

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
printf 'wall_0=Wall(0,0,0,4,0,0,2.5,0)\nbbox_0=Bbox(caf\xe9,1,1,0.5,0,0.5,0.5,1)\n' >"$work/latin1.txt"
check "a Latin-1 class in a SpatialLM file is refused with file, line and field" \
  bash -c "! '$smql' import spatiallm '$work/latin1.txt' --db '$db' 2>'$work/latin1.err' && grep -q 'latin1.txt:2: .*class: byte 0xE9' '$work/latin1.err'"
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
assert names == [\"frames\", \"align\", \"anchors\", \"objects\", \"openings\", \"relations\", \"write\"], names
frames = next(e for e in stages if e[\"event\"] == \"stage_finished\" and e[\"stage\"] == \"frames\")
assert abs(frames[\"frames_per_second\"] * frames[\"seconds\"] - 12) < 1e-6, frames
moved = [e[\"done\"] for e in stages if e[\"event\"] == \"stage_progress\" and e[\"stage\"] == \"frames\"]
assert 1 <= len(moved) <= 10 and moved == sorted(moved) and moved[-1] == 12, moved
' '$work/log'"
# The things the checks flag are named by the ids they are stored under, here after a scene already in the
# database: each warning's thing is, by its stored id, of the kind it names (a generated room of 60 things gives a
# few: slivers, a cabinet in the air). The ingest named them by its own ids (1..n) before.
check "an ingest's warnings name things by their stored ids" bash -c "
  '$smql' import replica '$replica' --db '$work/crowdmem' --scene room0 >/dev/null &&
  '$smql' synth --out '$work/crowded' --seed 1 --objects 60 --frames 40 >/dev/null &&
  '$smql' ingest '$work/crowded' --db '$work/crowdmem' --scene crowded --log json 2>'$work/crowded.log' >/dev/null &&
  '$smql' '$work/crowdmem' -csv -c 'USE SCENE crowded; FIND object RETURN id, category' >'$work/crowded.csv' &&
  python3 -c '
import csv, json, re, sys
notes = [e[\"text\"] for e in map(json.loads, open(sys.argv[1])) if e[\"event\"] == \"note\"]
named = [re.match(r\"warning: [a-z ]+: ([a-z-]+)#([0-9]+) \", n) for n in notes]
named = [m for m in named if m]
stored = {row[\"id\"]: row[\"category\"] for row in csv.DictReader(open(sys.argv[2]))}
assert named, notes
for m in named:
    assert stored.get(m.group(2)) == m.group(1), (m.group(0), stored.get(m.group(2)))
' '$work/crowded.log' '$work/crowded.csv'"
check "ingest prints each stage's rate in frames a second" bash -c "'$smql' ingest '$work/capture' --db '$work/rated' 2>&1 >/dev/null | grep -Eq '^frames +[0-9.]+ s +[0-9]+ frames/s  12 frames'"
check "check-ingest reports F1 as JSON" bash -c "'$smql' check-ingest '$work/memory' --truth '$work/capture/truth.json' --format json | python3 -c '
import json, sys
r = json.load(sys.stdin)
assert r[\"objects\"][\"f1\"] > 0.5 and 0 <= r[\"color_accuracy\"] <= 1, r
assert r[\"scale_error\"] is not None and r[\"scale_error\"] < 0.01, r
'"
# A capture missing a frame: check-ingest pairs each stored frame with its own pose line, as the
# ingest does; a frame attribute that is no position is passed over, never a bare stoul.
cp -r "$work/capture" "$work/gap" && rm "$work/gap/color/4.png" "$work/gap/depth/4.png"
check "check-ingest pairs the cameras of a capture missing a frame by frame number" bash -c "'$smql' ingest '$work/gap' --db '$work/gapmem' --quiet >/dev/null 2>&1 && '$smql' check-ingest '$work/gapmem' --truth '$work/gap/truth.json' --format json | python3 -c '
import json, sys
r = json.load(sys.stdin)
assert r[\"scale_error\"] is not None and r[\"scale_error\"] < 0.01 and r[\"anchors\"][\"f1\"] > 0.5, r
'"
check "check-ingest passes over a frame whose number is no number" bash -c "'$smql' export json --db '$work/memory' -o '$work/frames.json' 2>/dev/null && python3 -c '
import json, sys
scene = json.load(open(sys.argv[1]))
frames = [n for n in scene[\"nodes\"] if n.get(\"attributes\", {}).get(\"frame\") is not None and n[\"kind\"] == \"frame\"]
frames[0][\"attributes\"][\"frame\"] = \"four\"
json.dump(scene, open(sys.argv[1], \"w\"))
' '$work/frames.json' && '$smql' import json '$work/frames.json' --db '$work/framesdb' >/dev/null && '$smql' check-ingest '$work/framesdb' --truth '$work/capture/truth.json' 2>&1 | grep -q 'objects'"
check "ingested objects have scene-level text" bash -c "'$smql' '$work/memory' --format json -c \"FIND object WHERE text LIKE '% on the %' LIMIT 1\" | grep -q '\"id\"'"
check "DESCRIBE lists evidence" bash -c "'$smql' '$work/memory' -c 'DESCRIBE (FIND object LIMIT 1)' | grep -q 'evidence.*image/jpeg'"
node=$("$smql" "$work/memory" --format csv -c 'FIND object LIMIT 1' | sed -n 2p | cut -d, -f1)
check "export evidence writes JPEG crops" bash -c "'$smql' export evidence '#$node' '$work/crops' --db '$work/memory' >/dev/null && python3 -c '
import glob, sys
crops = glob.glob(sys.argv[1] + \"/*.jpg\")
assert crops and all(open(c, \"rb\").read(2) == bytes([0xff, 0xd8]) for c in crops), crops
' '$work/crops'"
check "evidence survives a JSON export and import" bash -c "'$smql' export json --db '$work/memory' -o '$work/memory.json' 2>/dev/null && '$smql' import json '$work/memory.json' --db '$work/copied' --scene copied >/dev/null && '$smql' '$work/copied' -c 'DESCRIBE (FIND object LIMIT 1)' | grep -q 'evidence.*image/jpeg'"
check ".categories names things, not camera frames or descriptions" bash -c "
  '$smql' '$work/memory' -csv -c '.categories' >'$work/cats' && grep -qx wall '$work/cats' &&
  ! grep -qx frame '$work/cats' && ! grep -qx description '$work/cats'"
check ".nullvalue is what a missing value prints as (an ingested anchor has no source id)" bash -c "
  '$smql' '$work/memory' -csv -c '.nullvalue NULL
FIND anchor RETURN kind, source_id LIMIT 1' | tail -1 | grep -qx 'anchor,NULL'"
check "--update refreshes the objects seen again" bash -c "'$smql' ingest '$work/capture' --db '$work/memory' --update capture 2>/dev/null | grep -q 'objects seen again' && '$smql' '$work/memory' -c 'USE SCENE capture; COUNT object WHERE captures = 2' | tail -1 | grep -qv '^0$'"
check "an update by the same capture changes nothing" bash -c "'$smql' '$work/memory' -c 'USE SCENE capture; SHOW CHANGES' | grep -q '0 changes in 1 update'"
check "import --update: the changed room's layout becomes the next version" bash -c "
  '$smql' synth --out '$work/tidy-a' --seed 11 --frames 1 >/dev/null &&
  '$smql' synth --out '$work/tidy-b' --seed 11 --frames 1 --changes >/dev/null &&
  '$smql' import json '$work/tidy-a/truth.json' --db '$work/tidy' >/dev/null &&
  '$smql' import json '$work/tidy-b/truth.json' --db '$work/tidy' --update synth-11 | grep -q '2 moved, 2 new, 2 missing' &&
  test \$('$smql' '$work/tidy' --format csv -c 'SHOW CHANGES' | tail -n +2 | wc -l) = 6 &&
  '$smql' '$work/tidy' -c \"RENAME SCENE 'synth-11' TO tidy; DROP SCENE tidy; SHOW SCENES\" | grep -q '(0 rows)'"
check "smql guide writes a plan as JSON, Markdown and a PNG map" bash -c "
  '$smql' synth --out '$work/route' --seed 11 --frames 1 >/dev/null &&
  '$smql' import json '$work/route/truth.json' --db '$work/routes' >/dev/null &&
  '$smql' guide '$work/routes' --from door --to mug --out '$work/plan' >/dev/null &&
  python3 -c '
import json, sys
plan = json.load(open(sys.argv[1] + \"/guide.json\"))
steps = plan[\"steps\"]
assert steps[0][\"step\"] == 0 and steps[-1][\"instruction\"].startswith(\"The white mug\"), steps
assert open(sys.argv[1] + \"/guide.png\", \"rb\").read(4) == bytes([0x89, 0x50, 0x4e, 0x47])
assert \"| 0 | Start at the door. |\" in open(sys.argv[1] + \"/guide.md\").read()
' '$work/plan'"
check "smql map draws a scene" bash -c "'$smql' map '$work/routes' --out '$work/map.png' | grep -q 'decision points' && test -s '$work/map.png'"
check "smql guide refuses an ambiguous goal and names the candidates" bash -c "
  out=\$('$smql' guide '$work/routes' --from door --to window --out '$work/none' 2>&1); status=\$?
  test \$status -eq 1 && grep -q 'window#9 at' <<<\"\$out\" && grep -q 'name one: window#' <<<\"\$out\" && test ! -e '$work/none'"
check "smql eval: the truth itself scores 1; the changed room misses exactly the things that moved or went" bash -c "
  '$smql' synth --out '$work/eval' --seed 11 --frames 8 >/dev/null &&
  '$smql' synth --out '$work/eval-changed' --seed 11 --frames 8 --changes >/dev/null &&
  '$smql' import json '$work/eval/truth.json' --db '$work/eval-truth' >/dev/null &&
  '$smql' import json '$work/eval-changed/truth.json' --db '$work/eval-other' >/dev/null &&
  '$smql' eval '$work/eval/eval-suite.json' --db '$work/eval-truth' --json '$work/eval-truth.json' >/dev/null &&
  '$smql' eval '$work/eval/eval-suite.json' --db '$work/eval-other' --json '$work/eval-other.json' >/dev/null &&
  python3 -c '
import json, sys
w = sys.argv[1]
def metrics(name):
    return {m[\"metric\"]: m for m in json.load(open(w + \"/\" + name))[\"metrics\"]}
truth = metrics(\"eval-truth.json\")
for name in (\"Acc_rel\", \"SR_nav\", \"StepComp\", \"SR_obj\", \"Acc_parent\", \"Acc_path\", \"Color Acc\", \"Loc@path\"):
    assert truth[name][\"value\"] == 1.0 and truth[name][\"episodes\"] > 0, (name, truth[name])
assert truth[\"SPL\"][\"value\"] > 0.99, truth[\"SPL\"]
# SR_obj by hand: a sought thing is found when the changed room has one of its kind within 0.5 m.
suite = json.load(open(w + \"/eval/eval-suite.json\"))
before = {n[\"id\"]: n for n in json.load(open(w + \"/eval/truth.json\"))[\"nodes\"]}
after = json.load(open(w + \"/eval-changed/truth.json\"))[\"nodes\"]
def found(t):
    return any(n[\"category\"] == t[\"category\"] and sum((a - b) ** 2 for a, b in zip(n[\"box\"][\"center\"], t[\"box\"][\"center\"])) <= 0.25 for n in after if \"box\" in n)
sought = [before[e[\"object\"]] for e in suite[\"retrieval\"]]
expected = sum(found(t) for t in sought) / len(sought)
other = metrics(\"eval-other.json\")[\"SR_obj\"]
assert expected < 1 and abs(other[\"value\"] - expected) < 1e-9, (other, expected)
' '$work'"
# The shell cannot destroy a database, and what it cannot write is an error (docs/shell.md).
check "import a database to harden" "$smql" import replica "$replica" --db "$work/hard"
check ".output and .once into the database's folder are refused, and the database stays whole" bash -c "
  printf '.output $work/hard/data.mdb\nCOUNT cushion;\n' | '$smql' '$work/hard' 2>'$work/e'; [ \$? -eq 1 ] &&
  grep -q 'would destroy the database' '$work/e' &&
  ! printf '.once $work/hard/lock.mdb\nCOUNT cushion;\n' | '$smql' '$work/hard' 2>/dev/null &&
  ! '$smql' export json --db '$work/hard' -o '$work/hard/x.json' 2>/dev/null && test ! -e '$work/hard/x.json' &&
  '$smql' check '$work/hard' >/dev/null && '$smql' '$work/hard' 'COUNT cushion' | grep -qx 9"
check ".read that reads itself stops with an error, not a crash" bash -c "
  echo '.read $work/self.smql' >'$work/self.smql'; '$smql' '$work/hard' -c '.read $work/self.smql' 2>'$work/e'
  [ \$? -eq 1 ] && grep -q 'more than 16 deep' '$work/e'"
check "results that cannot be written are an error: /dev/full, .output /dev/full, .once into /proc" bash -c "
  ! '$smql' '$work/hard' -c 'COUNT cushion' >/dev/full 2>'$work/e' && grep -q 'No space left' '$work/e' &&
  ! '$smql' export json --db '$work/hard' >/dev/full 2>/dev/null &&
  ! printf '.output /dev/full\nCOUNT cushion;\n' | '$smql' '$work/hard' 2>/dev/null &&
  ! printf '.once /proc/self/status\nCOUNT cushion;\n' | '$smql' '$work/hard' 2>/dev/null"
check "a script without a statement, a folder and /dev/zero as scripts are errors" bash -c "
  ! '$smql' '$work/hard' -c '-- nothing' 2>/dev/null &&
  ! '$smql' '$work/hard' -c '.read /tmp' 2>'$work/e' && grep -q 'it is a folder' '$work/e' &&
  ! '$smql' '$work/hard' -c '.read /dev/zero' 2>'$work/e' && grep -q 'more than 16 MiB' '$work/e'"
check "error messages show a NUL as \\x00 and cut a long name" bash -c "
  ! '$smql' '$work/hard' -c \"\$(printf 'FIND a\\001b')\" 2>'$work/e' && grep -qF '\\x01' '$work/e' &&
  ! '$smql' '$work/hard' -c \"FIND cushion WHERE category = '\$(head -c 6000 /dev/zero | tr '\\0' a)'\" 2>'$work/e' &&
  grep -q 'at most 4096' '$work/e' && test \$(wc -c <'$work/e') -lt 2000"
check "-safe and .safe on refuse .read, .output, .once and .open, and run statements" bash -c "
  for meta in '.read $work/self.smql' '.output $work/o.txt' '.once $work/o.txt' '.open $work/hard'; do
    ! '$smql' '$work/hard' -safe -c \"\$meta\" 2>'$work/e' && grep -q 'not allowed in safe mode' '$work/e' || exit 1
  done
  '$smql' '$work/hard' -safe -c 'COUNT cushion' | grep -qx 9 && test ! -e '$work/o.txt' &&
  printf '.safe on\n.read $work/self.smql\n' | '$smql' '$work/hard' 2>&1 | grep -q 'not allowed in safe mode' &&
  printf '.safe on\n.safe off\n' | '$smql' '$work/hard' 2>&1 | grep -q 'cannot be left'"
# Real layouts: the Replica room and VSI-Bench's rooms, scored with the suite smql eval generates.
check "GUIDE reaches at least 95% of the Replica room's floor-standing and supported things from the door" bash -c "
  '$smql' import replica '$replica' --db '$work/replica-guide' >/dev/null &&
  '$smql' eval --db '$work/replica-guide' --json '$work/replica-eval.json' >/dev/null &&
  python3 -c '
import json, sys
m = {r[\"metric\"]: r for r in json.load(open(sys.argv[1]))[\"metrics\"]}
assert m[\"Reach\"][\"episodes\"] >= 30 and m[\"Reach\"][\"value\"] >= 0.95, m[\"Reach\"]
assert m[\"SR_nav\"][\"value\"] >= 0.95 and m[\"Acc_rel\"][\"value\"] == 1.0, m
' '$work/replica-eval.json'"
check "GUIDE from the door reaches the sofas, the coffee table and the plant on it" bash -c "
  for goal in src#9 src#77 src#11 src#35; do '$smql' '$work/replica-guide' -c \"GUIDE FROM door TO \$goal\" | tail -1 | grep -q '^[0-9.]* m from door#' || exit 1; done"
check "import vsibench --all imports every room of a VSI-Bench file, standing on its floor" bash -c "
  '$smql' import vsibench '$data/real-layouts/scannet_meta_info_val.json' --db '$work/scannet' --all >'$work/scannet.out' &&
  test \$(grep -c '^imported scene' '$work/scannet.out') -eq 88 &&
  '$smql' '$work/scannet' -csv -c \"USE SCENE 'scene0251_00'; FIND door\" | tail -n +2 | grep -c ',door,' | grep -qx 3"
check "import vsibench without --scene names the rooms of a file that holds several" bash -c "
  ! '$smql' import vsibench '$data/real-layouts/arkitscenes_meta_info_val.json' --db '$work/none' 2>'$work/e' &&
  grep -q 'holds 150 rooms' '$work/e' && grep -q -- '--all' '$work/e' && test ! -e '$work/none'"
check "smql eval scores a real layout on the suite it generates, and writes the suite for another memory" bash -c "
  '$smql' eval --db '$work/scannet' --scene scene0251_00 --write-suite '$work/layout-suite' >'$work/layout.md' &&
  grep -q '| guidance | Reach |' '$work/layout.md' && test -s '$work/layout-suite/truth.json' &&
  '$smql' eval '$work/layout-suite/eval-suite.json' --db '$work/scannet' --scene scene0251_00 >'$work/again.md' &&
  diff <(cut -d'|' -f2-5 '$work/layout.md') <(cut -d'|' -f2-5 '$work/again.md')"
check "smql eval scores the only scene of a database when the suite's scene is not there" bash -c "
  '$smql' import json '$work/layout-suite/truth.json' --db '$work/renamed' --scene another-name >/dev/null &&
  '$smql' eval '$work/layout-suite/eval-suite.json' --db '$work/renamed' >'$work/renamed.md' &&
  diff <(cut -d'|' -f2-5 '$work/layout.md') <(cut -d'|' -f2-5 '$work/renamed.md')"
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
check "rgbd-dining's archway is found as a door, an opening in the left wall" bash -c "'$smql' '$work/dining' -csv -c 'FIND door' | tail -n +2 | grep -q '^[0-9]*,door,'"
# OpenCV's image files and videos (GDAL, GStreamer, FFmpeg: some 210 libraries) load only where needed
# (ingest/capture/media.hpp): not for a depth camera's PNGs (TUM's) nor its 16-bit PGMs (rgbd-dining's
# depth), whose things' crops TurboJPEG makes.
tum=$data/captures/tum-fr1-rpy
if [ -d "$tum" ]; then
  check "TUM's PNGs ingest without loading libsmql_media.so or what it brings" bash -c "
    LD_DEBUG=files '$smql' ingest '$tum' --db '$work/tum-libs' --quiet 2>'$work/libs' &&
    grep -q 'libopencv_dnn' '$work/libs' && ! grep -q 'libsmql_media\\|libgdal\\|libavcodec' '$work/libs'"
fi
check "rgbd-dining's PNGs and PGM depth images ingest without loading libsmql_media.so" bash -c "
  LD_DEBUG=files '$smql' ingest '$data/rgbd-dining' --db '$work/dining-libs' --quiet 2>'$work/libs' &&
  grep -q 'libopencv_dnn' '$work/libs' && ! grep -q 'libsmql_media\\|libgdal\\|libavcodec' '$work/libs'"
# The capture's points (docs/formats.md, "PLY"): a coloured cloud Open3D reads, its floor at z = 0, the
# boxes standing in it; a layout imported without points says so.
check "export ply --points writes rgbd-dining's coloured points, which Open3D reads" bash -c "
  '$smql' export ply --points --db '$work/dining' -o '$work/points.ply' &&
  /usr/bin/python3 - '$work/points.ply' <<'PY'
import sys
import numpy, open3d
cloud = open3d.io.read_point_cloud(sys.argv[1])
points, colours = numpy.asarray(cloud.points), numpy.asarray(cloud.colors)
floor = numpy.percentile(points[:, 2], 2)
print(len(points), cloud.has_colors(), floor, colours.std(axis=0))
assert len(points) > 5000 and cloud.has_colors() and colours.std(axis=0).min() > 0.05
assert -0.15 < floor < 0.05, floor
PY"
check "export ply --points of an imported layout says it has none" bash -c "
  ! '$smql' export ply --points --db '$db' --scene room0 -o '$work/none.ply' 2>'$work/e' && grep -q 'holds no points' '$work/e' && [ ! -e '$work/none.ply' ]"
if command -v colmap >/dev/null; then
  check "--colmap-dir keeps COLMAP's run, and the same frames read it back without COLMAP" bash -c "
    '$smql' ingest '$data/rgbd-dining' --db '$work/sfm1' --geometry colmap --colmap-dir '$work/sfm' --quiet &&
    [ -f '$work/sfm/smql-run.txt' ] && cp '$work/sfm/colmap.log' '$work/sfm.log' &&
    '$smql' ingest '$data/rgbd-dining' --db '$work/sfm2' --geometry colmap --colmap-dir '$work/sfm' >'$work/sfm.out' 2>&1 &&
    grep -q 'read from $work/sfm, run there before' '$work/sfm.out' &&
    cmp -s '$work/sfm/colmap.log' '$work/sfm.log' &&
    diff <('$smql' '$work/sfm1' -csv -c 'FIND object') <('$smql' '$work/sfm2' -csv -c 'FIND object')"
fi
# The detector (--objects detect) needs its model, which scripts/detector/setup.sh installs.
if [ -f /usr/local/share/smql/models/nanodet.onnx ]; then
  check "rgbd-dining with --objects detect gives named objects (chairs, a table), no unnamed ones" bash -c "
    '$smql' ingest '$data/rgbd-dining' --db '$work/detected' --objects detect --quiet &&
    '$smql' '$work/detected' -csv -c 'FIND object' | cut -d, -f2 | tail -n +2 >'$work/categories' &&
    [ \$(grep -cx chair '$work/categories') -ge 2 ] && grep -qx table '$work/categories' &&
    ! grep -qx object '$work/categories'"
else
  echo "skipped: --objects detect (no detector model; run scripts/detector/setup.sh)"
fi
check "--objects detect with a model but no class names is refused with a hint" bash -c "
  touch '$work/lone.onnx' && ! '$smql' ingest '$data/rgbd-dining' --db '$work/nomodel' --objects detect \
    --detector '$work/lone.onnx' 2>'$work/e' && grep -q 'coco.names' '$work/e' && grep -q 'scripts/detector/setup.sh' '$work/e'"
check "a capture that is not one is refused naming it" bash -c "mkdir -p '$work/empty' && ! '$smql' ingest '$work/empty' --db '$work/x' 2>'$work/e' && grep -q empty '$work/e'"

check "smql demo runs every example and leaves no capture behind" bash -c "mkdir -p '$work/demotmp' &&
  TMPDIR='$work/demotmp' '$smql' demo --db '$work/demo' >'$work/demo.out' && grep -q 'Explore it yourself' '$work/demo.out' &&
  [ -z \"\$(ls -A '$work/demotmp')\" ]"
check "smql demo --db DIR builds the database at DIR" bash -c "'$smql' '$work/demo' -csv -c 'SHOW SCENES' | grep -q '^demo-room,'"
check "smql demo refuses a folder that is not empty, and leaves it alone" bash -c "! '$smql' demo --db '$db' 2>'$work/e' && grep -q 'not an empty folder' '$work/e' && ! '$smql' '$db' -csv -c 'SHOW SCENES' | grep -q '^demo-room,'"
# Names that are not databases: a mistyped sub-command, sqlite3's :memory:, a fleet store's URL or
# connection string mistyped (with a password in it): none becomes a folder, none is echoed.
check "a mistyped sub-command is refused, naming the right one, and makes no database" bash -c "
  cd '$work' && ! '$smql' exprot json 2>'$work/e' && grep -q 'did you mean smql export' '$work/e' && [ ! -e exprot ]"
check ":memory: is a transient database, not a folder" bash -c "
  cd '$work' && '$smql' :memory: -c 'SHOW SCENES' >/dev/null 2>&1; [ ! -e ':memory:' ]"
check "a mistyped fleet URL makes no folder and shows no password" bash -c "
  cd '$work' && ! '$smql' 'postgresq://robot:SECRET@host/fleet' -c 'COUNT chair' 2>'$work/e' &&
  grep -q 'is a URL, not a folder' '$work/e' && ! grep -q SECRET '$work/e' && [ ! -e postgresq: ]"
check "a connection string makes no folder and shows no password" bash -c "
  cd '$work' && ! '$smql' 'host=db password=SECRET' -c 'COUNT chair' 2>'$work/e' &&
  grep -q 'connection string' '$work/e' && ! grep -q SECRET '$work/e' && [ ! -e 'host=db password=SECRET' ]"
# A name with a terminal's escape sequence in it, from an imported file: shown as \x1B, never sent raw.
python3 - "$work/esc.json" <<'PY'
import json, sys
json.dump({"smql_scene": 1, "scene": {"name": "esc"},
           "nodes": [{"id": 1, "kind": "anchor", "parent": 0, "category": "floor", "geometry": "plane",
                      "box": {"center": [2, 2, -0.01], "size": [4, 4, 0.02], "yaw": 0}},
                     {"id": 2, "kind": "object", "parent": 1, "category": "chair", "geometry": "box", "text": "\u001b]0;pwned\u0007red chair",
                      "box": {"center": [1, 1, 0.45], "size": [0.5, 0.5, 0.9], "yaw": 0}}]}, open(sys.argv[1], "w"))
PY
"$smql" import json "$work/esc.json" --db "$work/esc" >/dev/null 2>&1
for mode in table box markdown list line csv tsv; do
  check "$mode mode shows an escape sequence in a text as \\x1B" bash -c "
    '$smql' '$work/esc' -$mode -c 'FIND chair RETURN text' >'$work/o' && ! grep -q \$'\\x1b' '$work/o' && grep -q 'x1B' '$work/o'"
done
check "an empty -f script is an error" bash -c "
  : >'$work/empty.smql' && ! '$smql' '$db' -f '$work/empty.smql' 2>'$work/e' && grep -q 'holds no statement' '$work/e'"
check "a result that cannot be written is said once, exit 1" bash -c "
  ! '$smql' '$db' -c 'COUNT sofa' >/dev/full 2>'$work/e' && [ \$(grep -c 'cannot write standard output' '$work/e') -eq 1 ]"
check "an import whose report cannot be written is stored, exit 0, and says so" bash -c "
  '$smql' import replica '$replica' --db '$work/full' >/dev/full 2>'$work/e' && grep -q 'stored; the report could not' '$work/e' &&
  '$smql' '$work/full' -csv -c 'SHOW SCENES' | grep -q info_semantic"
check "a script that reads itself, 16 deep, stays small (no 16 MiB buffer a level)" bash -c "
  echo '.read $work/self.smql' >'$work/self.smql' && /usr/bin/time -f %M -o '$work/peak' '$smql' '$db' -f '$work/self.smql' >/dev/null 2>&1;
  [ \$(tail -1 '$work/peak') -lt 100000 ]"
check ".tree takes one node and runs nothing else" bash -c "
  ! '$smql' '$db' -cmd \".tree #1; DROP SCENE 'room0'\" -c 'SHOW SCENES' 2>'$work/e' && grep -q 'tree takes one node' '$work/e' &&
  '$smql' '$db' -csv -c 'SHOW SCENES' | grep -q '^room0,'"
check "smql --help names every sub-command, view among them" bash -c "'$smql' --help | grep -q 'guide, view, fleet'"
check "an empty suite fails, with a closing line" bash -c "! '$smql' test /dev/null >'$work/t.out' && tail -1 '$work/t.out' | grep -qx '0 passed, 1 failed'"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
