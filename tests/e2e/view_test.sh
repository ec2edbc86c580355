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
"$smql" ingest "$data/rgbd-dining" --db "$work/dining" --quiet || exit 1
"$smql" export html --db "$work/dining" -o "$work/dining.html" 2>/dev/null || exit 1
expected=$("$smql" "$work/db" -json "FIND cushion WHERE on(sofa)" | /usr/bin/python3 -c \
  'import json, sys; print(json.dumps([r["id"] for r in json.load(sys.stdin)[-1]["rows"]]))') || exit 1

"$smql" view "$work/db" --port 0 >"$work/server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null; wait $server 2>/dev/null' EXIT
for _ in $(seq 50); do
  url=$(grep -o 'http://127.0.0.1:[0-9]*/?token=[0-9a-f]*' "$work/server.log" | head -1)
  [[ -n $url ]] && break
  sleep 0.2
done
[[ -n ${url:-} ]] || { echo "FAIL the server did not start:"; cat "$work/server.log"; exit 1; }
echo "server at $url"

# Who may use it (docs/view.md, "Who can use it"): the API answers this machine's names and the token
# of the printed address only; a request's SET stays in that request; slow and idle connections
# starve no one; a LIKE that backtracked for hours answers at once.
/usr/bin/python3 - "$url" <<'PY' || exit 1
import socket, sys, threading, time, urllib.error, urllib.parse, urllib.request
url = sys.argv[1]
parts = urllib.parse.urlsplit(url)
base, token = f"{parts.scheme}://{parts.netloc}", urllib.parse.parse_qs(parts.query)["token"][0]
def get(path, headers=None, timeout=10):
    request = urllib.request.Request(base + path, headers=headers or {})
    try:
        with urllib.request.urlopen(request, timeout=timeout) as r:
            return r.status, r.read().decode()
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode()
failures = []
def check(what, ok):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)
def q(statement):
    return "/api/query?q=" + urllib.parse.quote(statement)
check("the API without the token is refused", get("/api/scenes")[0] == 403)
check("... with a wrong token too", get("/api/scenes", {"X-Smql-Token": "0" * 32})[0] == 403)
check("... with the token it answers", get("/api/scenes", {"X-Smql-Token": token})[0] == 200)
check("... the token as a parameter too", get(f"/api/scenes?token={token}")[0] == 200)
check("another site's Host is refused, token or not",
      get("/api/scenes", {"X-Smql-Token": token, "Host": "attacker.example"})[0] == 403)
near = lambda: get(q("COUNT cushion WHERE near(sofa)"), {"X-Smql-Token": token})
before = near()
get(q("SET near = 0 m"), {"X-Smql-Token": token})
check("a request's SET does not reach the next request", near() == before and before[0] == 200)
# Slow clients: 12 that trickle a byte a second, 300 that connect and say nothing.
stop = threading.Event()
def trickle():
    s = socket.create_connection((parts.hostname, parts.port))
    for b in b"GET /api/scenes HTTP/1.1\r\nHost: x\r\n":
        if stop.is_set():
            break
        s.send(bytes([b]))
        time.sleep(1)
    s.close()
tricklers = [threading.Thread(target=trickle, daemon=True) for _ in range(12)]
for t in tricklers:
    t.start()
idle = [socket.create_connection((parts.hostname, parts.port)) for _ in range(300)]
time.sleep(1)
start = time.monotonic()
status, _ = get(q("COUNT sofa"), {"X-Smql-Token": token}, timeout=10)
check(f"a real request beside 12 slow and 300 idle connections is answered ({time.monotonic() - start:.1f} s)",
      status == 200 and time.monotonic() - start < 5)
stop.set()
for s in idle:
    s.close()
start = time.monotonic()
status, body = get(q("COUNT node WHERE category LIKE '" + "%" * 40 + "x'"), {"X-Smql-Token": token}, timeout=30)
check(f"forty %s before a letter never seen answer at once ({time.monotonic() - start:.1f} s)",
      status == 200 and time.monotonic() - start < 5)
sys.exit(1 if failures else 0)
PY

node "$here/view_test.mjs" "$url" "$expected" "$work/room.html" "$work/shots" "$work/dining.html" || exit 1

# The highlight colour (#ff2d55, lit) in the frames: the hits are drawn highlighted, and the labels
# can be read.
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

# Each label as drawn: its text against its ground, WCAG's contrast of the darkest and the lightest
# pixels inside it (its colour bar left out) at least 4.5, what small text needs to be read.
import json
def luminance(bgr):
    c = bgr[::-1] / 255.0
    c = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
image = cv2.imread(f"{sys.argv[1]}/before.png").astype(float)
labels = json.load(open(f"{sys.argv[1]}/labels.json"))
ratios = []
for label in labels:
    x0, y0 = int(label["left"]) + 4, int(label["top"]) + 2
    x1, y1 = int(label["left"] + label["width"]) - 1, int(label["top"] + label["height"]) - 2
    pixels = sorted(luminance(p) for p in image[y0:y1, x0:x1].reshape(-1, 3))
    dark, light = pixels[len(pixels) // 50], pixels[-len(pixels) // 50 - 1]
    ratios.append((light + 0.05) / (dark + 0.05))
legible = len(ratios) >= 15 and min(ratios) >= 4.5
print(("ok  " if legible else "FAIL") + f" the {len(ratios)} labels on the screenshot read: text-to-ground contrast "
      f"{min(ratios, default=0):.1f} at the least")

# The captured scene with its points and without: the points cover a good part of the picture.
on, off = (cv2.imread(f"{sys.argv[1]}/points-{state}.png").astype(int) for state in ("on", "off"))
changed = int((np.abs(on - off).max(axis=2) > 30).sum())
drawn = changed > 5000
print(("ok  " if drawn else "FAIL") + f" the points are drawn: {changed} pixels change when they are hidden")
sys.exit(0 if ok and legible and drawn else 1)
PY
