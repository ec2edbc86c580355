#!/usr/bin/env python3
"""ASK on the shared real rooms, imported two ways (docs/ask.md, "How well it answers").

Every room of ../shared/data/real-layouts (VSI-Bench's 238 validation rooms) is imported twice:
through `smql import vsibench`, and through the smql JSON format with its categories spelt as
VSI-Bench's file spells them (`trash bin`, `computer mouse`: spaces, as a person or another tool
writes them). Each room is asked, about each category it holds, questions in several wordings: VSI-Bench's
count and size templates, a person's phrasings, units in other forms, the scene named ("in here",
"in this room"). Counts are scored exactly, sizes as right within 5 % of the longest side of the
category's first box. Prints the share right per import and wording, and how many answers differ
between the two imports.

    scripts/eval_ask_imports.py --smql build/shell/smql [--rooms 238] [--jobs 2]
"""
import argparse
import collections
import concurrent.futures
import json
import os
import re
import subprocess
import tempfile

LAYOUTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data", "real-layouts")
FILES = ["scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"]

COUNTS = {
    "template": "How many {c}(s) are in this room?",
    "person": "how many {p} are there in here?",
    "scene named": "how many {p} does this room have?",
}
SIZES = {
    "template": "What is the length of the longest dimension (length, width, or height) of the {c}, measured in "
                "centimeters?",
    "unit in parentheses": "What is the length of the longest dimension of the {c} (cm)?",
    "person, metres": "how long is the {c} in meters?",
}


def plural(word):
    last = word.split(" ")[-1]
    if last.endswith(("s", "x", "ch", "sh")):
        return word + "es"
    if last.endswith("y") and last[-2:-1] not in "aeiou":
        return word[:-1] + "ies"
    return word + "s"


def ask(smql, db, scene, question):
    text = question.replace("'", "''")
    proc = subprocess.run([smql, db, "-json", "-c", f"USE SCENE '{scene}'; ASK '{text}'"], capture_output=True,
                          text=True)
    out = proc.stdout.strip()
    try:
        results = json.loads(out) if out.startswith("[") and out.endswith("]") else []
    except json.JSONDecodeError:
        results = []
    if len(results) < 2:
        return None
    return results[1].get("message", "").split("\n")[-1]


def number(answer, unit):
    if answer is None:
        return None
    if unit == "count":
        m = re.match(r"^(\d+) ", answer)
        return int(m.group(1)) if m else None
    found = re.findall(r"(\d+(?:\.\d+)?) (cm|m)\b", answer)
    if not found:
        return None
    value, u = found[-1]
    return float(value) / (100.0 if u == "cm" else 1.0)


def mra(pred, truth):
    """VSI-Bench's mean relative accuracy over the thresholds 0.50, 0.55, ..., 0.95."""
    if pred is None or truth == 0:
        return 0.0
    rel = abs(pred - truth) / abs(truth)
    return sum(rel < 1 - (0.5 + 0.05 * k) for k in range(10)) / 10


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--smql", default="build/shell/smql")
    ap.add_argument("--rooms", type=int, default=238)
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="smql-eval-imports-")
    via_vsibench, via_json = os.path.join(work, "vsibench"), os.path.join(work, "json")
    rooms = []
    for name in FILES:
        path = os.path.join(LAYOUTS, name)
        layouts = json.load(open(path))
        subprocess.run([args.smql, "import", "vsibench", path, "--all", "--db", via_vsibench], check=True,
                       capture_output=True)
        rooms += [(room, layouts[room]) for room in layouts]
    rooms = rooms[:args.rooms]
    # The same rooms through the JSON format, categories as VSI-Bench's file writes them.
    for room, layout in rooms:
        exported = os.path.join(work, "room.json")
        subprocess.run([args.smql, "export", "json", "--db", via_vsibench, "-o", exported, "--scene", room],
                       check=True, capture_output=True)
        scene = json.load(open(exported))
        written = {c.replace(" ", "-").lower(): c for c in layout["object_bbox"]}
        for node in scene.get("nodes", []):
            node["category"] = written.get(node.get("category"), node.get("category"))
        json.dump(scene, open(exported, "w"))
        subprocess.run([args.smql, "import", "json", exported, "--db", via_json, "--scene", room], check=True,
                       capture_output=True)

    jobs = []
    for room, layout in rooms:
        for category, boxes in layout["object_bbox"].items():
            for wording, form in COUNTS.items():
                jobs.append(("count", wording, room, form.format(c=category, p=plural(category)), len(boxes)))
            if len(boxes) == 1:
                for wording, form in SIZES.items():
                    jobs.append(("size", wording, room, form.format(c=category), max(boxes[0]["axesLengths"])))

    def run(job):
        kind, wording, room, question, truth = job
        got = {}
        for label, db in (("vsibench", via_vsibench), ("json", via_json)):
            got[label] = ask(args.smql, db, room, question)
        return job, got

    right = collections.defaultdict(float)
    total = collections.Counter()
    differ = 0
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for (kind, wording, room, question, truth), got in pool.map(run, jobs):
            differ += got["vsibench"] != got["json"]
            for label, answer in got.items():
                value = number(answer, "count" if kind == "count" else "length")
                if kind == "count":
                    score = float(value is not None and value == truth)
                else:
                    score = mra(value, truth)
                total[(kind, wording, label)] += 1
                right[(kind, wording, label)] += score
    print(f"{len(rooms)} rooms, {len(jobs)} questions, each asked of both imports")
    print("| kind | wording | questions | score, import vsibench | score, JSON with spaced names |")
    print("|---|---|---:|---:|---:|")
    for kind, forms in (("count", COUNTS), ("size", SIZES)):
        for wording in forms:
            n = total[(kind, wording, "vsibench")]
            print(f"| {kind} | {wording} | {n} | {right[(kind, wording, 'vsibench')] / n:.3f} | "
                  f"{right[(kind, wording, 'json')] / n:.3f} |")
    all_v = sum(v for (k, w, l), v in right.items() if l == "vsibench") / len(jobs)
    all_j = sum(v for (k, w, l), v in right.items() if l == "json") / len(jobs)
    print(f"| all | | {len(jobs)} | {all_v:.3f} | {all_j:.3f} |")
    print(f"answers that differ between the two imports: {differ} of {len(jobs)}")


if __name__ == "__main__":
    main()
