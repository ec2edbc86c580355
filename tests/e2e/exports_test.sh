#!/usr/bin/env bash
# `smql export FORMAT` as a user runs it, each file opened by its own ecosystem's reader: the GLB and
# glTF by Khronos' glTF validator and Open3D, the PLY by Open3D, the GeoJSON by GDAL's ogrinfo, and
# Spark-DSG by importing it back and comparing. Exits 77 (skipped) when a reader is missing.
# Usage: exports_test.sh SMQL_BINARY SHARED_DATA_DIR NODE_MODULES_DIR
set -u
smql=$1
data=$2
node_modules=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# Debian's Python, which has Open3D (a pyenv python3 earlier on PATH would not).
python=/usr/bin/python3

missing=()
command -v node >/dev/null || missing+=("node")
[ -d "$node_modules/gltf-validator" ] || missing+=("the npm package gltf-validator in $node_modules (scripts/setup.sh)")
"$python" -c 'import open3d' 2>/dev/null || missing+=("Open3D for $python (python3-open3d)")
command -v ogrinfo >/dev/null || missing+=("GDAL's ogrinfo (gdal-bin)")
if ((${#missing[@]} > 0)); then
  printf 'skipped: missing %s\n' "${missing[@]}"
  exit 77
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
fail() {
  failed=$((failed + 1))
  echo "FAIL: $*"
}

"$smql" import replica "$data/replica-room0/info_semantic.json" --db "$work/db" >/dev/null || exit 1
# Each format under the name its readers expect (Spark-DSG loads a .json file as JSON).
for export in json:room.json glb:room.glb gltf:room.gltf ply:room.ply geojson:room.geojson spark-dsg:room-dsg.json; do
  format=${export%%:*}
  "$smql" export "$format" --db "$work/db" -o "$work/${export#*:}" 2>"$work/err" || {
    fail "smql export $format"
    cat "$work/err"
  }
done

# The boxes the mesh and map formats hold: anchors and objects with a box, neither hidden nor the ceiling.
boxes=$("$python" - "$work/room.json" <<'PY'
import json, sys
nodes = json.load(open(sys.argv[1]))["nodes"]
print(sum(n["kind"] in ("anchor", "object") and n["geometry"] != "none" and not n["hidden"]
          and n["category"] != "ceiling" for n in nodes))
PY
)
echo "the Replica room: $boxes boxes"
[ "$boxes" -gt 0 ] || fail "no boxes counted in the json export"

# glTF: no error and no warning from Khronos' validator, in both containers.
node "$here/validate_gltf.js" "$node_modules" "$work/room.glb" "$work/room.gltf" || fail "the glTF validator"

# Open3D reads the GLB and the PLY as one mesh of 8 vertices and 12 triangles a box, the PLY coloured.
"$python" - "$work/room.glb" "$work/room.ply" "$boxes" <<'PY' || fail "Open3D"
import sys
import open3d as o3d
glb, ply, boxes = sys.argv[1], sys.argv[2], int(sys.argv[3])
failed = False
def check(what, ok):
    global failed
    print(("ok: " if ok else "FAIL: ") + what)
    failed = failed or not ok
mesh = o3d.io.read_triangle_mesh(glb)
check(f"GLB: {len(mesh.vertices)} vertices (want {8 * boxes}), {len(mesh.triangles)} triangles (want {12 * boxes})",
      len(mesh.vertices) == 8 * boxes and len(mesh.triangles) == 12 * boxes)
mesh = o3d.io.read_triangle_mesh(ply)
check(f"PLY: {len(mesh.vertices)} vertices (want {8 * boxes}), {len(mesh.triangles)} triangles (want {12 * boxes})",
      len(mesh.vertices) == 8 * boxes and len(mesh.triangles) == 12 * boxes)
check("PLY: vertex colours", mesh.has_vertex_colors())
sys.exit(1 if failed else 0)
PY

# GDAL reads the GeoJSON as one layer of polygons, a feature per box.
ogrinfo -al -so "$work/room.geojson" >"$work/ogrinfo" 2>&1 || fail "ogrinfo cannot read the GeoJSON"
grep -q "^Feature Count: $boxes\$" "$work/ogrinfo" || fail "ogrinfo: want Feature Count: $boxes"
grep -q "^Geometry: Polygon\$" "$work/ogrinfo" || fail "ogrinfo: want Geometry: Polygon"
grep -E "^(Feature Count|Geometry|Extent):" "$work/ogrinfo"

# Spark-DSG both ways: the graph imported into a new database exports the same categories, boxes and
# parents as the room it came from.
"$smql" import spark-dsg "$work/room-dsg.json" --db "$work/back" >/dev/null || fail "smql import spark-dsg"
"$smql" export json --db "$work/back" -o "$work/back.json" 2>/dev/null || fail "smql export json of the round trip"
"$python" - "$work/room.json" "$work/back.json" <<'PY' || fail "the Spark-DSG round trip"
import json, math, sys
before, after = (json.load(open(path)) for path in sys.argv[1:3])
assert after["scene"]["name"] == before["scene"]["name"], (after["scene"]["name"], before["scene"]["name"])
a, b = before["nodes"], after["nodes"]
assert len(a) == len(b), (len(a), len(b))
nested = 0
for x, y in zip(a, b):
    for key in ("id", "category", "kind", "parent", "geometry", "hidden"):
        assert x[key] == y[key], (x["id"], key, x[key], y[key])
    nested += x["parent"] != 0
    if "box" in x:
        for key in ("center", "size"):
            assert all(abs(p - q) < 1e-9 for p, q in zip(x["box"][key], y["box"][key])), (x["id"], key)
        assert abs(math.remainder(x["box"]["yaw"] - y["box"]["yaw"], 2 * math.pi)) < 1e-9, x["id"]
print(f"ok: Spark-DSG round trip: {len(a)} nodes, {nested} with parents, same categories, boxes and parents")
PY

if [ "$failed" -gt 0 ]; then
  echo "$failed failed"
  exit 1
fi
echo "all exports read by their readers"
