#!/usr/bin/env python3
"""ASK on public question sets about real rooms (docs/ask.md, "How well it answers").

VSI-Bench's questions are asked word for word about the rooms of ../shared/data/real-layouts (its own
validation rooms, imported with `smql import vsibench --all`) and scored against VSI-Bench's ground
truth: exact choice for multiple-choice questions, mean relative accuracy (MRA, VSI-Bench's measure)
for numbers. ScanQA's and SQA3D's questions, human-written about ScanNet rooms, are asked about the
same rooms where they are among them, and counted as translated or not (their free-text answers are
checked by hand on a sample, printed with --sample). SQA3D's question is asked after its situation, as
one text ("I am sitting on the bed facing the window. What is to my left?"); --no-situation asks the
question alone.

    scripts/eval_ask.py --smql build/shell/smql --fixtures /path/to/question/files [--sample 40] [--only sqa3d]

The fixture folder holds vsibench_test.jsonl (VSI-Bench's test split as JSON lines),
ScanQA_v1.0_val.json and sqa3d_v1_balanced_questions_test_scannetv2.json; each set that is absent is
skipped with a note. Nothing here downloads.
"""
import argparse
import collections
import json
import os
import random
import re
import subprocess
import sys
import tempfile
import time

LAYOUTS = os.path.join(os.path.dirname(__file__), "..", "..", "shared", "data", "real-layouts")


def run_ask(smql, db, scene, question):
    text = question.replace("'", "''")
    started = time.perf_counter()
    proc = subprocess.run([smql, db, "-json", "-c", f"USE SCENE '{scene}'; ASK '{text}'"],
                          capture_output=True, text=True)
    elapsed = time.perf_counter() - started
    out = proc.stdout.strip()
    try:
        results = json.loads(out) if out.startswith("[") else []
    except json.JSONDecodeError:
        results = []
    error = None
    if proc.returncode != 0:
        for line in (proc.stdout + proc.stderr).splitlines():
            if line.startswith('{"error"'):
                error = json.loads(line)["error"]["message"]
        error = error or (proc.stderr.strip() or "failed")
    answer = results[1] if len(results) > 1 else None
    return answer, error, elapsed


def mra(pred, truth):
    """VSI-Bench's mean relative accuracy over the thresholds 0.50, 0.55, ..., 0.95."""
    if pred is None or truth == 0:
        return 0.0
    rel = abs(pred - truth) / abs(truth)
    return sum(rel < 1 - (0.5 + 0.05 * k) for k in range(10)) / 10


def smql_of(answer):
    return answer["message"].splitlines()[0] if answer and answer.get("message") else ""


def predicted(qtype, answer, options):
    """The answer's value in VSI-Bench's terms: a number, or an option's letter."""
    if not answer:
        return None
    rows, message = answer["rows"], answer["message"]
    if qtype == "object_counting":
        return float(rows[0]["count"]) if rows else None
    if qtype == "object_abs_distance":
        values = [r["distance"] for r in rows if isinstance(r.get("distance"), (int, float))]
        return min(values) if values else None
    if qtype == "object_size_estimation":
        sizes = [max(r["width"], r["depth"], r["height"]) * 100 for r in rows
                 if all(isinstance(r.get(k), (int, float)) for k in ("width", "depth", "height"))]
        return sizes[0] if len(sizes) == 1 else (sum(sizes) / len(sizes) if sizes else None)
    if qtype.startswith("object_rel_direction"):
        m = re.search(r"is to your ([a-z-]+)", message)
        if not m:
            return None
        word = m.group(1)
        for option in options or []:
            letter, _, text = option.partition(". ")
            if text.strip().lower() == word:
                return letter
        return None
    if qtype == "room_size_estimation":
        m = re.search(r"is about ([0-9.]+) m", message)
        return float(m.group(1)) if m else None
    if qtype == "obj_appearance_order":
        order = message.splitlines()[-1].split(" (")[0].strip().rstrip(".").lower()
        for option in options or []:
            letter, _, text = option.partition(". ")
            if ", ".join(t.strip() for t in text.lower().split(",")) == order:
                return letter
        return None
    if qtype == "route_planning":
        turns = message.splitlines()[-1].split(" (")[0].strip().rstrip(".").lower()
        for option in options or []:
            letter, _, text = option.partition(". ")
            if text.strip().lower() == turns:
                return letter
        return None
    if qtype == "object_rel_distance":
        if not rows:
            return None
        category = rows[0]["category"].replace("-", " ")
        for option in options or []:
            letter, _, text = option.partition(". ")
            if text.strip().lower() == category:
                return letter
        return None
    return None


ROOM_SIZE_TEMPLATE = ("What is the size of this room (in square meters)? If multiple rooms are shown, estimate the size "
                      "of the combined space.")
ROUTE_TEMPLATE = ("You are a robot beginning at the {start} facing the {facing}. You want to navigate to the {goal}. "
                  "You will perform the following actions (Note: for each [please fill in], choose either 'turn "
                  "back,' 'turn left,' or 'turn right.'): {actions} You have reached the final destination.")


