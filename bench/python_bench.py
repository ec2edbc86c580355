#!/usr/bin/env python3
"""The Python package's cost over the C API (docs/benchmarks.md, "Python"; `make bench-python`).

Each statement runs prepared, again and again, on the Replica room: through the C API
(smql_bench_c_api: reset, bind, step, read every value) and through the package
(`connection.execute(sql, params).fetchall()`, the statement cache warm). The difference is what
Python adds. As the peer, Python's sqlite3 fetches the same number of rows of as many values from
an in-memory table (a prepared SELECT): what a Python database call costs there.

    bench/python_bench.py BUILD_DIR SHARED_DATA [--runs N] [--out docs/benchmarks.md]
"""
import argparse
import os
import pathlib
import re
import sqlite3
import statistics
import subprocess
import sys
import tempfile
import time

STATEMENTS = [
    ("FIND ? WHERE on(?)", ("cushion", "sofa")),
    ("FIND ? WHERE near(?, ?) PATH", ("cushion", "sofa", 0.5)),
    ("RELATE #20 TO #21", ()),
    ("FIND object NEAREST TO ? LIMIT 5", ("door",)),
    ("COUNT ?", ("chair",)),
    ("FIND object PATH", ()),
]


def c_param(value):
    if isinstance(value, float):
        return f"d:{value}"
    if isinstance(value, int):
        return f"i:{value}"
    return f"s:{value}"


def median_us(call, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter_ns()
        call()
        times.append((time.perf_counter_ns() - start) / 1000)
    return statistics.median(times)


def sqlite_peer(rows, width, runs):
    db = sqlite3.connect(":memory:")
    db.execute(f"CREATE TABLE t ({', '.join(f'c{i} REAL' for i in range(width))})")
    db.executemany(f"INSERT INTO t VALUES ({', '.join('?' * width)})",
                   [tuple(float(r * width + c) for c in range(width)) for r in range(max(rows, 1))])
    return median_us(lambda: db.execute("SELECT * FROM t LIMIT ?", (rows,)).fetchall(), runs)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build")
    parser.add_argument("data")
    parser.add_argument("--runs", type=int, default=3000)
    parser.add_argument("--out")
    args = parser.parse_args()
    build = pathlib.Path(args.build).resolve()
    sys.path.insert(0, str(build / "python"))
    import smql

    with tempfile.TemporaryDirectory() as work:
        path = pathlib.Path(work) / "db"
        smql.import_scene(pathlib.Path(args.data) / "replica-room0" / "info_semantic.json", path, format="replica")
        connection = smql.connect(path, read_only=True)
        lines = []
        for sql, params in STATEMENTS:
            out = subprocess.run([str(build / "bench" / "smql_bench_c_api"), str(path), str(args.runs), sql,
                                  *map(c_param, params)], check=True, capture_output=True, text=True).stdout.split()
            c_us, rows = float(out[0]), int(out[1])
            cursor = connection.execute(sql, params)
            fetched = cursor.fetchall()
            assert len(fetched) == rows, (sql, len(fetched), rows)
            # A box is seven numbers in Python: count the values a row gives.
            width = sum(7 if isinstance(v, tuple) else 1 for v in fetched[0]) if fetched else 1
            python_us = median_us(lambda: connection.execute(sql, params).fetchall(), args.runs)
            peer_us = sqlite_peer(rows, width, args.runs)
            lines.append((sql, params, rows, width, c_us, python_us, peer_us))
        connection.close()

    table = ["| statement | rows x values | C API | Python | Python - C | per row | sqlite3 (Python), same rows |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for sql, params, rows, width, c_us, python_us, peer_us in lines:
        shown = sql if not params else f"{sql} with {params}"
        extra = python_us - c_us
        table.append(f"| `{shown}` | {rows} x {width} | {c_us:.1f} | {python_us:.1f} | {extra:.1f} | "
                     f"{extra / max(rows, 1):.2f} | {peer_us:.1f} |")
    text = ("\n".join(table) + "\n\nMedians of {runs} runs each, microseconds, on the Replica room; Python {py}, "
            "the package from {build}.\n").format(runs=args.runs, py=sys.version.split()[0], build=build.name)
    print(text)
    if args.out:
        page = pathlib.Path(args.out).read_text()
        begin, end = "<!-- python_bench: begin -->", "<!-- python_bench: end -->"
        block = f"{begin}\n{text}{end}"
        if begin in page:
            page = re.sub(re.escape(begin) + ".*?" + re.escape(end), lambda _: block, page, flags=re.S)
        else:
            page += f"\n## Python (`make bench-python`, `bench/python_bench.py`)\n\n{block}\n"
        pathlib.Path(args.out).write_text(page)


if __name__ == "__main__":
    main()
