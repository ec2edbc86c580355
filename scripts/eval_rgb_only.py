#!/usr/bin/python3
"""RGB-only memory of a capture against the truth: smql ingests photos without depth through COLMAP
(poses up to scale), then places a floor and a metric scale. For each capture this records whether
the memory was placed or refused (and why), its scale against the truth, the cameras' height above
the floor, the floor's tilt against the truth and the objects stored.

    scripts/eval_rgb_only.py SMQL [--only NAME ...] [--json OUT] [--runs N] [--max-frames 100]
                             [--work DIR] [--timeout SECONDS] [--rgb-options '--force']
                             [--colmap-dir DIR] CAPTURE_DIR ...
    scripts/eval_rgb_only.py --table OUT.json ...      (print the table of earlier runs)

Each CAPTURE_DIR is
1. an RGB-D capture (rgbd: color/ depth/ pose.txt [camera.json]; tum: rgb/ depth/ rgb.txt depth.txt
   groundtruth.txt camera.json): ingested as is (the metric reference, --fps 0 --force), then its
   colour frames alone (evenly subsampled to --max-frames, with camera.json's intrinsics and no
   depth; colour_camera.json's instead when the capture has one, {} for none) as a photo folder; the
   two memories are compared by their cameras (matched by colour image): scale = median ratio of the
   distances between pairs of cameras (true distance > 0.1 m), median camera height in both, the
   floor's tilt (the rotation of a similarity fitted from the RGB memory's cameras to the RGB-D
   memory's, applied to z), the objects and the tables' sizes;
2. a folder of photos named by TUM timestamp with groundtruth.txt: ingested as is, the cameras
   compared with the motion capture (nearest pose within 0.02 s) for the scale;
3. any other capture (photos, video, nerfstudio): ingested as is, with options from OPTIONS.json in
   its parent folder ({"name": ["--fps", "5"]}).
The RGB-only ingests are repeated --runs times (the same on one machine since COLMAP's runs repeat). With --colmap-dir DIR,
run N keeps COLMAP's work folder in DIR/NAME/run-N (smql ingest --colmap-dir), and a later evaluation
of the same frames with the same options reads that model back instead of running COLMAP again; the
photo folders made from RGB-D captures are then DIR/NAME/photos, so that any --work finds them alike
(smql's record of a COLMAP run names each frame's path).
"""
import argparse
import itertools
import json
import math
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

# TUM's groundtruth.txt as the real_captures test reads it.
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tests" / "e2e"))
from real_captures_test import true_position_at, true_positions  # noqa: E402
from eval_objects import FITS, score_objects, stored_things, umeyama  # noqa: E402  (scripts/, this file's folder)

IMAGE_EXTENSIONS = (".png", ".jpg", ".jpeg")
VIDEO_EXTENSIONS = (".mp4", ".mov", ".avi", ".mkv")
TABLES = ("table", "desk", "dining table", "coffee table")


def natural_key(path):
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", pathlib.PurePath(path).name)]


# ---------------------------------------------------------------------------------------------------
# Running smql


def ingest(smql, capture, db, options, timeout):
    """Runs `smql ingest` with json progress; returns what it said."""
    command = [smql, "ingest", str(capture), "--db", str(db), *options, "--log", "json"]
    start = time.monotonic()
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
        status = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)  # the ingest and the COLMAP it started, nothing else
        out, err = proc.communicate()
        status = "timeout"
    seconds = time.monotonic() - start
    notes, summaries, other = [], {}, []
    for line in (err + "\n" + out).splitlines():
        if line.startswith("{"):
            try:
                event = json.loads(line)
            except ValueError:
                other.append(line)
                continue
            if event.get("event") == "note":
                notes.append(event.get("text", ""))
            elif event.get("event") == "stage_finished":
                summaries[event.get("stage")] = event.get("summary", "")
        elif line.strip():
            other.append(line.strip())
    text = "\n".join(notes + list(summaries.values()) + other)
    registered = re.search(r"(\d+) of (\d+) frames registered", text)
    dense = [n for n in notes if n.startswith("dense:")]
    reason = None
    if status != 0:
        errors = [line for line in other if "error" in line or "wrong" in line]
        reason = "timeout" if status == "timeout" else " | ".join(errors or other[-3:])
    return {
        "command": " ".join(command), "exit": status, "seconds": round(seconds, 1), "reason": reason,
        "frames_registered": int(registered.group(1)) if registered else None,
        "frames_seen": int(registered.group(2)) if registered else None,
        "dense": dense[0] if dense else None, "notes": notes, "summaries": summaries, "said": other,
    }