def turn(heading, frm, to):
    """VSI-Bench's turn toward `to` from `frm` while facing along `heading`: back from 135 degrees."""
    import math
    vx, vy = to[0] - frm[0], to[1] - frm[1]
    angle = math.degrees(math.atan2(heading[0] * vy - heading[1] * vx, heading[0] * vx + heading[1] * vy))
    return "Turn Back" if abs(angle) >= 135 else ("Turn Left" if angle > 0 else "Turn Right")


def layout_questions():
    """VSI-Bench's room size and route plan questions, in its templates, over the 238 layouts.

    Room size asks for the layout's own figure (VSI-Bench's ground truth). A route plan walks between
    things a room holds one of (centroids from the file itself, not from smql): from the start, facing
    a thing, forward to each thing in turn; its ground truth is each turn toward the next thing, and
    its options are the truth and three other sequences, in VSI-Bench's form ("Turn Left, Turn Right").
    """
    import itertools
    out = []
    for file in ("scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"):
        for name, room in json.load(open(os.path.join(LAYOUTS, file))).items():
            out.append({"scene_name": name, "question_type": "room_size_estimation", "question": ROOM_SIZE_TEMPLATE,
                        "ground_truth": room["room_size"]})
            single = sorted(c for c, boxes in room["object_bbox"].items() if len(boxes) == 1)
            if len(single) < 4:
                continue
            rng = random.Random(name)
            start, facing, via, goal = rng.sample(single, 4)
            at = {c: room["object_bbox"][c][0]["centroid"] for c in (start, facing, via, goal)}
            first_turn = rng.random() < 0.5  # "1. [please fill in]" before the first forward, or after it
            if first_turn:
                path = [start, via, goal]
                steps = ["[please fill in]", f"Go forward until the {via}", "[please fill in]",
                         f"Go forward until the {goal}."]
                heading = (at[facing][0] - at[start][0], at[facing][1] - at[start][1])
            else:
                path = [facing, via, goal]
                steps = [f"Go forward until the {facing}", "[please fill in]", f"Go forward until the {via}",
                         "[please fill in]", f"Go forward until the {goal}."]
                heading = (at[facing][0] - at[start][0], at[facing][1] - at[start][1])
            truth, pos = [], at[start]
            if not first_turn:
                pos = at[facing]
            for k, target in enumerate(path[1:] if not first_turn else path[1:]):
                truth.append(turn(heading, pos, at[target]))
                heading = (at[target][0] - pos[0], at[target][1] - pos[1])
                pos = at[target]
            truth = ", ".join(truth)
            others = [", ".join(c) for c in itertools.product(["Turn Left", "Turn Right", "Turn Back"], repeat=2)]
            options = [truth] + rng.sample([o for o in others if o != truth], 3)
            rng.shuffle(options)
            letters = "ABCD"
            actions = " ".join(f"{i + 1}. {s}" for i, s in enumerate(steps))
            out.append({"scene_name": name, "question_type": "route_planning",
                        "question": ROUTE_TEMPLATE.format(start=start, facing=facing, goal=goal, actions=actions),
                        "options": [f"{letters[i]}. {o}" for i, o in enumerate(options)],
                        "ground_truth": letters[options.index(truth)]})
    return out


def vsibench(args, db, scenes):
    path = os.path.join(args.fixtures or "", "vsibench_test.jsonl")
    if args.layout_tasks:
        questions = layout_questions()
        print("VSI-Bench's room size and route plan tasks in its templates, generated from the layouts")
    elif not os.path.exists(path):
        print(f"note: {path} absent; VSI-Bench skipped")
        return
    else:
        questions = [json.loads(l) for l in open(path)]
    questions = [q for q in questions if q["scene_name"] in scenes]
    if args.limit:
        random.Random(7).shuffle(questions)
        questions = questions[: args.limit]
    by_type = collections.defaultdict(lambda: {"n": 0, "translated": 0, "score": 0.0})
    latencies, samples, failures = [], [], collections.Counter()
    for q in questions:
        answer, error, elapsed = run_ask(args.smql, db, q["scene_name"], q["question"])
        latencies.append(elapsed)
        row = by_type[q["question_type"]]
        row["n"] += 1
        if error:
            failures[(q["question_type"], error[:90])] += 1
            continue
        row["translated"] += 1
        pred = predicted(q["question_type"], answer, q.get("options"))
        if q.get("options"):
            row["score"] += 1.0 if pred == q["ground_truth"] else 0.0
        else:
            row["score"] += mra(pred, float(q["ground_truth"]))
        samples.append((q, answer, pred))
    print(f"\nVSI-Bench, {len(questions)} questions on {len(scenes)} real rooms")
    print("| question type | questions | translated | score (choice: accuracy; number: MRA) |")
    print("|---|---:|---:|---:|")
    total = {"n": 0, "translated": 0, "score": 0.0}
    for qtype in sorted(by_type):
        r = by_type[qtype]
        for k in total:
            total[k] += r[k]
        print(f"| {qtype} | {r['n']} | {r['translated'] / r['n']:.2f} | {r['score'] / r['n']:.2f} |")
    print(f"| all | {total['n']} | {total['translated'] / max(total['n'], 1):.2f} | "
          f"{total['score'] / max(total['n'], 1):.2f} |")
    latencies.sort()
    if latencies:
        print(f"process per question (start, open, translate, answer): median {latencies[len(latencies) // 2] * 1000:.1f} ms")
    print("most frequent refusals:")
    for (qtype, error), n in failures.most_common(12):
        print(f"  {n:5d}  {qtype}: {error}")
    if args.sample:
        print("\nsample of answers:")
        for q, answer, pred in random.Random(11).sample(samples, min(args.sample, len(samples))):
            print(f"- [{q['scene_name']}] {q['question'].splitlines()[0]}\n    truth {q['ground_truth']} "
                  f"{q.get('options') or ''}; got {pred}: {answer['message'].splitlines()[-1][:200]}")


