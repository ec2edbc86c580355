#!/usr/bin/env python3
"""The `contributing_excerpts` test: every ```cpp excerpt:PATH block of the pages given must still
be what PATH holds. A block's lines, split at lines that are `...`, are runs; each run must appear
in the file as consecutive lines (compared without their indentation and skipping blank lines), and
the runs in the block's order. Prints each block that drifted with the first line not found.

    check_excerpts.py SOURCE_ROOT PAGE.md...
"""
import pathlib
import re
import sys

FENCE = re.compile(r"^\s*```(\S*)\s*excerpt:(\S+)\s*$")


def blocks(page):
    lines = page.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        start, body = i + 1, []
        i += 1
        while i < len(lines) and lines[i].strip() != "```":
            body.append(lines[i])
            i += 1
        yield start, m.group(2), body
        i += 1


def runs(body):
    run = []
    for line in body:
        text = line.strip()
        if text == "...":
            if run:
                yield run
            run = []
        elif text:
            run.append(text)
    if run:
        yield run


def missing_line(body, source):
    """None when every run is found in order; else the first line of the block not found."""
    held = [line.strip() for line in source.splitlines() if line.strip()]
    at = 0
    for run in runs(body):
        found = next((i for i in range(at, len(held) - len(run) + 1) if held[i:i + len(run)] == run), None)
        if found is None:
            # The first line of the run that breaks it, for the message.
            for n in range(len(run), 0, -1):
                if any(held[i:i + n] == run[:n] for i in range(at, len(held) - n + 1)):
                    return run[n] if n < len(run) else run[0]
            return run[0]
        at = found + len(run)
    return None


def main():
    root = pathlib.Path(sys.argv[1])
    failures = checked = 0
    for page in map(pathlib.Path, sys.argv[2:]):
        for line_number, path, body in blocks(page):
            checked += 1
            source = root / path
            if not source.is_file():
                print(f"FAIL {page}:{line_number}: excerpt of {path}, which does not exist")
                failures += 1
                continue
            line = missing_line(body, source.read_text(encoding="utf-8"))
            if line is not None:
                print(f"FAIL {page}:{line_number}: excerpt of {path} no longer matches it; not found in order:\n"
                      f"    {line}")
                failures += 1
    print(f"{checked} excerpts checked, {failures} drifted")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
