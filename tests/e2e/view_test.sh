#!/usr/bin/env bash
# `smql view` end to end (docs/view.md): the Replica room served on 127.0.0.1, driven in headless
# Chromium by view_test.mjs, and the screenshots checked: after FIND cushion WHERE on(sofa) the
# frame holds the highlight colour, before it almost none.
#   view_test.sh SMQL SHARED_DATA WORK
set -uo pipefail
smql=$1 data=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
for need in /usr/bin/chromium node "$here/../../web/node_modules/playwright-core/index.mjs"; do
  if ! command -v "$need" >/dev/null && [[ ! -e $need ]]; then
    echo "view test skipped: $need is missing (scripts/setup.sh installs chromium and web/'s npm packages)"
    exit 77
  fi
done
rm -rf "$work" && mkdir -p "$work/shots"
"$smql" import replica "$data/replica-room0/info_semantic.json" --db "$work/db" >/dev/null || exit 1
"$smql" export html --db "$work/db" -o "$work/room.html" 2>/dev/null || exit 1
expected=$("$smql" "$work/db" -json "FIND cushion WHERE on(sofa)" | /usr/bin/python3 -c \
  'import json, sys; print(json.dumps([r["id"] for r in json.load(sys.stdin)[-1]["rows"]]))') || exit 1

"$smql" view "$work/db" --port 0 >"$work/server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null; wait $server 2>/dev/null' EXIT
for _ in $(seq 50); do
  url=$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/server.log" | head -1)
  [[ -n $url ]] && break
  sleep 0.2
done
[[ -n ${url:-} ]] || { echo "FAIL the server did not start:"; cat "$work/server.log"; exit 1; }
echo "server at $url"

node "$here/view_test.mjs" "$url" "$expected" "$work/room.html" "$work/shots" || exit 1

# The highlight colour (#ff2d55, lit) in the frames: the hits are drawn highlighted.
/usr/bin/python3 - "$work/shots" <<'PY' || exit 1
import sys
import cv2
import numpy as np

def highlighted(path):
    image = cv2.imread(path).astype(int)  # BGR
    b, g, r = image[..., 0], image[..., 1], image[..., 2]
    return int(((r > 200) & (g < 110) & (b > 50) & (b < 150) & (r - g > 120)).sum())

before, after = highlighted(f"{sys.argv[1]}/before.png"), highlighted(f"{sys.argv[1]}/after.png")
print(f"highlight-coloured pixels: {before} before the query, {after} after it")
ok = after > 300 and after > 10 * (before + 1)
print(("ok  " if ok else "FAIL") + " the screenshot shows the hits highlighted")
sys.exit(0 if ok else 1)
PY
