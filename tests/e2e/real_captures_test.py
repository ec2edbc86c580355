#!/usr/bin/python3
"""Public real captures, each ingested as a user would, its outcome held to what a person sees in
its photos (docs/ingest.md, "Real captures"). The captures are not part of the repository: they
are looked for in CAPTURES (../shared/data/captures, or $SMQL_CAPTURES), one folder per capture,
named as in the fixture folder's SOURCES.md. Captures that are absent are named; with none present
the test exits 77 (skipped).

    real_captures_test.py SMQL CAPTURES
"""
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77


def ingest(smql, capture, db, *options):
    proc = subprocess.run([smql, "ingest", str(capture), "--db", str(db), *options], capture_output=True, text=True)
    return proc.returncode, proc.stdout + proc.stderr


def camera_height(smql, db):
    out = subprocess.run([smql, "check-ingest", str(db)], capture_output=True, text=True).stdout
    match = re.search(r"cameras\s+([\d.]+) m above the floor", out)
    return float(match.group(1)) if match else None


def desk_rgbd(smql, folder, work):
    """TUM fr1/rpy: cameras pitched down at a desk. The floor is the floor: cameras 1.3-1.7 m up."""
    status, log = ingest(smql, folder, work / "db")
    assert status == 0, log
    height = camera_height(smql, work / "db")
    assert height is not None and 1.3 <= height <= 1.7, f"cameras {height} m above the floor\n{log}"


def desk_photos(smql, folder, work):
    """TUM fr3 office, 17 photos mostly of a desk: the floor is not seen, and photos without depth
    are refused, saying why and what to do."""
    status, log = ingest(smql, folder, work / "db")
    assert status == 1, log
    assert "the floor is not seen" in log and "is a table top" in log, log
    assert "--scale" in log and "--force" in log, log
    assert not (work / "db").exists(), "a refused ingest left a database"


def desk_photos_subset(smql, folder, work):
    """8 of the office photos: a small set, the largest group placed, any left out named."""
    photos = work / "photos"
    photos.mkdir()
    for image in sorted(folder.glob("*.png"))[::2][:8]:
        shutil.copy(image, photos)
    shutil.copy(folder / "camera.json", photos)
    status, log = ingest(smql, photos, work / "db", "--force")
    assert status == 0, log
    placed = re.search(r"8 frames(?: \((\d+) placed\))?", log)
    assert placed, log
    if placed.group(1):
        assert int(placed.group(1)) >= 4, log
        assert "left out:" in log, log


def largest_model(log):
    """The most frames any of COLMAP's mapper runs placed together, from the ingest's notes."""
    return max((int(n) for n in re.findall(r"the largest with (\d+) of \d+ frames", log)), default=0)


def refused_for_floor(status, log, db):
    assert status == 1, log
    assert "the memory would be wrong" in log, log
    assert "the floor is not seen" in log or "scale's two priors disagree" in log, log
    assert "--scale" in log and "--force" in log, log
    assert not db.exists(), "a refused ingest left a database"


def desk_frames_photos(smql, folder, work):
    """10 frames of the desk sequence as photos, without depth: COLMAP places most, and the desk
    that fills them is not taken for the floor: refused, saying why (the floor barely shows)."""
    photos = work / "photos"
    photos.mkdir()
    for image in sorted((folder / "rgb").glob("*.png"))[::12][:10]:
        shutil.copy(image, photos)
    camera = json.loads((folder / "camera.json").read_text())
    camera.pop("depth_scale", None)
    (photos / "camera.json").write_text(json.dumps(camera))
    status, log = ingest(smql, photos, work / "db")
    assert largest_model(log) >= 5, log
    refused_for_floor(status, log, work / "db")


def desk_video(smql, folder, work):
    """The desk sequence's 121 colour frames as a 24 s video (5 frames a second) with its camera:
    COLMAP places most of the 25 frames ingested, and the desk is not taken for the floor: refused."""
    import cv2  # Debian's python3-opencv, which the set-up installs
    frames = sorted((folder / "rgb").glob("*.png"))
    video = cv2.VideoWriter(str(work / "desk.mp4"), cv2.VideoWriter_fourcc(*"mp4v"), 5, (640, 480))
    for frame in frames:
        video.write(cv2.imread(str(frame)))
    video.release()
    camera = json.loads((folder / "camera.json").read_text())
    camera.pop("depth_scale", None)
    (work / "camera.json").write_text(json.dumps(camera))
    status, log = ingest(smql, work / "desk.mp4", work / "db", "--video-frames", str(work / "frames"))
    assert largest_model(log) >= 13, log
    refused_for_floor(status, log, work / "db")


def table_photos(smql, folder, work):
    """10 photos of a toy on a kitchen table, all looking down at the table: the table top is not
    the floor (the floor never shows): refused, saying why."""
    photos = work / "photos"
    photos.mkdir()
    for image in sorted(folder.glob("*.png"))[:10]:
        shutil.copy(image, photos)
    status, log = ingest(smql, photos, work / "db")
    assert largest_model(log) >= 5, log
    refused_for_floor(status, log, work / "db")


CHECKS = {
    "tum-fr1-rpy": desk_rgbd,
    "tum-fr3-office-photos": desk_photos,
    "mipnerf360-kitchen": table_photos,
}
SUBSETS = {"tum-fr3-office-photos": [desk_photos_subset], "tum-fr1-rpy": [desk_frames_photos, desk_video]}


def main():
    smql, captures = sys.argv[1], pathlib.Path(os.environ.get("SMQL_CAPTURES", sys.argv[2]))
    present = [name for name in CHECKS if (captures / name).is_dir()]
    absent = [name for name in CHECKS if name not in present]
    if absent:
        print(f"not in {captures} (see docs/ingest.md, 'Real captures', for their sources): {', '.join(absent)}")
    if not present:
        print("no real capture to ingest: skipped")
        return SKIP
    failures = 0
    for name in present:
        for check in [CHECKS[name]] + SUBSETS.get(name, []):
            with tempfile.TemporaryDirectory() as work:
                try:
                    check(smql, captures / name, pathlib.Path(work))
                    print(f"ok   {name}: {check.__doc__.split(':')[0].strip()}")
                except AssertionError as e:
                    failures += 1
                    print(f"FAIL {name} ({check.__name__}): {e}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