def kind_of(answer):
    """The question's kind as the answer's first line shows it: its statement and VIEW FROM (a pose)."""
    smql = smql_of(answer)
    head = smql.split(": ", 1)[-1].split(" ")[0] if smql else "?"
    return head + (" VIEW" if " VIEW FROM " in smql else "")


def free_text(args, db, scenes, name, file, read):
    path = os.path.join(args.fixtures, file)
    if not os.path.exists(path):
        print(f"note: {path} absent; {name} skipped")
        return
    questions = [(scene, text) for scene, text in read(json.load(open(path))) if scene in scenes]
    if args.limit:
        random.Random(7).shuffle(questions)
        questions = questions[: args.limit]
    translated, samples, failures, kinds = 0, [], collections.Counter(), collections.Counter()
    for scene, text in questions:
        answer, error, _ = run_ask(args.smql, db, scene, text)
        # A reading that is not run (an unknown word, the room taken as a thing) is no translation.
        if not error and smql_of(answer).startswith("SMQL (not run)"):
            error = answer["message"].splitlines()[-1]
        if error:
            failures[error[:80]] += 1
            if args.failures:
                print(f"  x [{scene}] {text}\n      {error[:160]}")
        else:
            translated += 1
            kinds[kind_of(answer)] += 1
            samples.append((scene, text, answer))
    print(f"\n{name}: {len(questions)} questions on rooms of real-layouts; translated {translated} "
          f"({translated / max(len(questions), 1):.2f})")
    print("  translated, by statement: " + ", ".join(f"{k} {n}" for k, n in kinds.most_common()))
    for error, n in failures.most_common(8):
        print(f"  {n:5d}  {error}")
    if args.sample:
        rng = random.Random(args.seed)
        for scene, text, answer in rng.sample(samples, min(args.sample, len(samples))):
            print(f"- [{scene}] {text}\n    {smql_of(answer)} -> {answer['message'].splitlines()[-1][:160]}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--smql", default="build/shell/smql")
    parser.add_argument("--fixtures", help="folder with the public question files")
    parser.add_argument("--layout-tasks", action="store_true",
                        help="ask VSI-Bench's room size and route plan questions in its templates, made from the "
                             "layouts (layout_questions), instead of the question files")
    parser.add_argument("--db", help="a database of the real layouts (made in a temporary folder if absent)")
    parser.add_argument("--limit", type=int, default=0, help="ask at most this many questions of each set")
    parser.add_argument("--sample", type=int, default=0, help="print this many answers of each set to check by hand")
    parser.add_argument("--seed", type=int, default=11, help="the seed of the sample")
    parser.add_argument("--only", choices=["vsibench", "scanqa", "sqa3d"], help="ask one set only")
    parser.add_argument("--no-situation", action="store_true", help="ask SQA3D's questions without their situation")
    parser.add_argument("--failures", action="store_true", help="print each question that does not translate")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        db = args.db or os.path.join(tmp, "layouts")
        if not os.path.exists(db):
            for file in ("scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"):
                subprocess.run([args.smql, "import", "vsibench", os.path.join(LAYOUTS, file), "--all", "--db", db],
                               check=True, capture_output=True)
        listing = subprocess.run([args.smql, db, "-json", "-c", "SHOW SCENES"], check=True, capture_output=True,
                                 text=True).stdout
        scenes = {r["name"] for r in json.loads(listing)[0]["rows"]}
        if args.only in (None, "vsibench"):
            vsibench(args, db, scenes)
        if args.layout_tasks or not args.fixtures:
            return
        if args.only in (None, "scanqa"):
            free_text(args, db, scenes, "ScanQA (val)", "ScanQA_v1.0_val.json",
                      lambda data: [(q["scene_id"], q["question"]) for q in data])
        if args.only in (None, "sqa3d"):
            situated = not args.no_situation
            free_text(args, db, scenes, "SQA3D (test)" + (", with the situation" if situated else ""),
                      "sqa3d_v1_balanced_questions_test_scannetv2.json",
                      lambda data: [(q["scene_id"], (q["situation"].strip() + " " if situated else "") + q["question"])
                                    for q in data["questions"]])


if __name__ == "__main__":
    sys.exit(main())
