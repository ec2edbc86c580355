#!/usr/bin/env python3
"""Import scaling: `smql import` of files at n, 2n and 4n of what makes them large, so that a cost
that grows with the square of the input shows as a 4x step where a linear one shows 2x.

Inputs, generated from the real files of ../shared/data into a temporary folder:
  json      the Replica room as smql JSON with n random `near` relations between its objects
  vsibench  VSI-Bench's ScanNet and ARKitScenes rooms, repeated under new names to n rooms (--all)
  replica   the Replica room tiled on a grid of rooms 12 m apart, to n objects

Each import runs RUNS times (default 3) into a fresh database; the table gives the median wall
time, the step from the size before, and Python's json.load of the same file beside it (a reader
that only parses: the floor under any import of that file).

Usage: bench/import_scaling.py SMQL SHARED_DATA [--out docs/benchmarks.md]
"""
import argparse
import copy
import json
import os
import random
import shutil
import statistics
import subprocess
import tempfile
import time

HEADING = "## Import scaling (`make bench-import`, `bench/import_scaling.py`)"


def relations_scene(data, work, smql, count):
    db = os.path.join(work, "seed")
    if not os.path.exists(db):
        subprocess.run([smql, "import", "replica", os.path.join(data, "replica-room0/info_semantic.json"), "--db",
                        db], check=True, stdout=subprocess.DEVNULL)
    exported = subprocess.run([smql, "export", "json", "--db", db], check=True, capture_output=True).stdout
    scene = json.loads(exported)
    objects = [n["id"] for n in scene["nodes"] if n["kind"] == "object"]
    rng = random.Random(count)
    scene["relations"] = [{"subject": a, "object": b, "type": "near", "score": 0.5, "support": 1, "frame": 0}
                          for a, b in (rng.sample(objects, 2) for _ in range(count))]
    return scene


def vsibench_rooms(data, count):
    rooms = {}
    for name in ("scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"):
        with open(os.path.join(data, "real-layouts", name)) as f:
            rooms.update(json.load(f))
    out, names = {}, list(rooms)
    for i in range(count):
        out[f"{names[i % len(names)]}_{i // len(names)}"] = rooms[names[i % len(names)]]
    return out


def tiled_replica(data, count):
    with open(os.path.join(data, "replica-room0/info_semantic.json")) as f:
        room = json.load(f)
    objects = room["objects"]
    out = copy.deepcopy(room)
    out["objects"] = []
    for i in range(count):
        o = copy.deepcopy(objects[i % len(objects)])
        o["id"] = i + 1
        tile = i // len(objects)
        o["oriented_bbox"]["orientation"]["translation"][0] += (tile % 30) * 12
        o["oriented_bbox"]["orientation"]["translation"][1] += (tile // 30) * 12
        out["objects"].append(o)
    return out


CASES = [
    ("json", "relations", (100_000, 200_000, 400_000), relations_scene, []),
    ("vsibench", "rooms", (300, 600, 1200), lambda data, work, smql, n: vsibench_rooms(data, n), ["--all"]),
    ("replica", "objects", (12_500, 25_000, 50_000), lambda data, work, smql, n: tiled_replica(data, n), []),
]


def median_seconds(run, runs):
    samples = []
    for _ in range(runs):
        start = time.perf_counter()
        run()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def measure(smql, data, runs):
    rows = []
    work = tempfile.mkdtemp(prefix="smql-import-scaling-")
    try:
        for form, unit, sizes, make, flags in CASES:
            before = None
            for n in sizes:
                path = os.path.join(work, f"{form}-{n}.json")
                with open(path, "w") as f:
                    json.dump(make(data, work, smql, n), f)
                db = os.path.join(work, "db")

                def run_import():
                    shutil.rmtree(db, ignore_errors=True)
                    subprocess.run([smql, "import", form, path, "--db", db, *flags], check=True,
                                   stdout=subprocess.DEVNULL)

                def parse():
                    with open(path) as f:
                        json.load(f)

                seconds = median_seconds(run_import, runs)
                parsed = median_seconds(parse, runs)
                rows.append((form, f"{n:,} {unit}", os.path.getsize(path) / 2**20, seconds,
                             seconds / before if before else None, parsed))
                before = seconds
                os.remove(path)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return rows


def table(rows, runs):
    lines = [f"Median of {runs} runs of `smql import FORMAT FILE --db DB` into a fresh database (wall time, the "
             "process included), each size twice the one before: a step of 2x is linear, 4x quadratic. Python's "
             "`json.load` of the same file is the floor under any import of it.", "",
             "| format | size | file | smql import | step | Python json.load |", "|---|---:|---:|---:|---:|---:|"]
    for form, size, mib, seconds, step, parsed in rows:
        lines.append(f"| {form} | {size} | {mib:.1f} MiB | {seconds:.2f} s | {f'{step:.1f}x' if step else ''} | "
                     f"{parsed:.2f} s |")
    return "\n".join(lines) + "\n"


def write_section(path, body):
    with open(path) as f:
        text = f.read()
    section = f"{HEADING}\n\n{body}"
    if HEADING in text:
        start = text.index(HEADING)
        end = text.find("\n## ", start + len(HEADING))
        rest = text[end + 1:] if end != -1 else ""
        text = text[:start] + section + ("\n" + rest if rest else "")
    else:
        text = text.rstrip("\n") + "\n\n" + section
    with open(path, "w") as f:
        f.write(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("smql")
    parser.add_argument("data")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--out", help="replace the section of this Markdown file (docs/benchmarks.md)")
    args = parser.parse_args()
    body = table(measure(os.path.realpath(args.smql), args.data, args.runs), args.runs)
    print(body, end="")
    if args.out:
        write_section(args.out, body)


if __name__ == "__main__":
    main()
