#!/usr/bin/python3
"""Objects of real captures against their true 3D boxes, end to end (docs/ingest.md, "Objects
against the truth"): each capture is ingested as a user would, its stored things matched to the
truth's, and questions whose answers follow from the truth boxes asked in English.

    scripts/eval_objects.py SMQL CAPTURE... [--options "--objects detect"] [--json OUT]
                            [--keep DIR] [--reuse] [--thinned EVERY:FROM ...]

A CAPTURE is a folder smql ingests (rgbd, tum ...) holding truth.json:
    {"up": [0, 0, 1], "source": "ScanNet ...", "unlabelled": ["chair"],
     "objects": [{"category": "bed", "center": [x, y, z], "size": [sx, sy, sz],
                  "rotation": [9 numbers, row after row, box axes -> world] or "yaw": radians}]}
in the frame of the capture's poses (pose.txt). "unlabelled" names classes of the truth's label set
that its annotators left out in this room (their stored things are not counted either way).

Matching (one to one, nearest first): a truth thing is matched by a stored thing of a fitting name
(FITS) whose centre is within 0.5 m of its centre and whose sides are each within 50 % of its sides
(the height against the height, the longer and the shorter horizontal side against theirs). Only
truth things a packaged model can name are scored (FITS' keys), and of the stored things only those
whose name fits a class the truth labels. A stored thing that is not the match but fits a truth
thing's name and lies on it (its centre within 0.5 m, or its centre inside the truth box) is a
duplicate. Implausible: a stored thing with a side under 3 cm, a side over 4 m, or a name its box
does not fit (stored as `object` with detected_as; a thing the ingest named by its use, a suitcase
among seats stored as a table, is not).

Questions (ASK, in English) about the truth's classes that a model can name and the truth labels:
how many X (the count), is there a X (also for classes that are absent), how long is the X (one
thing of its kind: the answer's one number within 25 % of the longest side), how far is X from Y
(both one of a kind: within 25 % or 0.15 m of the gap between the boxes), what is on the X (where
the truth has labelled things resting on it: the named kinds agree).

Appearance order (VSI-Bench's question, in its words, counted apart from the questions above): for
captures of several frames with depth, a true thing is first seen in the first frame where 15 or
more of the points on its box's faces project into the image and lie within 0.1 m of the depth
there (seen, not hidden); a kind is first seen when its first thing is. Of the kinds scored above,
each set of four (else three, else two) whose first sights lie 10 or more frames apart is asked
"What will be the first-time appearance order of the following categories in the video: a, b, c,
d?", and is right when the answer orders them as the truth does.

VSI-Bench's relative questions, in its words, also counted apart: relative distance ("Measuring from the
closest point of each object, which of these objects (a, b, c, d) is the closest to the x?", x one of its kind,
the other scored kinds offered four at a time, right when the answer names the kind whose nearest thing's box
lies closest to x's; not asked when the next lies within 0.15 m as close) and relative direction ("If I am
standing by the x and facing the y, is the z to my front-left, front-right, back-left, or back-right?", each of
three kinds one of its kind, by their boxes' centres; not asked within 15 degrees of a quadrant's edge), and
route plans in its fill-in form (from a thing facing a second, forward to it, then by a third to a fourth, each
one of its kind: the two turns, back from 135 degrees, not asked where a turn lies within 15 degrees of straight
ahead or of 135; the first 10 so asked, the kinds taken in name order).

--thinned EVERY:FROM scores each frames folder (color/, depth/, pose.txt) also from every EVERY-th of its
frames from FROM on, a folder of links beside the databases: the same room walked at another pace.
"""
import argparse
import itertools
import json
import math
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

