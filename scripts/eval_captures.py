#!/usr/bin/env python3
"""Ingests every capture of a fixture folder and prints what came out (docs/ingest.md, "Real
captures"): exit status, seconds, peak memory, the plausibility checks, walls, floor and named
objects. The judgement of right and wrong (is the floor the floor? are the chairs chairs?) is made
by looking at the photos; this script gathers the figures.

    scripts/eval_captures.py SMQL FIXTURES [--only NAME ...] [--json OUT]

FIXTURES holds one folder per capture (a video is the one .mp4/.mov file in its folder) and may
hold OPTIONS.json: {"name": ["--fps", "5"]} for captures that need options.
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys
import tempfile
import time


def capture_path(folder):
    videos = [p for p in folder.iterdir() if p.suffix.lower() in (".mp4", ".mov", ".avi", ".mkv")]
    return videos[0] if len(videos) == 1 and not (folder / "color").exists() else folder


def run(smql, folder, options):
    with tempfile.TemporaryDirectory() as work:
        db = pathlib.Path(work) / "db"
        start = time.monotonic()
        proc = subprocess.run(["/usr/bin/time", "-f", "%M", smql, "ingest", str(capture_path(folder)), "--db", str(db),
                               "--log", "json", *options], capture_output=True, text=True)
        seconds = time.monotonic() - start
        lines = proc.stderr.strip().splitlines()
        peak_mb = int(lines[-1]) / 1024 if lines and lines[-1].isdigit() else None
        notes = [json.loads(l)["text"] for l in lines if l.startswith("{") and '"note"' in l]
        errors = [l for l in lines if not l.startswith("{") and not l.isdigit()]
        row = {"name": folder.name, "exit": proc.returncode, "seconds": round(seconds, 1), "peak_mb": peak_mb,
               "findings": [n for n in notes if n.startswith(("warning:", "implausible"))],
               "misnamed": [n for n in notes if "detected as" in n], "error": " ".join(errors)[:400]}
        if proc.returncode == 0:
            def query(statement):
                out = subprocess.run([smql, str(db), "-json", statement], capture_output=True, text=True).stdout
                return json.loads(out)[-1]["rows"] if out.strip() else []
            row["walls"] = query("COUNT wall")[0]["count"]
            row["floor"] = query("COUNT floor")[0]["count"] > 0
            objects = query("FIND object RETURN category")
            counts = {}
            for o in objects:
                counts[o["category"]] = counts.get(o["category"], 0) + 1
            row["objects"] = dict(sorted(counts.items(), key=lambda kv: -kv[1]))
            check = subprocess.run([smql, "check-ingest", str(db), "--format", "json"], capture_output=True, text=True)
            report = json.loads(check.stdout) if check.stdout.strip() else {}
            row["camera_height_m"] = report.get("camera_height_m")
            row["size_ratio"] = report.get("size_ratio")
        return row


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("smql")
    parser.add_argument("fixtures", type=pathlib.Path)
    parser.add_argument("--only", nargs="*")
    parser.add_argument("--json")
    args = parser.parse_args()
    options_file = args.fixtures / "OPTIONS.json"
    options = json.loads(options_file.read_text()) if options_file.exists() else {}
    rows = []
    for folder in sorted(p for p in args.fixtures.iterdir() if p.is_dir() and not p.name.startswith(("_", "."))):
        if args.only and folder.name not in args.only:
            continue
        row = run(args.smql, folder, options.get(folder.name, []))
        print(json.dumps(row), flush=True)
        rows.append(row)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    sys.exit(main())
