#!/usr/bin/env python3
"""`make stress`: the fault tests that take minutes, run as a user would run the smql command.

  scripts/stress.py SMQL kill    [--runs 200]               SIGKILL during imports and ingests
  scripts/stress.py SMQL readers [--seconds 300 --readers 8]  one writer beside readers
  scripts/stress.py SMQL flips   [--flips 400]              single-bit flips across data.mdb

kill: a database holds two base scenes (the Replica room of ../shared/data and an ingested
synthetic capture). Each run starts an import (a Replica room under a new name) or an ingest (a
small synthetic capture under a new name) and kills it with SIGKILL after a random delay within
the shortest of three clean runs. After every run: `smql check` passes, both base scenes export
byte-identical to before, and the killed scene is either absent or complete (as many nodes as a
clean run of the same input gives).

readers: one process imports new scenes in a loop while N reader processes query in a loop. Every
answer is checked: the base scene's counts never change, the list of scenes only grows, and every
scene a reader sees is complete. Any error or wrong answer is counted and fails the run.

flips: a database holds the Replica room and an ingested synthetic capture (with evidence blobs).
Each run flips one random bit of a copy of its data.mdb, then runs `smql check` and every class of
read (SHOW SCENES, FIND with paths, COUNT, RELATE, SHOW TREE, GUIDE, `smql export json` of each
scene) and compares each answer with the undamaged database's. A read that exits 0 with another
answer is a silent wrong answer; it counts against the test when the flipped byte lies where a
checksum covers it (a record of 31 bytes or more: nodes, scenes, relation entries, blobs, history),
or when `smql check` passed the damaged copy; a wrong answer from what LMDB alone keeps (keys, the
fixed-size index entries of children and labels) that `smql check` reports is counted apart. A
crash (a signal) counts against the test outside LMDB's page structure (branch pages, page headers
and node pointers, node headers), which LMDB follows without checks (docs/storage.md).

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


PAGE = 4096
P_BRANCH, P_LEAF, P_OVERFLOW, P_META, P_LEAF2 = 0x01, 0x02, 0x04, 0x08, 0x20
F_BIGDATA, F_SUBDATA, F_DUPDATA = 0x01, 0x02, 0x04
CHECKSUMMED = 31  # the shortest record that carries a checksum: a relation entry


def u16(page, at):
    return page[at] | page[at + 1] << 8


def byte_kind(data, offset, overflow):
    """Where a byte of data.mdb lies: 'checksummed' (in a record smql seals), 'structure' (LMDB's
    page structure: branch pages, page headers and node pointers, node headers) or 'lmdb' (other
    bytes only LMDB keeps: keys, the fixed-size entries of children and labels)."""
    number = offset // PAGE
    if number in overflow:
        return "checksummed"  # the pages of a large value (a blob, a large record)
    page = data[number * PAGE:(number + 1) * PAGE]
    if len(page) < 16:
        return "lmdb"
    flags, at = u16(page, 10), offset % PAGE
    if flags & P_OVERFLOW:  # the first page of a large value: its header, then the value
        return "structure" if at < 16 else "checksummed"
    if flags & P_BRANCH or (flags & P_LEAF and not flags & P_LEAF2 and at < u16(page, 12)):
        return "structure"
    if flags & P_LEAF2:  # packed fixed-size entries: checksummed when relation entries
        return "checksummed" if u16(page, 8) >= CHECKSUMMED and at >= 16 else "lmdb"
    if not flags & P_LEAF:
        return "lmdb"
    lower = u16(page, 12)
    for slot in range(16, lower, 2):
        node = u16(page, slot)
        if node + 8 > PAGE:
            continue
        size = u16(page, node) | u16(page, node + 2) << 16
        node_flags, key_size = u16(page, node + 4), u16(page, node + 6)
        start = node + 8 + key_size
        if node <= at < node + 8:
            return "structure"
        if node_flags & (F_BIGDATA | F_SUBDATA):
            continue
        # A sub-page of duplicates starts with its own 16-byte header.
        first = start + (16 if node_flags & F_DUPDATA else 0)
        if first <= at < start + size and (size >= CHECKSUMMED or node_flags & F_DUPDATA):
            return "checksummed"
    return "lmdb"


def overflow_pages(data):
    """The page numbers that continue an overflow page (only the first has a header). The pages are
    read in order and a run's continuation skipped, so a blob's bytes are never read as a header."""
    out = set()
    pages = len(data) // PAGE
    number = 0
    while number < pages:
        page = data[number * PAGE:(number + 1) * PAGE]
        count = int.from_bytes(page[12:16], "little") if u16(page, 10) & P_OVERFLOW else 1
        count = max(1, min(count, pages - number))
        out.update(range(number + 1, number + count))
        number += count
    return out


def relate_statements(smql, scenes):
    """For each scene, RELATE between its first object and its first anchor (by id), from the
    undamaged database."""
    out = {}
    for scene in scenes:
        answer = smql.query(f"USE SCENE '{scene}'; FIND object LIMIT 1; FIND anchor LIMIT 1")
        ids = [part["rows"][0]["id"] for part in answer[1:]]
        out[scene] = f"RELATE #{ids[0]} TO #{ids[1]}"
    return out


def read_answers(smql, scenes, relate):
    """Every class of read, as (name, exit status, output): statements through the shell, exports."""
    out = [("SHOW SCENES", *answer(smql, [smql.db, "--json", "-c", "SHOW SCENES"]))]
    for scene in scenes:
        use = f"USE SCENE '{scene}'; "
        for name, statement in (("FIND PATH", "FIND node PATH"), ("COUNT", "COUNT object"),
                                ("RELATE", relate[scene]), ("SHOW TREE", "SHOW TREE"),
                                ("GUIDE", "GUIDE FROM HERE TO (FIND object LIMIT 1)")):
            out.append((f"{name} {scene}", *answer(smql, [smql.db, "--json", "-c", use + statement])))
        out.append((f"export {scene}", *answer(smql, ["export", "json", "--db", smql.db, "--scene", scene])))
    return out


def answer(smql, args):
    done = subprocess.run([smql.binary, *args], capture_output=True, text=True, errors="replace")
    return done.returncode, done.stdout


def flips_test(smql, work, flips, seed):
    capture = work / "capture"
    smql.run("synth", "--out", str(capture), "--seed", "7", "--frames", "12", "--objects", "8")
    smql.run("import", "replica", str(REPLICA), "--db", smql.db, "--scene", "replica")
    smql.run("ingest", str(capture), "--db", smql.db, "--scene", "capture", "--quiet")
    scenes = ["replica", "capture"]
    pristine_db = Path(smql.db)
    relate = relate_statements(smql, scenes)
    truth = read_answers(smql, scenes, relate)
    for name, status, _ in truth:
        if status != 0:
            raise RuntimeError(f"{name} fails on the undamaged database (exit {status}): no flip can be judged by it")
    data = (pristine_db / "data.mdb").read_bytes()
    overflow = overflow_pages(data)
    random.seed(seed)
    tally = {"flips": 0, "found by check": 0, "reads refused": 0, "silent wrong answers (checksummed)": 0,
             "silent wrong answers (LMDB's own bytes)": 0, "silent wrong answers smql check passed": 0, "crashes": 0,
             "crashes in LMDB's page structure": 0}
    failures = []
    damaged = Smql(smql.binary, work / "flipped")
    for _ in range(flips):
        shutil.rmtree(damaged.db, ignore_errors=True)
        shutil.copytree(pristine_db, damaged.db)
        offset, bit = random.randrange(len(data)), random.randrange(8)
        kind = byte_kind(data, offset, overflow)
        with open(Path(damaged.db) / "data.mdb", "r+b") as f:
            f.seek(offset)
            byte = f.read(1)[0]
            f.seek(offset)
            f.write(bytes([byte ^ (1 << bit)]))
        tally["flips"] += 1
        def crashed(what):
            tally["crashes in LMDB's page structure" if kind == "structure" else "crashes"] += 1
            if kind != "structure":
                kept = Path(tempfile.gettempdir()) / f"smql-flip-crash-{offset}-{bit}"
                shutil.rmtree(kept, ignore_errors=True)
                shutil.copytree(damaged.db, kept)
                failures.append(f"crash: {what} after a flip at byte {offset}, bit {bit} ({kind}); kept in {kept}")

        checked = damaged.check()
        if checked.returncode < 0 or checked.returncode > 128:
            crashed("smql check")
            continue
        tally["found by check"] += checked.returncode == 1
        for (name, status, output), (_, _, truth_output) in zip(read_answers(damaged, scenes, relate), truth):
            where = f"{name} after a flip at byte {offset}, bit {bit} ({kind})"
            if status < 0 or status > 128:
                crashed(name)
            elif status != 0:
                tally["reads refused"] += 1
            elif output != truth_output:
                key = "silent wrong answers (checksummed)" if kind == "checksummed" else \
                    "silent wrong answers (LMDB's own bytes)"
                tally[key] += 1
                if kind == "checksummed":
                    failures.append(f"silent wrong answer: {where}")
                elif checked.returncode == 0:
                    # The one defence against damage smql cannot seal is `smql check`: it must see it.
                    tally["silent wrong answers smql check passed"] += 1
                    failures.append(f"silent wrong answer that smql check passed: {where}")
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
    flip = sub.add_parser("flips", help="single-bit flips across data.mdb")
    flip.add_argument("--flips", type=int, default=400)
    flip.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    if not REPLICA.is_file():
        sys.exit(f"stress: {REPLICA} is missing (the shared data sits beside the repository)")
    work = Path(tempfile.mkdtemp(prefix="smql-stress-"))
    smql = Smql(args.smql.resolve(), work / "db")
    start = time.monotonic()
    try:
        if args.test == "kill":
            tally, failures = kill_test(smql, work, args.runs, args.seed)
        elif args.test == "flips":
            tally, failures = flips_test(smql, work, args.flips, args.seed)
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