# Truth class -> the stored categories that name it. Only these classes are scored: the ones some
# packaged model (COCO's NanoDet, Open Images' SSD, PASCAL's DeepLab) can name.
FITS = {
    "bed": {"bed"},
    "sofa": {"sofa"},
    "couch": {"sofa"},
    "chair": {"chair"},
    "table": {"table", "desk"},
    "desk": {"desk", "table"},
    "refrigerator": {"fridge"},
    "fridge": {"fridge"},
    "toilet": {"toilet"},
    "sink": {"sink"},
    "tv": {"tv", "monitor"},
    "monitor": {"tv", "monitor"},
    "plant": {"plant"},
    "microwave": {"microwave"},
    "oven": {"oven"},
    "laptop": {"laptop"},
    "bottle": {"bottle"},
    "book": {"book"},
}
# VSI-Bench's relative questions: at most this many kinds offered a question; the closest kind's gap this much
# (metres) under the next one's, else the question is not asked; a direction this many degrees off every
# quadrant's edge, else not asked (both as VSI-Bench leaves out ambiguous questions).
RELATIVE_OPTIONS = 4
RELATIVE_MARGIN = 0.15
RELATIVE_BOUNDARY = 15
# Route plans asked of a capture at most (the first unambiguous ones, the kinds in name order).
ROUTES = 10
# The word a person uses for a truth class in a question.
WORD = {"refrigerator": "fridge", "couch": "sofa"}
# Label sets of the truth's sources: a stored thing whose name fits none of these is not counted.
LABEL_SETS = {
    "ScanNet": {"cabinet", "bed", "chair", "sofa", "table", "door", "window", "bookshelf", "picture", "counter",
                "desk", "curtain", "refrigerator", "showercurtrain", "toilet", "sink", "bathtub", "garbagebin"},
    "SUN RGB-D": {"bed", "table", "sofa", "chair", "toilet", "desk", "dresser", "night_stand", "bookshelf",
                  "bathtub", "dresser_mirror", "lamp", "ottoman"},
}


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def query(smql, db, statement):
    out = run([smql, str(db), "-json", statement]).stdout
    return json.loads(out)[-1] if out.strip() else {}


def rotation_of(obj):
    if "rotation" in obj:
        return np.array(obj["rotation"], dtype=float).reshape(3, 3)
    c, s = math.cos(obj.get("yaw", 0.0)), math.sin(obj.get("yaw", 0.0))
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=float)


def umeyama(src, dst):
    """Similarity (s, R, t) with dst ~ s R src + t (Umeyama 1991); s is nan when the source points coincide."""
    src, dst = np.asarray(src, float), np.asarray(dst, float)
    mu_s, mu_d = src.mean(0), dst.mean(0)
    a, b = src - mu_s, dst - mu_d
    u, d, vt = np.linalg.svd(b.T @ a / len(src))
    sign = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        sign[2, 2] = -1
    r = u @ sign @ vt
    var = (a ** 2).sum(1).mean()
    s = float(np.trace(np.diag(d) @ sign) / var) if var > 0 else float("nan")
    return s, r, mu_d - s * r @ mu_s


def true_cameras(capture):
    """Frame number -> camera centre from pose.txt (line i: the i-th frame by number)."""
    numbers = sorted(int(p.stem) for p in (capture / "color").iterdir() if p.stem.isdigit())
    lines = [l.split() for l in (capture / "pose.txt").read_text().splitlines()
             if l.strip() and not l.startswith("#")]
    return {n: np.array([float(v) for v in line[:3]]) for n, line in zip(numbers, lines)}


def to_memory(smql, db, capture):
    """The similarity from the truth's frame to the memory's: from the stored cameras against the
    true ones where three or more spread apart are stored (COLMAP's frame is its own), else the
    scene's stored alignment (poses given: the capture's frame is the truth's)."""
    truth = true_cameras(capture) if (capture / "pose.txt").exists() else {}
    rows = query(smql, db, "FIND frame RETURN text, x, y, z").get("rows", [])
    pairs = [(truth[int(pathlib.PurePath(r["text"]).stem)], np.array([r["x"], r["y"], r["z"]])) for r in rows
             if pathlib.PurePath(r["text"]).stem.isdigit() and int(pathlib.PurePath(r["text"]).stem) in truth]
    if len(pairs) >= 3:
        src, dst = np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])
        if np.linalg.norm(src - src.mean(0), axis=1).max() > 0.3:
            return umeyama(src, dst)
    with tempfile.TemporaryDirectory() as work:
        out = pathlib.Path(work) / "scene.json"
        run([smql, "export", "json", "--db", str(db), "-o", str(out)])
        m = np.array(json.loads(out.read_text())["scene"]["alignment"], dtype=float).reshape(4, 4)
    s = np.cbrt(np.linalg.det(m[:3, :3]))
    return s, m[:3, :3] / s, m[:3, 3]