def query(smql, db, statement):
    out = subprocess.run([smql, str(db), "-json", statement], capture_output=True, text=True)
    if out.returncode != 0 or not out.stdout.strip():
        return []
    return json.loads(out.stdout)[-1].get("rows", [])


def stored_cameras(smql, db):
    """{image path as stored: (x, y, z)}"""
    return {r["text"]: (r["x"], r["y"], r["z"]) for r in query(smql, db, "FIND frame RETURN text, x, y, z")
            if r.get("text") is not None and r.get("x") is not None}


def stored_objects(smql, db):
    """({category: count}, [(category, [sx, sy, sz]) of tables and desks])"""
    counts, tables = {}, []
    for row in query(smql, db, "FIND object RETURN category, box"):
        category = row.get("category") or "?"
        counts[category] = counts.get(category, 0) + 1
        if category in TABLES and row.get("box"):
            tables.append((category, [round(v, 2) for v in row["box"]["size"]]))
    return dict(sorted(counts.items())), tables


def median(values):
    values = sorted(values)
    return values[len(values) // 2] if values else None


# ---------------------------------------------------------------------------------------------------
# Geometry


def pair_scale(pairs):
    """Median over camera pairs of stored distance / true distance (true distance > 0.1 m)."""
    ratios = [math.dist(a, b) / math.dist(ta, tb)
              for (a, ta), (b, tb) in itertools.combinations(pairs, 2) if math.dist(ta, tb) > 0.1]
    return median(ratios), len(ratios)


# The cameras' spread along the second of their axes (RMS, metres) below which the similarity's rotation, and
# so the tilt, is not measured: cameras along a line leave the turn about it open, and TUM fr1/rpy's camera,
# which turns on the spot, spreads 5 and 3 cm, where centres a centimetre off turn the fit by degrees. A walk
# at one height spreads over a plane, which fixes the rotation.
MIN_SPREAD_FOR_TILT = 0.1


def tilt_and_spread(rgb, rgbd):
    """Floor tilt (degrees between R z and z; None when the true cameras' spread along their second axis is
    under MIN_SPREAD_FOR_TILT) and the singular value ratios of the true cameras."""
    sv = np.linalg.svd(np.asarray(rgbd, float) - np.mean(rgbd, 0), compute_uv=False)
    s2, s3 = (float(sv[1] / sv[0]), float(sv[2] / sv[0])) if sv[0] > 0 else (0.0, 0.0)
    if sv[1] / math.sqrt(len(rgbd)) < MIN_SPREAD_FOR_TILT:
        return None, round(s2, 3), round(s3, 3)
    _, r, _ = umeyama(rgb, rgbd)
    up = r @ np.array([0.0, 0.0, 1.0])
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, float(up[2])))))
    return round(tilt, 2), round(s2, 3), round(s3, 3)


# ---------------------------------------------------------------------------------------------------
# Captures


def kind_of(folder):
    if folder.is_dir() and (folder / "color").is_dir() and (folder / "depth").is_dir():
        return "rgbd"
    if folder.is_dir() and (folder / "rgb.txt").is_file() and (folder / "depth.txt").is_file():
        return "tum"
    if folder.is_dir() and (folder / "groundtruth.txt").is_file():
        return "photos+truth"
    return "other"


def capture_path(folder):
    """A video capture is the one video file in its folder."""
    if not folder.is_dir():
        return folder
    videos = [p for p in folder.iterdir() if p.suffix.lower() in VIDEO_EXTENSIONS]
    return videos[0] if len(videos) == 1 and not (folder / "color").exists() else folder


