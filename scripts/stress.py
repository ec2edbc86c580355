#!/usr/bin/env python3
"""`make stress`: the fault tests that take minutes, run as a user would run the smql command.

  scripts/stress.py SMQL kill    [--runs 200]               SIGKILL during imports and ingests
  scripts/stress.py SMQL readers [--seconds 300 --readers 8]  one writer beside readers

kill: a database holds two base scenes (the Replica room of ../shared/data and an ingested
synthetic capture). Each run starts an import (a Replica room under a new name) or an ingest (a
small synthetic capture under a new name) and kills it with SIGKILL after a random delay within
the shortest of three clean runs. After every run: `smql check` passes, both base scenes export
byte-identical to before, and the killed scene is either absent or complete (as many nodes as a
clean run of the same input gives).

readers: one process imports new scenes in a loop while N reader processes query in a loop. Every
answer is checked: the base scene's counts never change, the list of scenes only grows, and every
scene a reader sees is complete. Any error or wrong answer is counted and fails the run.

Prints a table of the figures (docs/testing.md, "Stress") and exits 1 on any failure.
"""
import argparse
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
REPLICA = ROOT.parent / "shared" / "data" / "replica-room0" / "info_semantic.json"


class Smql:
    def __init__(self, binary, db):
        self.binary = str(binary)
        self.db = str(db)

    def run(self, *args, check=True):
        done = subprocess.run([self.binary, *args], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise RuntimeError(f"smql {' '.join(args)}: exit {done.returncode}: {done.stderr.strip()}")
        return done

    def query(self, statements):
        out = self.run(self.db, "--json", "-c", statements).stdout
        return json.loads(out)

    def scenes(self):
        return [row["name"] for row in self.query("SHOW SCENES")[0]["rows"]]

    def node_count(self, scene):
        answer = self.query(f"USE SCENE '{scene}'; COUNT object; COUNT anchor")
        return tuple(part["rows"][0]["count"] for part in answer[1:])

    def export(self, scene):
        return self.run("export", "json", "--db", self.db, "--scene", scene).stdout

    def check(self):
        return self.run("check", self.db, check=False)


def import_command(smql, scene):
    return [smql.binary, "import", "replica", str(REPLICA), "--db", smql.db, "--scene", scene]


def ingest_command(smql, capture, scene):
    return [smql.binary, "ingest", str(capture), "--db", smql.db, "--scene", scene, "--quiet"]


def timed(command):
    start = time.monotonic()
    subprocess.run(command, check=True, capture_output=True)
    return time.monotonic() - start


def prepare(smql, work):
    """Writes the base scenes and returns the capture and the shortest of three clean runs of each
    kind: a kill lands within that time, so it meets the run at work, not after its end."""
    capture = work / "capture"
    smql.run("synth", "--out", str(capture), "--seed", "7", "--frames", "12", "--objects", "8")
    import_seconds = timed(import_command(smql, "base-replica"))
    ingest_seconds = timed(ingest_command(smql, capture, "base-capture"))
    for n in range(2):
        import_seconds = min(import_seconds, timed(import_command(smql, f"clean-import-{n}")))
        ingest_seconds = min(ingest_seconds, timed(ingest_command(smql, capture, f"clean-ingest-{n}")))
    return capture, import_seconds, ingest_seconds


def kill_test(smql, work, runs, seed):
    capture, import_seconds, ingest_seconds = prepare(smql, work)
    base = {scene: smql.export(scene) for scene in ("base-replica", "base-capture")}
    expected = {"import": smql.node_count("base-replica"), "ingest": smql.node_count("base-capture")}
    rng = random.Random(seed)
    tally = {"runs": 0, "killed": 0, "finished": 0, "absent": 0, "complete": 0, "failures": 0}
    failures = []
    for run in range(runs):
        kind = rng.choice(("import", "ingest"))
        scene = f"{kind}-{run}"
        command = import_command(smql, scene) if kind == "import" else ingest_command(smql, capture, scene)
        budget = import_seconds if kind == "import" else ingest_seconds
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(rng.uniform(0, budget))
        if process.poll() is None:
            process.send_signal(signal.SIGKILL)
            tally["killed"] += 1
        else:
            tally["finished"] += 1
        process.wait()
        tally["runs"] += 1

        problems = []
        checked = smql.check()
        if checked.returncode != 0:
            problems.append(f"smql check failed: {checked.stdout.strip()} {checked.stderr.strip()}")
        else:
            for name, text in base.items():
                if smql.export(name) != text:
                    problems.append(f"base scene {name} changed")
            if scene in smql.scenes():
                if smql.node_count(scene) == expected[kind]:
                    tally["complete"] += 1
                else:
                    problems.append(f"scene {scene} is partial: {smql.node_count(scene)} != {expected[kind]}")
            else:
                tally["absent"] += 1
        if problems:
            tally["failures"] += 1
            failures.append(f"run {run} ({kind}): " + "; ".join(problems))
            if checked.returncode != 0:
                break  # a damaged database makes every later run meaningless
    return tally, failures


def readers_test(smql, work, seconds, readers):
    smql.run("import", "replica", str(REPLICA), "--db", smql.db, "--scene", "base-replica")
    expected = smql.node_count("base-replica")
    stop = threading.Event()
    lock = threading.Lock()
    tally = {"imports": 0, "queries": 0, "errors": 0, "wrong answers": 0}
    failures = []

    def fail(kind, text):
        with lock:
            tally[kind] += 1
            if len(failures) < 20:
                failures.append(text)

    def writer():
        index = 0
        while not stop.is_set():
            done = smql.run(*import_command(smql, f"churn-{index}")[1:], check=False)
            if done.returncode != 0:
                fail("errors", f"import churn-{index}: {done.stderr.strip()}")
            else:
                with lock:
                    tally["imports"] += 1
            index += 1

    def reader(number):
        rng = random.Random(number)
        seen = 0
        while not stop.is_set():
            try:
                scenes = smql.scenes()
                if len(scenes) < seen:
                    fail("wrong answers", f"reader {number}: {len(scenes)} scenes after {seen}")
                seen = len(scenes)
                scene = rng.choice(scenes)
                counts = smql.node_count(scene)
                if counts != expected:
                    fail("wrong answers", f"reader {number}: scene {scene} has {counts}, not {expected}")
                with lock:
                    tally["queries"] += 3
            except (RuntimeError, json.JSONDecodeError, KeyError, IndexError) as error:
                fail("errors", f"reader {number}: {error}")

    threads = [threading.Thread(target=writer)] + [threading.Thread(target=reader, args=(n,)) for n in range(readers)]
    for thread in threads:
        thread.start()
    time.sleep(seconds)
    stop.set()
    for thread in threads:
        thread.join()
    checked = smql.check()
    if checked.returncode != 0:
        fail("errors", f"smql check after the run: {checked.stdout.strip()}")
    return tally, failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("smql", type=Path, help="the smql program")
    sub = parser.add_subparsers(dest="test", required=True)
    kill = sub.add_parser("kill", help="SIGKILL during imports and ingests")
    kill.add_argument("--runs", type=int, default=200)
    kill.add_argument("--seed", type=int, default=1)
    read = sub.add_parser("readers", help="one writer beside readers")
    read.add_argument("--seconds", type=float, default=300)
    read.add_argument("--readers", type=int, default=8)
    args = parser.parse_args()

    if not REPLICA.is_file():
        sys.exit(f"stress: {REPLICA} is missing (the shared data sits beside the repository)")
    work = Path(tempfile.mkdtemp(prefix="smql-stress-"))
    smql = Smql(args.smql.resolve(), work / "db")
    start = time.monotonic()
    try:
        if args.test == "kill":
            tally, failures = kill_test(smql, work, args.runs, args.seed)
        else:
            tally, failures = readers_test(smql, work, args.seconds, args.readers)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"stress {args.test}: " + ", ".join(f"{value} {name}" for name, value in tally.items()) +
          f" in {time.monotonic() - start:.0f} s")
    for failure in failures:
        print("    " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