def truth_in_memory(capture, similarity):
    s, r, t = similarity
    truth = json.loads((capture / "truth.json").read_text())
    things = []
    for obj in truth["objects"]:
        rot = r @ rotation_of(obj)
        size = np.array(obj["size"], dtype=float) * s
        # Which of the box's axes stands up in the memory's frame (z up there).
        up = int(np.argmax(np.abs(rot[2, :])))
        flat = sorted((size[k] for k in range(3) if k != up), reverse=True)
        corners = [np.array(obj["center"]) + rotation_of(obj) @ (np.array(c) * np.array(obj["size"]) / 2)
                   for c in itertools.product((-1, 1), repeat=3)]
        corners = np.array([s * r @ c + t for c in corners])
        things.append({"category": obj["category"], "center": s * r @ np.array(obj["center"]) + t,
                       "sides": (flat[0], flat[1], size[up]), "lo": corners.min(0), "hi": corners.max(0),
                       "rotation": rot, "size": size, "structural": obj.get("structural", False)})
    source = truth.get("source", "")
    labels = next((v for k, v in LABEL_SETS.items() if source.startswith(k) or k in source), None)
    if labels is None:
        labels = {t["category"] for t in things}
    labels = labels - set(truth.get("unlabelled", []))
    return things, labels


def stored_things(smql, db):
    result = query(smql, db, "FIND object RETURN id, category, box, detected_as, parent")
    if "rows" not in result:  # no thing was kept as detected_as: the column is unknown
        result = query(smql, db, "FIND object RETURN id, category, box, parent")
    rows = result.get("rows", [])
    out = []
    for r in rows:
        b = r["box"]
        x, y, h = b["size"]
        c, s = math.cos(b["yaw"]), math.sin(b["yaw"])
        hx, hy = abs(c) * x / 2 + abs(s) * y / 2, abs(s) * x / 2 + abs(c) * y / 2
        centre = np.array(b["center"])
        out.append({"id": r["id"], "category": r["category"], "center": centre,
                    "sides": (max(x, y), min(x, y), h), "detected_as": r.get("detected_as"),
                    "lo": centre - [hx, hy, h / 2], "hi": centre + [hx, hy, h / 2]})
    return out


def fits(truth, stored):
    if stored["category"] not in FITS.get(truth["category"], ()):
        return False
    if np.linalg.norm(truth["center"] - stored["center"]) > 0.5:
        return False
    return all(abs(a - b) <= 0.5 * b for a, b in zip(stored["sides"], truth["sides"]))


def inside(point, box):
    return bool(np.all(point >= box["lo"]) and np.all(point <= box["hi"]))


