#!/usr/bin/env python3
"""smql eval over real room layouts: the Replica room and VSI-Bench's ScanNet and ARKitScenes rooms.

Each room is imported, scored with the suite `smql eval` generates from it (docs/eval.md, "Suites for
real layouts"), and the metrics are pooled per data set (every episode of every room counts once).
Prints the Markdown table of docs/eval.md, "Real layouts".

    scripts/eval_layouts.py build/shell/smql ../shared/data [--rooms N] [--replica info_semantic.json ...] [--digits D]

--replica adds other Replica rooms, one column each (docs/guidance.md, "On real rooms").
"""
import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile


def smql(binary, *args):
    done = subprocess.run([binary, *args], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"smql {' '.join(args)} failed:\n{done.stderr}")
    return done.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("smql", help="the smql binary")
    parser.add_argument("data", help="the shared data folder (replica-room0/, real-layouts/)")
    parser.add_argument("--rooms", type=int, default=0, help="at most this many rooms of each data set (0: all)")
    parser.add_argument("--replica", nargs="*", default=[], help="more Replica info_semantic.json files, a column each")
    parser.add_argument("--digits", type=int, default=2, help="decimals of each figure")
    options = parser.parse_args()

    sets = [("Replica room0", "replica", os.path.join(options.data, "replica-room0/info_semantic.json")),
            ("ScanNet (VSI-Bench)", "vsibench", os.path.join(options.data, "real-layouts/scannet_meta_info_val.json")),
            ("ARKitScenes (VSI-Bench)", "vsibench",
             os.path.join(options.data, "real-layouts/arkitscenes_meta_info_val.json"))]
    # A column is named by its file, or by its folder when the file has Replica's own name.
    sets += [(f"Replica {os.path.basename(os.path.dirname(os.path.abspath(path)))}"
              if os.path.basename(path) == "info_semantic.json" else f"Replica {os.path.basename(path)}", "replica", path)
             for path in options.replica]
    columns = []
    pooled = {}
    with tempfile.TemporaryDirectory() as work:
        for label, form, path in sets:
            db = os.path.join(work, form + str(len(columns)))
            smql(options.smql, "import", form, path, "--db", db, *(["--all"] if form == "vsibench" else []))
            scenes = [line.split()[0] for line in smql(options.smql, db, "-tsv", "SHOW SCENES").splitlines()[1:]]
            if options.rooms:
                scenes = scenes[:options.rooms]
            sums = collections.OrderedDict()
            for scene in scenes:
                out = os.path.join(work, "metrics.json")
                smql(options.smql, "eval", "--db", db, "--scene", scene, "--json", out)
                for row in json.load(open(out))["metrics"]:
                    key = (row["task"], row["metric"])
                    value, episodes = sums.get(key, (0.0, 0))
                    sums[key] = (value + row["value"] * row["episodes"], episodes + row["episodes"])
            columns.append(f"{label} ({len(scenes)} rooms)")
            pooled[columns[-1]] = sums

    keys = list(collections.OrderedDict.fromkeys(k for sums in pooled.values() for k in sums))
    print("| task | metric | " + " | ".join(columns) + " |")
    print("|---|---|" + "---:|" * len(columns))
    for task, metric in keys:
        if metric.startswith("Acc_rel (") or metric == "Color Acc":
            continue  # per anchor type and colour: layouts name neither consistently
        cells = []
        for column in columns:
            value, episodes = pooled[column].get((task, metric), (0.0, 0))
            cells.append(f"{value / episodes:.{options.digits}f} ({episodes})" if episodes else "-")
        print(f"| {task} | {metric} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
