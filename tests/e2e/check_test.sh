#!/usr/bin/env bash
# `smql check DB` as a user runs it: a sound database passes (exit 0), damaged ones are
# reported (exit 1) with what is wrong. Usage: check_test.sh SMQL_BINARY SHARED_DATA_DIR
set -u
smql=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0

expect() {  # expect NAME STATUS PATTERN COMMAND...: the exit status and a line of its output
  local name=$1 status=$2 pattern=$3
  shift 3
  "$@" >"$work/out" 2>&1
  local got=$?
  if [ "$got" -ne "$status" ] || ! grep -q -- "$pattern" "$work/out"; then
    failed=$((failed + 1))
    echo "FAIL: $name (exit $got, wanted $status and /$pattern/)"
    sed 's/^/  out: /' "$work/out" | head -20
  fi
}

db=$work/db
"$smql" import replica "$data/replica-room0/info_semantic.json" --db "$db" --scene room0 >/dev/null || exit 1
expect "a sound database passes" 0 "^$db: ok (1 scene, 92 nodes" "$smql" check "$db"

# A bit flipped in the first sofa's record (its category is stored right after the fixed header).
cp -r "$db" "$work/flipped"
python3 - "$work/flipped/data.mdb" <<'PY'
import sys
path = sys.argv[1]
data = bytearray(open(path, "rb").read())
at = data.find(b"\x04sofa")
assert at > 0, "no sofa record"
data[at + 2] ^= 0x20  # 'o' -> 'O'
open(path, "wb").write(bytes(data))
PY
expect "a flipped byte is a corrupt record of its scene" 1 "^problem: scene 'room0' (#1): corrupt record in scene 'room0'" \
  "$smql" check "$work/flipped"
expect "queries refuse it too" 1 "corrupt record in scene 'room0'" "$smql" "$work/flipped" -c "FIND sofa"

# Recovery: a second scene beside the damaged one is salvaged into a new database, which checks ok;
# the damaged scene is named and left out.
cp -r "$db" "$work/two"
"$smql" import replica "$data/replica-room0/info_semantic.json" --db "$work/two" --scene intact >/dev/null || exit 1
python3 - "$work/two/data.mdb" <<'PY'
import sys
path = sys.argv[1]
data = bytearray(open(path, "rb").read())
at = data.find(b"\x04sofa")
data[at + 2] ^= 0x20
open(path, "wb").write(bytes(data))
PY
expect "--salvage copies the sound scenes and names the damaged one" 1 "left out: scene 'room0'" \
  "$smql" check "$work/two" --salvage "$work/saved"
expect "... the salvaged database checks ok with the sound scene" 0 "^$work/saved: ok (1 scene, 92 nodes" \
  "$smql" check "$work/saved"
expect "... and answers as the original did" 0 "^2$" "$smql" "$work/saved" -c "USE SCENE 'intact'; COUNT sofa"
expect "--salvage refuses a folder that holds files" 1 "not empty" "$smql" check "$db" --salvage "$work/saved"

cp -r "$db" "$work/short"
truncate -s 8192 "$work/short/data.mdb"
expect "a data.mdb cut short" 1 "cut short" "$smql" check "$work/short"
expect "queries on it do not crash" 1 "cut short" "$smql" "$work/short" -c "FIND sofa"

cp -r "$db" "$work/empty"
truncate -s 0 "$work/empty/data.mdb"
expect "an emptied data.mdb is not re-created" 1 "data.mdb is empty" "$smql" "$work/empty" -c "SHOW SCENES"
if [ -s "$work/empty/data.mdb" ]; then failed=$((failed + 1)); echo "FAIL: the emptied data.mdb was re-initialised"; fi

[ "$failed" -eq 0 ] && echo "check_test: all passed"
exit "$failed"