def score_objects(truth, labels, stored):
    scored = [t for t in truth if t["category"] in FITS and t["category"] in labels and not t["structural"]]
    counted_names = set().union(*(FITS[c] for c in labels if c in FITS)) if labels else set()
    counted = [s for s in stored if s["category"] in counted_names]
    candidates = sorted(((np.linalg.norm(t["center"] - s["center"]), ti, si) for ti, t in enumerate(scored)
                         for si, s in enumerate(counted) if fits(t, s)), key=lambda c: c[0])
    match_t, match_s = {}, {}
    for _, ti, si in candidates:
        if ti not in match_t and si not in match_s:
            match_t[ti], match_s[si] = si, ti
    duplicates = [si for si, s in enumerate(counted) if si not in match_s and any(
        s["category"] in FITS[t["category"]] and ti in match_t and
        (np.linalg.norm(t["center"] - s["center"]) <= 0.5 or inside(s["center"], t))
        for ti, t in enumerate(scored))]
    implausible = [s for s in stored if min(s["sides"]) < 0.03 or max(s["sides"]) > 4.0 or
                   (s["detected_as"] and s["category"] == "object")]
    matched = len(match_t)
    precision = matched / len(counted) if counted else (1.0 if not scored else 0.0)
    recall = matched / len(scored) if scored else 1.0
    f1 = 2 * precision * recall / (precision + recall) if precision + recall else 0.0
    return {
        "truth": len(scored), "stored": len(counted), "matched": matched, "missed": len(scored) - matched,
        "duplicated": len(duplicates), "implausible": len(implausible), "all_stored": len(stored),
        "precision": round(precision, 3), "recall": round(recall, 3), "f1": round(f1, 3),
        "missed_things": [f"{t['category']} at ({t['center'][0]:.2f}, {t['center'][1]:.2f}) sides "
                          f"{'x'.join(f'{v:.2f}' for v in t['sides'])}" for ti, t in enumerate(scored)
                          if ti not in match_t],
        "extra_things": [f"{s['category']}#{s['id']} at ({s['center'][0]:.2f}, {s['center'][1]:.2f}) sides "
                         f"{'x'.join(f'{v:.2f}' for v in s['sides'])}" for si, s in enumerate(counted)
                         if si not in match_s],
        "depth_ratio": {f"{t['category']}#{ti}": round(min(1.0, max(
            (min(s['sides'][:2]) / min(t['sides'][:2]) for s in counted
             if s['category'] in FITS[t['category']] and inside(s['center'], t)), default=0.0)), 2)
            for ti, t in enumerate(scored) if t["category"] in ("bed", "sofa", "table", "couch")},
    }


def surface_points(box, n=12):
    """Points on the faces of an oriented box, n x n on each."""
    grid = np.linspace(-0.5, 0.5, n)
    faces = []
    for axis in range(3):
        for side in (-0.5, 0.5):
            u, v = np.meshgrid(grid, grid)
            p = np.zeros((n * n, 3))
            others = [k for k in range(3) if k != axis]
            p[:, axis] = side
            p[:, others[0]], p[:, others[1]] = u.ravel(), v.ravel()
            faces.append(p)
    local = np.concatenate(faces) * box["size"]
    return local @ box["rotation"].T + box["center"]


def gap(a, b):
    """The distance between two oriented boxes' closest points (0 when they overlap), as smql measures it."""
    pa, pb = surface_points(a), surface_points(b)
    if inside_oriented(pa, b).any() or inside_oriented(pb, a).any():
        return 0.0
    d = np.sqrt(((pa[:, None, :] - pb[None, :, :]) ** 2).sum(-1))
    return float(d.min())


def inside_oriented(points, box):
    local = (points - box["center"]) @ box["rotation"]
    return np.all(np.abs(local) <= box["size"] / 2 + 1e-9, axis=1)


def ask(smql, db, question):
    escaped = question.replace("'", "''")  # SMQL's string literal, as SQL's
    result = query(smql, db, f"ASK '{escaped}'")
    return result.get("rows", []), result.get("message", "")


def numbers_in(message):
    """The distinct lengths the answer's last line names, in metres."""
    return sorted({float(v) for v in re.findall(r"(\d+(?:\.\d+)?) m\b", message.split("\n")[-1])})


def scored_kinds(truth, labels):
    """Truth class -> its true things, for the classes the questions ask about: a packaged model can name them
    (FITS), the truth labels them, and they are no part of the room's structure."""
    kinds = {t["category"] for t in truth if t["category"] in FITS and t["category"] in labels and not t["structural"]}
    return {k: [t for t in truth if t["category"] == k] for k in sorted(kinds)}


