#!/usr/bin/env bash
# The shell in a real terminal (tmux). Ctrl-C: at the prompt it drops the line, in a statement
# spanning lines it drops the statement, while statements run it cancels them; the shell goes on
# every time. A statement typed over two lines is one history entry. Tables fit the terminal's
# width; the ingest progress bar stays on one line at 40 columns.
# Usage: terminal_test.sh SMQL_BINARY
set -u
smql=$1
work=$(mktemp -d)
socket=smql-terminal-$$
trap 'tmux -L "$socket" kill-server 2>/dev/null; rm -rf "$work"' EXIT
passed=0
failed=0

pass() { passed=$((passed + 1)); }
fail() {
  failed=$((failed + 1))
  echo "FAIL: $1"
  screen | grep -v '^$' | tail -15 | sed 's/^/  screen: /'
}
screen() { tmux -L "$socket" capture-pane -t shell -p -S -200; }
# Text typed as is; tmux reads a trailing `;` as its command separator unless escaped.
type_keys() {
  local text=$1
  [[ $text == *';' ]] && text="${text%;}\\;"
  tmux -L "$socket" send-keys -t shell -l "$text"
}
press() { tmux -L "$socket" send-keys -t shell "$@"; }
# wait_for PATTERN [SECONDS]: until the screen's last non-empty line matches (an extended regex;
# tmux drops the spaces that end a line, so the prompt shows as `smql>`).
wait_for() {
  local deadline=$((SECONDS + ${2:-10}))
  while ((SECONDS < deadline)); do
    screen | grep -v '^$' | tail -1 | grep -Eq "$1" && return 0
    sleep 0.1
  done
  return 1
}
# Until a line of the screen matches (an answer, not the prompt that was there before it).
wait_until() {
  local deadline=$((SECONDS + ${2:-10}))
  while ((SECONDS < deadline)); do
    screen | grep -Eq "$1" && return 0
    sleep 0.1
  done
  return 1
}
# Until a line matching PATTERN comes after the screen's last line that is LINE: the answer to that statement,
# not an earlier one's of the same text.
wait_after() {
  local deadline=$((SECONDS + ${3:-10}))
  while ((SECONDS < deadline)); do
    screen | awk -v line="$1" '$0 == line { seen = 1; after = ""; next } seen { after = after $0 "\n" } END { printf "%s", after }' |
      grep -Eq "$2" && return 0
    sleep 0.1
  done
  return 1
}
alive() { tmux -L "$socket" list-panes -t shell -F '#{pane_dead}' 2>/dev/null | grep -qx 0; }

# 400 objects on a circle 9 km across: no object lies between two others, so
# `between(object, object)` tries every pair for every object, about a second per statement.
python3 - "$work/ring.json" <<'PY' || exit 1
import json, math, sys
n = 400
nodes = [{"id": i + 1, "kind": "object", "parent": 0, "category": ["chair", "sofa", "lamp"][i % 3], "geometry": "box",
          "box": {"center": [9000 * math.cos(2 * math.pi * i / n), 9000 * math.sin(2 * math.pi * i / n), 0.4],
                  "size": [0.5, 0.5, 0.8], "yaw": 0.0},
          "attributes": {}, "confidence": 1.0, "source_id": i + 1, "text": "", "hidden": False} for i in range(n)]
json.dump({"smql_scene": 1, "scene": {"name": "ring"}, "nodes": nodes, "relations": []}, open(sys.argv[1], "w"))
PY
"$smql" import json "$work/ring.json" --db "$work/db" --scene ring >/dev/null || exit 1
for i in $(seq 20); do echo 'COUNT object WHERE between(object, object);'; done >"$work/slow.smql"

mkdir -p "$work/home"
# The pane stays after smql exits (remain-on-exit), so the test can see it leave.
tmux -L "$socket" -f /dev/null new-session -d -s shell -x 100 -y 40 "sleep 0.5; HOME='$work/home' '$smql' '$work/db'"
tmux -L "$socket" set-option -t shell remain-on-exit on
deadline=$((SECONDS + 60))
if wait_for '^smql>$'; then pass; else fail "the shell shows its prompt"; fi

type_keys 'FIND sof'
sleep 0.3
press C-c
if wait_for '^smql>$' 5 && screen | grep -q '^smql> FIND sof\^C$' && alive; then pass; else fail "Ctrl-C at the prompt drops the line"; fi

