#!/usr/bin/env bash
# Files smql writes on a user's word never land outside the folder asked for, nor on a database's own
# files (docs/shell.md, "Output"): evidence crops whose blob names came from an imported scene (`../`,
# an absolute path, `..`) stay in their folder, renamed and said so; an export, a map or `.output`
# to data.mdb or lock.mdb, to a hard link of them elsewhere, or into the database's folder is refused
# and the database still answers. Usage: untrusted_files_test.sh SMQL_BINARY
set -u
smql=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
fail() {
  failed=$((failed + 1))
  echo "FAIL: $*"
}

# A scene whose one object carries four crops named by whoever wrote the file.
mkdir -p "$work/elsewhere"
cat >"$work/scene.json" <<JSON
{"smql_scene": 1, "scene": {"name": "crafted"},
 "nodes": [{"id": 1, "kind": "anchor", "parent": 0, "category": "floor", "geometry": "plane",
            "box": {"center": [2, 2, -0.01], "size": [4, 4, 0.02], "yaw": 0}},
           {"id": 2, "kind": "object", "parent": 1, "category": "chair", "geometry": "box",
            "box": {"center": [1, 1, 0.45], "size": [0.5, 0.5, 0.9], "yaw": 0}}],
 "blobs": [{"node": 2, "name": "../../escaped.jpg", "media_type": "image/jpeg", "base64": "AAEC"},
           {"node": 2, "name": "$work/elsewhere/absolute.jpg", "media_type": "image/jpeg", "base64": "AAEC"},
           {"node": 2, "name": "..", "media_type": "image/jpeg", "base64": "AAEC"},
           {"node": 2, "name": "plain.jpg", "media_type": "image/jpeg", "base64": "AAEC"}]}
JSON
"$smql" import json "$work/scene.json" --db "$work/db" >/dev/null || exit 1
mkdir -p "$work/out/crops"
chair=$("$smql" "$work/db" -csv -noheader -c "FIND chair RETURN id")
"$smql" export evidence "#$chair" "$work/out/crops" --db "$work/db" >"$work/written" 2>"$work/notes" ||
  fail "export evidence failed: $(cat "$work/notes")"
[ "$(find "$work/out/crops" -type f | wc -l)" -eq 4 ] || fail "not four files in the crops folder: $(ls "$work/out/crops")"
[ -e "$work/escaped.jpg" ] || [ -e "$work/out/escaped.jpg" ] && fail "a crop escaped its folder through ../"
[ -n "$(ls -A "$work/elsewhere")" ] && fail "a crop was written at its absolute name"
[ -e "$work/out/crops/plain.jpg" ] || fail "a plain name was not kept"
[ "$(grep -c "written as" "$work/notes")" -eq 3 ] || fail "the three renamed crops were not said: $(cat "$work/notes")"
while read -r path; do
  case "$(realpath "$path")" in "$work/out/crops/"*) ;; *) fail "wrote $path" ;; esac
done <"$work/written"

# The database's own files, however they are reached.
db=$work/db
ln "$db/data.mdb" "$work/hardlink.mdb"
ln -s "$db/lock.mdb" "$work/symlink.mdb"
refused() {  # refused WHAT COMMAND...: exit status 1 and "would destroy the database"
  local what=$1
  shift
  if "$@" >"$work/out.txt" 2>&1; then
    fail "$what was written"
  elif ! grep -q "would destroy the database" "$work/out.txt"; then
    fail "$what: $(cat "$work/out.txt")"
  fi
}
refused "export to data.mdb" "$smql" export json --db "$db" -o "$db/data.mdb"
refused "export to a hard link of data.mdb" "$smql" export json --db "$db" -o "$work/hardlink.mdb"
refused "export to a symbolic link of lock.mdb" "$smql" export json --db "$db" -o "$work/symlink.mdb"
refused "export into the database's folder" "$smql" export json --db "$db" -o "$db/scene.json"
refused "a map onto lock.mdb" "$smql" map "$db" --out "$db/lock.mdb"
refused ".output to the hard link" "$smql" "$db" -cmd ".output $work/hardlink.mdb" -c "COUNT chair"
refused ".once onto data.mdb through .." "$smql" "$db" -cmd ".once $work/out/../db/data.mdb" -c "COUNT chair"
"$smql" check "$db" >"$work/check" 2>&1 || fail "the database does not check after the refusals: $(cat "$work/check")"
[ "$("$smql" "$db" -c "COUNT chair" | tail -n +3 | head -1)" = "1" ] || fail "the database no longer answers"

if ((failed > 0)); then
  echo "$failed failed"
  exit 1
fi
echo "ok: crops stay in their folder; the database's files are never written"