def questions(smql, db, truth, labels):
    asked = []
    by_kind = scored_kinds(truth, labels)
    kinds = sorted(by_kind)
    absent = sorted(c for c in labels if c in FITS and c not in kinds and c not in ("couch", "fridge"))

    def record(kind, question, right, answer):
        asked.append({"kind": kind, "question": question, "right": bool(right), "answer": answer.split("\n")[-1]})

    for k in kinds:
        word = WORD.get(k, k)
        rows, message = ask(smql, db, f"how many {word}s are there?")
        got = rows[0].get("count") if rows else None
        record("count", f"how many {word}s are there?", got == len(by_kind[k]), message)
        rows, message = ask(smql, db, f"is there a {word}?")
        record("exists", f"is there a {word}?", len(rows) > 0, message)
        if len(by_kind[k]) == 1:
            longest = max(by_kind[k][0]["sides"])
            rows, message = ask(smql, db, f"how long is the {word}?")
            values = numbers_in(message)
            record("length", f"how long is the {word}? (truth {longest:.2f} m)",
                   len(values) == 1 and abs(values[0] - longest) <= 0.25 * longest, message)
    for k in absent:
        word = WORD.get(k, k)
        rows, message = ask(smql, db, f"is there a {word}?")
        record("exists", f"is there a {word}? (none)", len(rows) == 0, message)
    singles = [k for k in kinds if len(by_kind[k]) == 1]
    for a, b in itertools.combinations(singles, 2):
        truth_gap = gap(by_kind[a][0], by_kind[b][0])
        question = f"how far is the {WORD.get(a, a)} from the {WORD.get(b, b)}?"
        rows, message = ask(smql, db, question)
        values = numbers_in(message)
        record("distance", f"{question} (truth {truth_gap:.2f} m)",
               len(values) == 1 and abs(values[0] - truth_gap) <= max(0.15, 0.25 * truth_gap), message)
    for k in singles:
        carrier = by_kind[k][0]
        on = sorted({t["category"] for t in truth if t is not carrier and t["category"] in FITS and
                     abs(t["lo"][2] - carrier["hi"][2]) < 0.1 and inside(np.array([*t["center"][:2],
                                                                                  carrier["hi"][2] - 0.01]), carrier)})
        if not on:
            continue
        rows, message = ask(smql, db, f"what is on the {WORD.get(k, k)}?")
        named = {r.get("category") for r in rows}
        wanted = {next(iter(FITS[c])) for c in on}
        record("on", f"what is on the {WORD.get(k, k)}? (truth: {', '.join(on)})",
               wanted <= named, message)
    return asked