def colour_frames(folder, kind):
    """The capture's colour images in capture order."""
    if kind == "rgbd":
        return sorted((p for p in (folder / "color").iterdir() if p.suffix.lower() in IMAGE_EXTENSIONS),
                      key=natural_key)
    frames = []
    for line in (folder / "rgb.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            frames.append(folder / line.split()[1])
    return frames


def subsample(items, limit):
    if len(items) <= limit:
        return list(items)
    return [items[round(i * (len(items) - 1) / (limit - 1))] for i in range(limit)]


def make_photo_folder(folder, kind, photos, max_frames):
    """Copies the colour frames (subsampled) to `photos` as 0000.ext ..., with camera.json's
    intrinsics and no depth scale. Returns ({photo name: original path}, frames in the capture, note)."""
    if photos.exists():
        shutil.rmtree(photos)
    photos.mkdir(parents=True)
    frames = colour_frames(folder, kind)
    chosen = subsample(frames, max_frames)
    origin = {}
    for i, frame in enumerate(chosen):
        name = f"{i:04d}{frame.suffix.lower()}"
        shutil.copy2(frame, photos / name)
        origin[name] = os.path.normpath(frame)
    note = None
    if (folder / "colour_camera.json").is_file():
        # The colour camera's own calibration where the capture's camera.json is its depth camera's (7-Scenes
        # gives only the depth camera's 585 px; its colour camera's is about 526): {} when it is unknown, and
        # COLMAP estimates it.
        camera = json.loads((folder / "colour_camera.json").read_text())
        if camera:
            (photos / "camera.json").write_text(json.dumps(camera) + "\n")
        return origin, len(frames), None if camera else "colour camera unknown: COLMAP estimates it"
    if (folder / "camera.json").is_file():
        given = json.loads((folder / "camera.json").read_text())
        camera = {k: given[k] for k in ("width", "height", "fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3")
                  if k in given}
    else:
        import cv2
        height, width = cv2.imread(str(chosen[0])).shape[:2]
        f = 525.0 * width / 640.0  # what smql assumes for an rgbd capture without camera.json
        camera = {"width": width, "height": height, "fx": f, "fy": f, "cx": (width - 1) / 2, "cy": (height - 1) / 2}
        note = "no camera.json: photos given the Kinect default intrinsics smql uses for the RGB-D ingest"
    (photos / "camera.json").write_text(json.dumps(camera) + "\n")
    return origin, len(frames), note


def stored_key(text, folder):
    path = pathlib.Path(text)
    return os.path.normpath(path if path.is_absolute() else folder / path)


def capture_positions(folder, kind):
    """{colour image path: camera centre} from the capture's own metric poses (pose.txt for rgbd,
    groundtruth.txt nearest within 0.02 s for tum), in the capture's frame."""
    frames = colour_frames(folder, kind)
    positions = {}
    if kind == "rgbd":
        lines = [line for line in (folder / "pose.txt").read_text().splitlines()
                 if line.strip() and not line.lstrip().startswith("#")]
        for frame, line in zip(frames, lines):
            values = [float(v) for v in line.split()[:3]]
            if all(math.isfinite(v) for v in values):
                positions[os.path.normpath(frame)] = values
    else:
        times, centres = true_positions(folder / "groundtruth.txt")
        for frame in frames:
            if (truth := true_position_at(times, centres, float(frame.stem))) is not None:
                positions[os.path.normpath(frame)] = truth
    return positions


def compare_memories(smql, rgb_db, rgbd_db, origin, folder, kind):
    """The RGB memory's cameras against the truth in the RGB-D memory's frame (metres, z up, floor at
    0). The RGB-D memory stores keyframes only, so every photo's true position is the capture's own
    pose carried into that frame by the rigid motion fitted on the RGB-D memory's keyframes."""
    stored = {stored_key(t, folder): p for t, p in stored_cameras(smql, rgbd_db).items()}
    poses = capture_positions(folder, kind)
    common = [k for k in stored if k in poses]
    result = {"rgbd_frames": len(stored)}
    truth = dict(stored)
    if len(common) >= 3:
        s, r, t = umeyama([poses[k] for k in common], [stored[k] for k in common])
        fit = [s * r @ np.asarray(poses[k]) + t for k in common]
        result["pose_fit"] = {"keyframes": len(common), "scale": round(s, 4),
                              "rms_cm": round(100 * float(np.sqrt(np.mean([np.sum((f - np.asarray(stored[k])) ** 2)
                                                                          for f, k in zip(fit, common)]))), 1)}
        truth.update({k: tuple(s * r @ np.asarray(p) + t) for k, p in poses.items()})
    pairs = []
    for text, position in stored_cameras(smql, rgb_db).items():
        original = origin.get(pathlib.PurePath(text).name)
        if original in truth:
            pairs.append((position, truth[original]))
    result["matched"] = len(pairs)
    if len(pairs) < 3:
        return result
    scale, npairs = pair_scale(pairs)
    h_rgb = median(p[2] for p, _ in pairs)
    h_rgbd = median(t[2] for _, t in pairs)
    tilt, s2, s3 = tilt_and_spread([p for p, _ in pairs], [t for _, t in pairs])
    result.update(scale=round(scale, 3) if scale else None, scale_pairs=npairs,
                  height_rgb=round(h_rgb, 3), height_rgbd=round(h_rgbd, 3),
                  height_diff_cm=round(100 * (h_rgb - h_rgbd), 1),
                  tilt_deg=tilt, sv2_over_sv1=s2, sv3_over_sv1=s3)
    result["objects_vs_rgbd"] = objects_against(smql, rgb_db, rgbd_db, pairs)
    return result


def objects_against(smql, rgb_db, rgbd_db, pairs):
    """The RGB memory's things against the RGB-D memory's, as eval_objects.py scores things against true boxes:
    the RGB memory carried into the RGB-D memory's frame by the similarity its cameras fit, the RGB-D memory's
    things of the kinds FITS scores taken as the truth (its `object`s, which no model named, are not scored)."""
    s, r, t = umeyama([p for p, _ in pairs], [q for _, q in pairs])
    truth = [dict(thing, structural=False) for thing in stored_things(smql, rgbd_db)]
    moved = []
    for thing in stored_things(smql, rgb_db):
        centre = s * r @ thing["center"] + t
        half = s * (thing["hi"] - thing["lo"]) / 2
        moved.append(dict(thing, center=centre, sides=tuple(s * v for v in thing["sides"]),
                          lo=centre - half, hi=centre + half))
    labels = {thing["category"] for thing in truth if thing["category"] in FITS}
    score = score_objects(truth, labels, moved)
    return {k: score[k] for k in ("truth", "stored", "matched", "duplicated", "precision", "recall", "f1",
                                  "missed_things", "extra_things")}


def compare_with_truth(smql, db, groundtruth):
    """Stored cameras against TUM's motion capture, as tests/e2e/real_captures_test.py against_truth, with the
    cameras' spread."""
    times, centres = true_positions(groundtruth)
    pairs = []
    for name, stored in stored_cameras(smql, db).items():
        try:
            t = float(pathlib.PurePath(name).stem)
        except ValueError:
            continue
        if (truth := true_position_at(times, centres, t)) is not None:
            pairs.append((stored, truth))
    result = {"matched": len(pairs)}
    if len(pairs) >= 3:
        scale, npairs = pair_scale(pairs)
        result.update(scale=round(scale, 3) if scale else None, scale_pairs=npairs,
                      height_rgb=round(median(p[2] for p, _ in pairs), 3))
        # Tilt is not measured: the motion capture's z is not the floor's normal.
        sv = np.linalg.svd(np.asarray([t for _, t in pairs]) - np.mean([t for _, t in pairs], 0), compute_uv=False)
        result.update(sv2_over_sv1=round(float(sv[1] / sv[0]), 3), sv3_over_sv1=round(float(sv[2] / sv[0]), 3))
    return result


def rgb_run(smql, capture, db, options, timeout, run):
    if db.exists():
        shutil.rmtree(db)
    outcome = ingest(smql, capture, db, options, timeout)
    outcome["run"] = run
    outcome["placed"] = outcome["exit"] == 0
    if outcome["placed"]:
        cameras = stored_cameras(smql, db)
        outcome["frames_stored"] = len(cameras)
        if "height_rgb" not in outcome and cameras:
            outcome["height_rgb"] = round(median(c[2] for c in cameras.values()), 3)
        outcome["objects"], outcome["tables"] = stored_objects(smql, db)
    return outcome


def colmap_options(args, work, run):
    """--colmap-dir DIR/NAME/run-N for run N when --colmap-dir DIR was given."""
    if not args.colmap_dir:
        return []
    folder = pathlib.Path(args.colmap_dir).resolve() / work.name / f"run-{run}"
    folder.parent.mkdir(parents=True, exist_ok=True)
    return ["--colmap-dir", str(folder)]


def evaluate(smql, folder, args, log):
    name = folder.name
    kind = kind_of(folder)
    work = pathlib.Path(args.work) / (name + ("-" + args.rgb_options.strip("- ").replace(" ", "_") if args.rgb_options else ""))
    work.mkdir(parents=True, exist_ok=True)
    record = {"name": work.name, "kind": kind, "capture": str(folder), "rgb_options": args.rgb_options, "runs": []}
    if kind in ("rgbd", "tum"):
        if (work / "rgbd").exists():
            shutil.rmtree(work / "rgbd")
        reference = ingest(smql, folder, work / "rgbd", ["--fps", "0", "--force"], args.timeout)
        record["rgbd"] = {k: reference[k] for k in ("exit", "seconds", "reason", "command")}
        log(f"{name}: RGB-D reference exit {reference['exit']} in {reference['seconds']} s")
        if reference["exit"] == 0:
            record["rgbd"]["frames_stored"] = len(stored_cameras(smql, work / "rgbd"))
            record["rgbd"]["objects"], record["rgbd"]["tables"] = stored_objects(smql, work / "rgbd")
        photos = (pathlib.Path(args.colmap_dir).resolve() / work.name if args.colmap_dir else work) / "photos"
        origin, total, note = make_photo_folder(folder, kind, photos, args.max_frames)
        record.update(frames_in_capture=total, frames_given=len(origin), photo_note=note)
        for run in range(1, args.runs + 1):
            db = work / f"rgb-{run}"
            outcome = rgb_run(smql, photos, db, args.rgb_options.split() + colmap_options(args, work, run),
                              args.timeout, run)
            if outcome["placed"] and reference["exit"] == 0:
                outcome.update(compare_memories(smql, db, work / "rgbd", origin, folder, kind))
            record["runs"].append(outcome)
            log(f"{name} run {run}: {row_text(record, outcome)}")
    else:
        capture = capture_path(folder)
        options = []
        options_file = folder.parent / "OPTIONS.json"
        if options_file.is_file():
            options = json.loads(options_file.read_text()).get(name, [])
        record["options"] = options
        if folder.is_dir() and capture == folder:
            images = [p for p in folder.rglob("*") if p.suffix.lower() in IMAGE_EXTENSIONS]
            record["frames_given"] = len(images)
        for run in range(1, args.runs + 1):
            db = work / f"rgb-{run}"
            outcome = rgb_run(smql, capture, db, options + args.rgb_options.split() + colmap_options(args, work, run),
                              args.timeout, run)
            if outcome["placed"] and kind == "photos+truth":
                outcome.update(compare_with_truth(smql, db, folder / "groundtruth.txt"))
            if record.get("frames_given") is None and outcome.get("frames_seen"):
                record["frames_given"] = outcome["frames_seen"]
            record["runs"].append(outcome)
            log(f"{name} run {run}: {row_text(record, outcome)}")
    return record


# ---------------------------------------------------------------------------------------------------
# Report


def fmt(value, spec):
    return format(value, spec) if isinstance(value, (int, float)) and value is not None else "-"


HEADER = (f"{'capture':32} {'kind':12} {'run':>3} {'given':>5} {'reg':>5} {'exit':>7} {'secs':>6} "
          f"{'scale':>6} {'h_rgb':>6} {'h_rgbd':>6} {'dh_cm':>6} {'tilt':>6} {'sv2':>5} {'sv3':>5}  result")


def row_text(record, run):
    if run["placed"]:
        objects = ", ".join(f"{k} {v}" for k, v in run.get("objects", {}).items())
        result = f"placed; objects: {objects or 'none'}"
        if run.get("tables"):
            result += "; tables " + " ".join("x".join(f"{v:.2f}" for v in size) for _, size in run["tables"])
        if run.get("dense"):
            result += f"; {run['dense']}"
        if against := run.get("objects_vs_rgbd"):
            result += (f"; against the RGB-D memory's {against['truth']} things: {against['matched']} matched of "
                       f"{against['stored']} stored, F1 {against['f1']:.2f}")
    else:
        result = f"refused: {run.get('reason')}"
    return (f"{record['name'][-32:]:32} {record['kind']:12} {run['run']:>3} {fmt(record.get('frames_given'), 'd'):>5} "
            f"{fmt(run.get('frames_registered'), 'd'):>5} {str(run['exit']):>7} {fmt(run['seconds'], '.0f'):>6} "
            f"{fmt(run.get('scale'), '.3f'):>6} {fmt(run.get('height_rgb'), '.2f'):>6} "
            f"{fmt(run.get('height_rgbd'), '.2f'):>6} {fmt(run.get('height_diff_cm'), '.0f'):>6} "
            f"{fmt(run.get('tilt_deg'), '.1f'):>6} {fmt(run.get('sv2_over_sv1'), '.2f'):>5} "
            f"{fmt(run.get('sv3_over_sv1'), '.2f'):>5}  {result}")


def print_table(records):
    print(HEADER)
    for record in records:
        for run in record["runs"]:
            print(row_text(record, run))
        reference = record.get("rgbd")
        if reference:
            objects = ", ".join(f"{k} {v}" for k, v in reference.get("objects", {}).items())
            tables = " ".join("x".join(f"{v:.2f}" for v in size) for _, size in reference.get("tables", []))
            print(f"{'':32} {'(RGB-D ref)':12} {'':>3} {'':>5} {fmt(reference.get('frames_stored'), 'd'):>5} "
                  f"{str(reference['exit']):>7} {fmt(reference['seconds'], '.0f'):>6}  objects: {objects or 'none'}"
                  + (f"; tables {tables}" if tables else "")
                  + (f"; {reference['reason']}" if reference.get("reason") else ""))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("smql", nargs="?")
    parser.add_argument("captures", nargs="*", type=pathlib.Path)
    parser.add_argument("--only", nargs="+", default=None)
    parser.add_argument("--json", dest="json_out")
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--max-frames", type=int, default=100)
    parser.add_argument("--work", default="/tmp/rgbonly")
    parser.add_argument("--timeout", type=float, default=900, help="seconds an ingest may take (default 900)")
    parser.add_argument("--rgb-options", default="", help="extra options for the RGB-only ingests, e.g. '--force'")
    parser.add_argument("--colmap-dir", help="keep COLMAP's work folders under this folder and reuse them")
    parser.add_argument("--table", nargs="+", help="print the table of earlier --json outputs and exit")
    args = parser.parse_intermixed_args()
    if args.table:
        records = []
        for path in args.table:
            records += json.loads(pathlib.Path(path).read_text())
        print_table(records)
        return 0
    if not args.smql or not args.captures:
        parser.error("SMQL and at least one CAPTURE_DIR are required")
    smql = str(pathlib.Path(args.smql).resolve())

    def log(message):
        print(f"[{time.strftime('%H:%M:%S', time.gmtime())}] {message}", flush=True)

    records = []
    start = time.monotonic()
    for folder in args.captures:
        folder = pathlib.Path(os.path.abspath(folder))
        if args.only and folder.name not in args.only:
            continue
        log(f"{folder.name}: {kind_of(folder)}")
        records.append(evaluate(smql, folder, args, log))
        if args.json_out:  # after each capture, so that an interrupted run keeps what it measured
            pathlib.Path(args.json_out).write_text(json.dumps(records, indent=1) + "\n")
    print()
    print_table(records)
    print(f"\ntotal {time.monotonic() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