type_keys 'FIND sofa'; press Enter
wait_for '^ +\.\.\.>$' 5
press C-c
wait_for '^smql>$' 5
type_keys 'COUNT lamp;'; press Enter
# Had the first line been kept, `FIND sofa COUNT lamp;` would be a syntax error.
if wait_until '^\(1 row\)$|error' 5 && wait_for '^smql>$' 5 && ! screen | grep -q error && alive; then pass
else fail "Ctrl-C on a continuation line drops the whole statement"; fi

# Twenty slow statements: Ctrl-C stops the one running (or drops its result) and the rest.
type_keys ".read $work/slow.smql"; press Enter
sleep 1.5
press C-c
if wait_for '^smql>$' 5 && screen | grep -q '^interrupted: the statement was interrupted$' && [ "$(screen | grep -c '^(1 row)$')" -lt 10 ] && alive; then pass
else fail "Ctrl-C while statements run cancels them, not the shell"; fi

# COUNT lamp's answer is 133 too: the 133 must come after this statement's line.
type_keys 'COUNT sofa;'; press Enter
if wait_after 'smql> COUNT sofa;' '^133$' 10 && wait_for '^smql>$' 10 &&
  [ "$(screen | grep -v '^$' | tail -3 | head -1)" = 133 ] && alive; then pass
else fail "the shell answers after an interrupt"; fi

# SHOW SETTINGS' meaning column alone is about 90 characters: rows are cut to the 100 columns. Its last row,
# then the prompt after it: the prompt before the statement matched at once on a loaded machine.
type_keys 'SHOW SETTINGS;'; press Enter
if wait_until '^shape_cache ' 10 && wait_for '^smql>$' 10 && screen | grep -q '^lateral\.min_offset .*…$' &&
  ! screen | grep -q 'viewer.s axis'; then pass
else fail "table rows fit the terminal's width"; fi

type_keys 'COUNT chair'; press Enter
type_keys 'WHERE near(lamp, 1 m);'; press Enter
wait_for '^smql>$' 10
type_keys '.quit'; press Enter
sleep 0.5
if grep -qx 'COUNT chair\\nWHERE near(lamp, 1 m);' "$work/home/.smql_history"; then pass
else fail "a statement typed over two lines is one history entry"; sed 's/^/  history: /' "$work/home/.smql_history"; fi
if ! alive; then pass; else fail ".quit leaves"; fi

# -bail: the interactive shell ends at its first error, with status 1.
tmux -L "$socket" new-session -d -s bail -x 100 -y 20 "sleep 0.5; HOME='$work/home' '$smql' -bail '$work/db'; echo status=\$?; sleep 60"
until tmux -L "$socket" capture-pane -t bail -p | grep -q '^smql>' || ((SECONDS > deadline)); do sleep 0.1; done
tmux -L "$socket" send-keys -t bail -l 'COUNT sofa'; tmux -L "$socket" send-keys -t bail '\;' Enter
tmux -L "$socket" send-keys -t bail -l 'FIND nothing'; tmux -L "$socket" send-keys -t bail '\;' Enter
sleep 1
if tmux -L "$socket" capture-pane -t bail -p | grep -q '^status=1$'; then pass
else fail "-bail ends the interactive shell at the first error"; tmux -L "$socket" capture-pane -t bail -p | sed 's/^/  bail: /'; fi

# The ingest's progress bar is redrawn in place: at 40 columns it must not wrap, or every redraw
# would scroll a line into the history of the terminal.
"$smql" synth --out "$work/capture" --seed 2 --frames 20 >/dev/null || exit 1
tmux -L "$socket" new-session -d -s ingest -x 40 -y 20 "'$smql' ingest '$work/capture' --db '$work/memory'; echo ingest-done; sleep 60"
deadline=$((SECONDS + 60))
until tmux -L "$socket" capture-pane -t ingest -p | grep -q ingest-done || ((SECONDS > deadline)); do sleep 0.2; done
if [ "$(tmux -L "$socket" capture-pane -t ingest -p -S -1000 | grep -c '^frames ')" -eq 1 ]; then pass
else fail "the progress bar stays on one line at 40 columns"; tmux -L "$socket" capture-pane -t ingest -p -S -1000 | sed 's/^/  ingest: /'; fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