def relative_questions(smql, db, truth, labels):
    """VSI-Bench's relative distance, relative direction and route plan questions, in its words, about the scored
    kinds (module docstring), their truth from the true boxes. A kind the answer names fits an option by FITS (a
    stored desk answers "table"; of two options it fits, the first)."""
    asked = []
    by_kind = scored_kinds(truth, labels)
    kinds = sorted(by_kind)
    singles = [k for k in kinds if len(by_kind[k]) == 1]
    word = lambda k: WORD.get(k, k)

    def record(kind, question, truth_answer, answer, message):
        asked.append({"kind": kind, "question": question, "truth": truth_answer, "answer": answer,
                      "right": answer == truth_answer, "message": message.split("\n")[-1]})

    for target in singles:
        others = [k for k in kinds if k != target]
        for start in range(0, len(others), RELATIVE_OPTIONS):
            options = others[start:start + RELATIVE_OPTIONS]
            if len(options) < 2:
                continue
            nearest = sorted((min(gap(by_kind[target][0], t) for t in by_kind[k]), k) for k in options)
            if nearest[1][0] - nearest[0][0] < RELATIVE_MARGIN:
                continue
            question = (f"Measuring from the closest point of each object, which of these objects "
                        f"({', '.join(word(k) for k in options)}) is the closest to the {word(target)}?")
            rows, message = ask(smql, db, question)
            named = rows[0].get("category") if len(rows) == 1 else None
            answer = next((k for k in options if named in FITS[k]), named)
            gaps = ", ".join(f"{word(k)} {g:.2f} m" for g, k in nearest)
            record("relative distance", f"{question} (truth {gaps})", nearest[0][1], answer, message)
    for standing, facing, other in itertools.combinations(singles, 3):
        at = by_kind[standing][0]["center"][:2]
        ahead = by_kind[facing][0]["center"][:2] - at
        there = by_kind[other][0]["center"][:2] - at
        angle = math.degrees(math.atan2(ahead[0] * there[1] - ahead[1] * there[0], ahead @ there))
        # Counter-clockwise (z up) is to the left; ambiguous within RELATIVE_BOUNDARY degrees of a quadrant's edge.
        if min(abs(angle - edge) for edge in (-180, -90, 0, 90, 180)) < RELATIVE_BOUNDARY:
            continue
        truth_answer = ("front" if abs(angle) < 90 else "back") + "-" + ("left" if angle > 0 else "right")
        question = (f"If I am standing by the {word(standing)} and facing the {word(facing)}, is the "
                    f"{word(other)} to my front-left, front-right, back-left, or back-right?")
        rows, message = ask(smql, db, question)
        said = re.search(r"to your (front-left|front-right|back-left|back-right)\b", message)
        record("relative direction", question, truth_answer, said.group(1) if said else None, message)
    routes = 0
    for start, facing, via, goal in itertools.permutations(singles, 4):
        if routes == ROUTES:
            break
        at = {k: by_kind[k][0]["center"][:2] for k in (start, facing, via, goal)}
        turns, heading, pos = [], at[facing] - at[start], at[facing]
        for target in (via, goal):
            ahead = at[target] - pos
            angle = math.degrees(math.atan2(heading[0] * ahead[1] - heading[1] * ahead[0], heading @ ahead))
            # Ahead, or at the edge of back (135 degrees), within RELATIVE_BOUNDARY: ambiguous.
            if min(abs(abs(angle) - edge) for edge in (0, 135)) < RELATIVE_BOUNDARY:
                break
            turns.append("Turn Back" if abs(angle) >= 135 else ("Turn Left" if angle > 0 else "Turn Right"))
            heading, pos = ahead, at[target]
        if len(turns) < 2:
            continue
        routes += 1
        question = (f"You are a robot beginning at the {word(start)} facing the {word(facing)}. You want to navigate "
                    f"to the {word(goal)}. You will perform the following actions (Note: for each [please fill in], "
                    f"choose either 'turn back,' 'turn left,' or 'turn right.'): 1. Go forward until the "
                    f"{word(facing)} 2. [please fill in] 3. Go forward until the {word(via)} 4. [please fill in] "
                    f"5. Go forward until the {word(goal)}. You have reached the final destination.")
        rows, message = ask(smql, db, question)
        said = re.match(r"(Turn (?:Left|Right|Back)), (Turn (?:Left|Right|Back))", message.split("\n")[-1])
        record("route plan", f"from the {word(start)} facing the {word(facing)}, by the {word(via)} to the "
               f"{word(goal)}", ", ".join(turns), ", ".join(said.groups()) if said else None, message)
    return asked


def first_sights(capture):
    """Truth category -> the first frame number in which a thing of it is seen (module docstring), for a
    capture of several frames with depth and poses; {} otherwise."""
    import cv2  # python3-opencv, which the set-up installs
    frames = sorted(int(p.stem) for p in (capture / "color").iterdir() if p.stem.isdigit())
    if len(frames) < 2 or not (capture / "depth").is_dir() or not (capture / "pose.txt").exists():
        return {}
    camera = json.loads((capture / "camera.json").read_text())
    lines = [l.split() for l in (capture / "pose.txt").read_text().splitlines()
             if l.strip() and not l.startswith("#")]
    truth = json.loads((capture / "truth.json").read_text())["objects"]
    boxes = [{"center": np.array(o["center"], dtype=float), "size": np.array(o["size"], dtype=float),
              "rotation": rotation_of(o)} for o in truth]
    points = [surface_points(b) for b in boxes]
    first = {}
    for number, line in zip(frames, lines):
        depth_file = next((capture / "depth").glob(f"{number}.*"), None)
        if depth_file is None:
            continue
        depth = cv2.imread(str(depth_file), cv2.IMREAD_UNCHANGED).astype(float) / camera.get("depth_scale", 1000)
        if depth.shape[:2] != (camera["height"], camera["width"]):  # registered at another resolution, as smql reads it
            depth = cv2.resize(depth, (camera["width"], camera["height"]), interpolation=cv2.INTER_NEAREST)
        t = np.array([float(v) for v in line[:3]])
        qx, qy, qz, qw = (float(v) for v in line[3:7])
        r = np.array([[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
                      [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
                      [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]])
        for obj, pts in zip(truth, points):
            if obj["category"] in first:
                continue
            local = (pts - t) @ r  # camera frame: x right, y down, z ahead
            ahead = local[:, 2] > 0.1
            u = np.round(camera["fx"] * local[ahead, 0] / local[ahead, 2] + camera["cx"]).astype(int)
            v = np.round(camera["fy"] * local[ahead, 1] / local[ahead, 2] + camera["cy"]).astype(int)
            inside = (u >= 0) & (u < depth.shape[1]) & (v >= 0) & (v < depth.shape[0])
            d = depth[v[inside], u[inside]]
            seen = (d > 0) & (np.abs(d - local[ahead][inside, 2]) <= 0.1)
            if seen.sum() >= 15:
                first[obj["category"]] = number
    return first


def appearance_order(smql, db, capture, truth, labels):
    sights = first_sights(capture)
    kinds = sorted(c for c in {t["category"] for t in truth} if c in sights and c in FITS and c in labels)
    asked = []
    for size in (4, 3, 2):
        for group in itertools.combinations(kinds, size):
            frames = sorted(sights[k] for k in group)
            if any(b - a < 10 for a, b in zip(frames, frames[1:])):
                continue
            words = [WORD.get(k, k) for k in group]
            question = ("What will be the first-time appearance order of the following categories in the video: "
                        f"{', '.join(words)}?")
            _, message = ask(smql, db, question)
            answer = message.split("\n")[-1].split(" (first seen")[0].rstrip(".")
            truth_order = [WORD.get(k, k) for k in sorted(group, key=lambda k: sights[k])]
            asked.append({"question": question, "truth": ", ".join(truth_order), "answer": answer,
                          "right": [w.strip() for w in answer.split(",")] == truth_order})
        if asked:
            break
    return asked


def evaluate(smql, capture, db, options, reuse):
    row = {"capture": capture.name}
    if not (reuse and db.exists()):
        if db.exists():
            shutil.rmtree(db)
        start = time.monotonic()
        proc = run([smql, "ingest", str(capture), "--db", str(db), *options])
        row["seconds"] = round(time.monotonic() - start, 1)
        row["exit"] = proc.returncode
        if proc.returncode != 0:
            row["error"] = (proc.stdout + proc.stderr).strip().splitlines()[-3:]
            return row
    similarity = to_memory(smql, db, capture)
    row["scale_to_truth"] = round(float(similarity[0]), 3)
    truth, labels = truth_in_memory(capture, similarity)
    stored = stored_things(smql, db)
    row.update(score_objects(truth, labels, stored))
    row["questions"] = questions(smql, db, truth, labels)
    row["questions_right"] = sum(q["right"] for q in row["questions"])
    row["order"] = appearance_order(smql, db, capture, truth, labels)
    row["relative"] = relative_questions(smql, db, truth, labels)
    return row


def thinned(capture, every, offset, work):
    """The capture from every `every`-th frame from `offset` on, as a folder of links beside the work's databases
    (a frames folder of color/, depth/ and pose.txt, frame i = line i in the frames' numeric order), or None."""
    color, depth, poses = capture / "color", capture / "depth", capture / "pose.txt"
    if not (color.is_dir() and depth.is_dir() and poses.exists()):
        return None
    frames = sorted(color.iterdir(), key=lambda f: int(f.stem) if f.stem.isdigit() else -1)
    lines = poses.read_text().splitlines()
    header, rows = [l for l in lines if l.startswith("#")], [l for l in lines if l.strip() and not l.startswith("#")]
    if len(rows) != len(frames):
        return None
    out = work / f"{capture.name}-every{every}from{offset}"
    shutil.rmtree(out, ignore_errors=True)
    (out / "color").mkdir(parents=True)
    (out / "depth").mkdir()
    kept = list(range(offset, len(frames), every))
    for j, i in enumerate(kept):
        (out / "color" / f"{j}{frames[i].suffix}").symlink_to(frames[i].resolve())
        (out / "depth" / f"{j}.png").symlink_to((depth / f"{frames[i].stem}.png").resolve())
    (out / "pose.txt").write_text("\n".join(header + [rows[i] for i in kept]) + "\n")
    for name in ("camera.json", "truth.json"):
        (out / name).symlink_to((capture / name).resolve())
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("smql")
    parser.add_argument("captures", nargs="+", type=pathlib.Path)
    parser.add_argument("--options", default="", help="ingest options, one string")
    parser.add_argument("--keep", type=pathlib.Path, help="keep the databases in this folder")
    parser.add_argument("--reuse", action="store_true", help="with --keep: score databases already there")
    parser.add_argument("--json")
    parser.add_argument("--verbose", action="store_true")
    parser.add_argument("--thinned", nargs="*", default=[], metavar="EVERY:FROM",
                        help="score each frames folder also from every EVERY-th frame from FROM on (2:0 2:1 3:0)")
    args = parser.parse_args()
    work = args.keep or pathlib.Path(tempfile.mkdtemp(prefix="smql-eval-objects-"))
    work.mkdir(parents=True, exist_ok=True)
    captures = list(args.captures)
    for spec in args.thinned:
        every, offset = (int(v) for v in spec.split(":"))
        captures += [t for t in (thinned(c, every, offset, work / "thinned") for c in args.captures) if t]
    rows = []
    for capture in captures:
        if not (capture / "truth.json").exists():
            continue
        row = evaluate(args.smql, capture, work / capture.name, shlex.split(args.options), args.reuse)
        rows.append(row)
        brief = {k: v for k, v in row.items()
                 if args.verbose or k not in ("questions", "missed_things", "extra_things", "order", "relative")}
        print(json.dumps(brief), flush=True)
    scored = [r for r in rows if "f1" in r]
    matched = sum(r["matched"] for r in scored)
    stored = sum(r["stored"] for r in scored)
    truth = sum(r["truth"] for r in scored)
    precision, recall = (matched / stored if stored else 0), (matched / truth if truth else 0)
    asked = [q for r in scored for q in r["questions"]]
    ordered = [q for r in scored for q in r.get("order", [])]
    relative = [q for r in scored for q in r.get("relative", [])]
    kinds = sorted({q["kind"] for q in asked})
    total = {
        "captures": len(rows), "scored": len(scored), "truth": truth, "stored": stored, "matched": matched,
        "duplicated": sum(r["duplicated"] for r in scored), "implausible": sum(r["implausible"] for r in scored),
        "precision": round(precision, 3), "recall": round(recall, 3),
        "f1": round(2 * precision * recall / (precision + recall), 3) if precision + recall else 0.0,
        "questions": f"{sum(q['right'] for q in asked)}/{len(asked)}",
        "by_kind": {k: f"{sum(q['right'] for q in asked if q['kind'] == k)}/"
                       f"{sum(1 for q in asked if q['kind'] == k)}" for k in kinds},
        "appearance_order": f"{sum(q['right'] for q in ordered)}/{len(ordered)}",
        **{k.replace(" ", "_"): f"{sum(q['right'] for q in relative if q['kind'] == k)}/"
                                f"{sum(1 for q in relative if q['kind'] == k)}"
           for k in ("relative distance", "relative direction", "route plan")},
    }
    print(json.dumps({"total": total}))
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps({"rows": rows, "total": total}, indent=1, default=str) + "\n")
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
