"""The Python package against the real Replica room and the real RGB-D frames of ../shared/data."""
import base64
import contextlib
import json
import os
import pathlib
import signal
import threading
import time

import numpy
import pytest

import smql

DATA = pathlib.Path(os.environ.get("SMQL_SHARED_DATA", pathlib.Path(__file__).parents[3] / "shared" / "data"))
REPLICA = DATA / "replica-room0" / "info_semantic.json"
DINING = DATA / "rgbd-dining"


@pytest.fixture(scope="module")
def replica(tmp_path_factory):
    path = tmp_path_factory.mktemp("replica") / "db"
    smql.import_scene(REPLICA, path, format="replica")
    return path


@pytest.fixture
def db(replica):
    with smql.connect(replica, read_only=True) as connection:
        yield connection


def test_module_follows_pep_249():
    assert smql.apilevel == "2.0" and smql.paramstyle == "qmark" and smql.threadsafety == 2
    assert smql.version.count(".") == 2
    for name in ("Warning", "Error", "InterfaceError", "DatabaseError", "DataError", "OperationalError",
                 "IntegrityError", "InternalError", "ProgrammingError", "NotSupportedError"):
        assert issubclass(getattr(smql, name), Exception)
    assert issubclass(smql.ProgrammingError, smql.DatabaseError) and issubclass(smql.DatabaseError, smql.Error)


def test_dbapi20_api_level_checks(db, replica):
    """The API-level checks of the classic DB-API 2.0 compliance suite (dbapi20.py), adapted: SMQL
    has no tables to create, so the checks that need DDL run on the Replica room instead; those that
    need transactions (commit, rollback) are not applicable (each statement is atomic on its own)."""
    # Type objects compare equal to the type codes of description; constructors exist.
    cur = db.execute("FIND sofa RETURN id, category, height LIMIT 1")
    codes = [d[1] for d in cur.description]
    assert codes[0] == smql.NUMBER and codes[0] == smql.ROWID and codes[1] == smql.STRING
    assert codes[2] == smql.NUMBER and codes[1] != smql.NUMBER and codes[0] != smql.STRING
    assert smql.BINARY != smql.TEXT and smql.DATETIME != smql.TEXT
    assert smql.Date(2026, 11, 28) == smql.DateFromTicks(smql.time.mktime((2026, 11, 28, 12, 0, 0, 0, 0, -1)))
    assert smql.Timestamp(2026, 11, 28, 12, 30, 5) == smql.TimestampFromTicks(
        smql.time.mktime((2026, 11, 28, 12, 30, 5, 0, 0, -1)))
    assert smql.TimeFromTicks(0).__class__ is smql.Time and smql.Binary(b"x") == b"x"
    # A timestamp binds as its ISO 8601 text.
    stamp = smql.Timestamp(2026, 11, 28, 9, 0, 0)
    assert db.execute("FIND sofa WHERE category = ? LIMIT 1", (stamp,)).fetchall() == []
    # Fetching before any statement, or after one without a result set, is an Error.
    fresh = db.cursor()
    for fetch in (fresh.fetchone, fresh.fetchall, lambda: fresh.fetchmany(2)):
        with pytest.raises(smql.Error):
            fetch()
    fresh.execute("SET near = 1 m")
    assert fresh.description is None
    with pytest.raises(smql.Error):
        fresh.fetchall()
    fresh.execute("COUNT sofa")
    assert fresh.fetchall() == [(2,)] and fresh.fetchone() is None
    # arraysize drives fetchmany; setinputsizes and setoutputsize are accepted.
    fresh.arraysize = 3
    fresh.execute("FIND cushion")
    assert len(fresh.fetchmany()) == 3
    fresh.setinputsizes((25,))
    fresh.setoutputsize(1000)
    fresh.close()
    with pytest.raises(smql.Error):
        fresh.execute("COUNT sofa")
    # A column the last statement does not have is named in plain words.
    with pytest.raises(smql.ProgrammingError, match="the last statement has no column named 'current'"):
        db.execute("COUNT sofa").current_scene()
    with pytest.raises(smql.ProgrammingError, match="the last statement has no box column"):
        db.execute("COUNT sofa").boxes()
    # A write on a read-only connection is an OperationalError, as docs/python.md says.
    with pytest.raises(smql.OperationalError, match="open for writing"):
        db.execute("DROP SCENE 'replica-room0'")


def test_bound_parameters_answer_as_literals(db):
    bound = db.execute("FIND ? WHERE on(?) PATH", ("cushion", "sofa")).fetchall()
    literal = db.execute("FIND cushion WHERE on(sofa) PATH").fetchall()
    assert bound == literal and len(bound) >= 3
    assert all(isinstance(row, tuple) for row in bound)
    # A distance bound as a number is metres.
    near = db.execute("FIND ? WHERE near(?, ?)", ("cushion", "sofa", 0.5)).fetchall()
    assert near == db.execute("FIND cushion WHERE near(sofa, 0.5 m)").fetchall()
    # A name is data, never SMQL text.
    with pytest.raises(smql.ProgrammingError) as error:
        db.execute("FIND ? WHERE on(sofa)", ("cushion' OR 'x",))
    assert "unknown category 'cushion' or 'x'" in str(error.value)


def test_description_rows_and_fetching(db):
    cur = db.cursor()
    cur.execute("FIND cushion WHERE on(sofa) PATH")
    names = [d[0] for d in cur.description]
    assert names == ["id", "category", "source_id", "box", "path"]
    assert [d[1] for d in cur.description] == [smql.INTEGER, smql.TEXT, smql.INTEGER, smql.BOX, smql.TEXT]
    rows = cur.fetchall()
    cur.execute("FIND cushion WHERE on(sofa) PATH")
    assert cur.fetchone() == rows[0]
    assert cur.fetchmany(2) == rows[1:3]
    assert list(cur) == rows[3:]
    assert cur.fetchone() is None
    for row in rows:
        assert row[1] == "cushion" and row[4].startswith("replica-room0 / ") and row[4].endswith(f"cushion#{row[0]}")


def test_boxes_are_numpy(db):
    cur = db.execute("FIND cushion WHERE on(sofa)")
    rows = cur.fetchall()
    boxes = cur.boxes()
    assert boxes.shape == (len(rows), 7) and boxes.dtype == numpy.float64
    assert numpy.allclose(boxes, numpy.array([row[3] for row in rows]))
    assert (boxes[:, 3:6] > 0).all()
    # The cushions rest on sofas: their bottoms are above the floor and below 1 m.
    assert ((boxes[:, 2] - boxes[:, 5] / 2) > 0.2).all() and ((boxes[:, 2] - boxes[:, 5] / 2) < 1.0).all()
    with pytest.raises(smql.ProgrammingError):
        db.execute("COUNT cushion").boxes()


def test_errors_carry_message_position_and_hint(db):
    with pytest.raises(smql.ProgrammingError) as error:
        db.execute("FIND cushon WHERE on(sofa)")
    e = error.value
    assert e.line == 1 and e.column == 6 and e.hint == "did you mean cushion?"
    assert e.status_name == "name does not resolve" and "unknown category 'cushon'" in str(e)
    with pytest.raises(smql.ProgrammingError) as error:
        db.execute("FIND cushion WHERE on(sofa")
    assert error.value.status_name == "syntax error" and error.value.line == 1
    with pytest.raises(smql.ProgrammingError, match="Incorrect number of bindings"):
        db.execute("FIND ? WHERE on(?)", ("cushion",))
    with pytest.raises(smql.OperationalError):
        db.import_scene(REPLICA, format="replica", scene="again")  # a read-only connection


def test_bad_input_and_closed_connections(tmp_path, replica):
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with contextlib.closing(smql.connect(tmp_path / "db")) as connection:
        with pytest.raises(smql.DataError):
            connection.import_scene(bad)
        with pytest.raises(smql.InterfaceError):
            connection.execute("FIND ?", (object(),))
    with pytest.raises(smql.ProgrammingError, match="closed"):
        connection.execute("COUNT chair")
    with pytest.raises(smql.OperationalError):
        smql.connect(tmp_path / "missing", read_only=True)


def test_translator_is_set_and_read(db):
    assert db.translator == "built-in"
    with pytest.raises(smql.ProgrammingError):
        db.translator = "ftp://127.0.0.1/v1"
    assert db.translator == "built-in"
    # Nothing listens on the loopback's discard port: the built-in reader answers, with a note.
    db.translator = "http://127.0.0.1:9/v1"
    assert db.translator == "http://127.0.0.1:9/v1"
    message = db.execute("ASK 'how many cushions are on the couch?'").message
    assert "COUNT cushion WHERE on(sofa)" in message and "built-in reader" in message and "7 cushions" in message
    db.translator = None
    assert db.translator == "built-in"


def test_messages_and_scripts(db):
    cur = db.execute("RELATE #20 TO #21")
    assert "wall-plug#20" in cur.message and cur.description
    cur = db.executescript("SET near.distance = 2 m; USE SCENE 'replica-room0'")
    assert "replica-room0" in cur.message and cur.description is None
    assert db.execute("COUNT cushion WHERE near(sofa)").fetchone()[0] >= 5


def test_similar_to_a_numpy_vector(tmp_path):
    vectors = {1: [1, 0, 0], 2: [0.8, 0.6, 0], 3: [0, 1, 0]}
    scene = {
        "smql_scene": 1, "scene": {"name": "shelf"},
        "nodes": [{"id": i, "kind": "object", "category": c, "box": {"center": [i, 0, 0.1], "size": [0.1, 0.1, 0.1]}}
                  for i, c in ((1, "mug"), (2, "cup"), (3, "book"))],
        "blobs": [{"node": i, "name": "embedding", "media_type": "application/x-float32",
                   "base64": base64.b64encode(numpy.array(v, dtype="<f4").tobytes()).decode()}
                  for i, v in vectors.items()],
    }
    path = tmp_path / "shelf.json"
    path.write_text(json.dumps(scene))
    with smql.connect(tmp_path / "db") as connection:
        connection.import_scene(path)
        cur = connection.execute("FIND object SIMILAR TO ? RETURN category, similarity",
                                 (numpy.array([1.0, 0.1, 0.0]),))
        rows = cur.fetchall()
        assert [r[0] for r in rows] == ["mug", "cup", "book"]
        assert rows[0][1] > rows[1][1] > rows[2][1]
        with pytest.raises(smql.ProgrammingError, match="3 dimensions"):
            connection.execute("FIND object SIMILAR TO ?", (numpy.ones(4, dtype=numpy.float32),))
        with pytest.raises(smql.InterfaceError):
            connection.execute("FIND object SIMILAR TO ?", (numpy.ones((2, 2)),))


def test_ingest_with_progress(tmp_path):
    events = []
    scene = smql.ingest(DINING, tmp_path / "db", progress=events.append, scene="dining", objects="cluster")
    assert scene == "dining"
    kinds = {e.kind for e in events}
    assert {"stage_started", "stage_finished"} <= kinds
    assert events[-1].kind == "stage_finished" and events[-1].stage == "write"
    assert any(e.stage == "frames" for e in events)
    with contextlib.closing(smql.connect(tmp_path / "db", read_only=True)) as connection:
        objects = connection.execute("COUNT object").fetchone()[0]
        assert objects > 0
        # Stamped as an imported scene is.
        assert connection.execute("COUNT object WHERE added SINCE '2000-01-01'").fetchone()[0] == objects
        # It looks like a room: the cameras at a person's height, nothing refused.
        room = connection.check_ingest()
        assert 1.0 < room["camera_height_m"] < 2.0 and room["refused"] == 0
        # The capture's points, as a PLY and, with Open3D, as a PointCloud under the boxes.
        connection.export(tmp_path / "points.ply", format="ply", points=True)
        assert (tmp_path / "points.ply").read_bytes().startswith(b"ply\nformat binary_little_endian 1.0\n")
        with pytest.raises(smql.ProgrammingError, match="exported as ply"):
            connection.export(tmp_path / "points.json", points=True)
        try:
            import smql.open3d as interop
        except ImportError:
            return
        cloud = interop.scene_points(connection)
        assert len(cloud.points) > 5000 and cloud.has_colors()
        floor = numpy.percentile(numpy.asarray(cloud.points)[:, 2], 2)
        assert -0.15 < floor < 0.05
    # Options are checked before the work.
    with pytest.raises(smql.ProgrammingError) as error:
        smql.ingest(DINING, tmp_path / "db", objcts="cluster")
    assert error.value.hint.startswith("did you mean objects?")
    # The cameras' height in metres, as the shell's --camera-height: 150 is centimetres.
    with pytest.raises(smql.ProgrammingError, match="--camera-height 150") as error:
        smql.ingest(DINING, tmp_path / "db", scene="dining-2", camera_height=150)
    assert "metres above the floor" in error.value.hint
    with pytest.raises(smql.DataError, match="already exists"):
        smql.ingest(DINING, tmp_path / "db", scene="dining")


def test_progress_stops_and_raises(tmp_path):
    with smql.connect(tmp_path / "db") as connection:
        with pytest.raises(smql.OperationalError, match="stopped"):
            connection.ingest(DINING, progress=lambda event: event.kind == "stage_finished")

        def fails(event):
            raise KeyError("from the callback")

        with pytest.raises(KeyError, match="from the callback"):
            connection.ingest(DINING, progress=fails)
        assert connection.execute("SHOW SCENES").fetchall() == []


def test_progress_counts_colmap_frames_and_stops_a_running_command(tmp_path):
    """COLMAP's bar counts the frames its command has done; a stop asked there stops the command at once."""
    photos = DATA / "captures" / "tum-fr3-office-photos"
    if not photos.is_dir():
        pytest.skip(f"{photos} is absent")
    events = []

    def stop_at_third(event):
        events.append(event)
        return event.stage == "colmap" and event.kind == "advanced" and event.done >= 3

    with smql.connect(tmp_path / "db") as connection:
        with pytest.raises(smql.OperationalError, match="stopped"):
            connection.ingest(photos, progress=stop_at_third)
        assert connection.execute("SHOW SCENES").fetchall() == []
    counted = [e.done for e in events if e.stage == "colmap" and e.kind == "advanced"]
    assert counted and counted[-1] >= 3 and counted == sorted(counted)
    assert all(e.total == 17 for e in events if e.stage == "colmap")
    # Stopped while the extractor ran: the frames, placing and finding things never started.
    assert not any(e.stage == "frames" for e in events)


def test_ctrl_c_stops_an_ingest_without_a_progress_callback(tmp_path):
    """Ctrl-C (SIGINT) during a long ingest raises KeyboardInterrupt within a moment, nothing written."""
    photos = DATA / "captures" / "tum-fr3-office-photos"
    if not photos.is_dir():
        pytest.skip(f"{photos} is absent")
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        smql.ingest(photos, tmp_path / "db")  # COLMAP alone takes several seconds here
    timer.join()
    assert time.monotonic() - started < 5
    with contextlib.closing(smql.connect(tmp_path / "db", read_only=True)) as connection:
        assert connection.execute("SHOW SCENES").fetchall() == []


def test_ingest_releases_the_gil_and_can_be_interrupted(tmp_path):
    with smql.connect(tmp_path / "db") as connection:
        started = threading.Event()
        outcome = []

        def run():
            try:
                connection.ingest(DINING, progress=lambda event: started.set())
                outcome.append("finished")
            except smql.OperationalError as e:
                outcome.append(e.status_name)

        worker = threading.Thread(target=run)
        worker.start()
        # This thread runs while the ingest works only because the ingest released the GIL.
        assert started.wait(60)
        connection.interrupt()
        worker.join(120)
        assert outcome == ["interrupted"]


def test_threads_share_a_connection(db):
    expected = db.execute("FIND cushion WHERE near(sofa) PATH").fetchall()
    results = []

    def query():
        for _ in range(20):
            results.append(db.execute("FIND cushion WHERE near(sofa) PATH").fetchall() == expected)

    threads = [threading.Thread(target=query) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 80 and all(results)


def test_evaluation_as_a_call(db):
    metrics = {m["metric"]: m for m in db.evaluate(scene="replica-room0")}
    assert metrics["SR_obj"]["value"] == 1.0 and metrics["SR_obj"]["episodes"] > 20
    assert 0.0 <= metrics["SR_nav"]["value"] <= 1.0


def test_open3d_interop(db):
    o3d = pytest.importorskip("open3d", reason="python3-open3d is not installed")
    import smql.open3d

    cur = db.execute("FIND cushion WHERE on(sofa)")
    rows, boxes = cur.fetchall(), cur.boxes()
    obbs = smql.open3d.oriented_boxes(boxes)
    assert len(obbs) == len(rows) and all(isinstance(b, o3d.geometry.OrientedBoundingBox) for b in obbs)
    for obb, box in zip(obbs, boxes):
        assert numpy.allclose(obb.center, box[:3]) and numpy.allclose(obb.extent, box[3:6])
        assert obb.volume() == pytest.approx(box[3] * box[4] * box[5])
    lines = smql.open3d.scene_lines(db, scene="replica-room0", statement="FIND object")
    objects = db.execute("COUNT object").fetchone()[0]
    assert len(lines.lines) == 12 * objects and len(lines.colors) == len(lines.lines)
    # Each box in its category's colour as SHOW CATEGORIES gives it (the view's and the exports').
    shown = {c: colour for c, _, colour in db.execute("SHOW CATEGORIES").fetchall()}
    sofa = db.execute("FIND sofa").fetchone()
    first = db.execute("FIND object").column("category").index(sofa[1])
    drawn = "#" + "".join(f"{round(c * 255):02x}" for c in numpy.asarray(lines.colors)[12 * first])
    assert drawn == shown["sofa"]


def test_export_and_import_back(db, tmp_path):
    db.export(tmp_path / "room.json", scene="replica-room0")
    with smql.connect(tmp_path / "copy") as copy:
        copy.import_scene(tmp_path / "room.json", scene="again")
        assert copy.execute("FIND cushion WHERE on(sofa)").fetchall() == db.execute("FIND cushion WHERE on(sofa)").fetchall()
    with pytest.raises(smql.DatabaseError, match="holds no points"):
        db.export(tmp_path / "points.ply", format="ply", points=True)
    db.export(tmp_path / "room.html", format="html")
    assert (tmp_path / "room.html").read_text().startswith("<!doctype html>")
    with pytest.raises(smql.ProgrammingError, match="unknown export format"):
        db.export(tmp_path / "x", format="jsn")


def test_export_never_writes_the_database_s_own_files(tmp_path):
    """The library's one guard: an export onto data.mdb or lock.mdb, a hard link of them, or into the
    database's folder is refused, and the database still answers."""
    path = tmp_path / "db"
    smql.import_scene(REPLICA, path, format="replica")
    os.link(path / "data.mdb", tmp_path / "hardlink.mdb")
    with smql.connect(path) as db:
        sofas = db.execute("COUNT sofa").fetchone()[0]
        for target in (path / "data.mdb", path / "lock.mdb", tmp_path / "hardlink.mdb", path / "room.json"):
            with pytest.raises(smql.Error, match="would destroy the database"):
                db.export(target)
        assert db.execute("COUNT sofa").fetchone()[0] == sofas
    with smql.connect(path, read_only=True) as again:
        assert again.execute("COUNT sofa").fetchone()[0] == sofas


def test_paths_and_texts_are_what_they_say(tmp_path):
    """connect takes a path, never an object's repr; a NUL never cuts a path, a statement or a bound
    text short; a with block keeps the connection open, as sqlite3's does."""
    os.chdir(tmp_path)
    for wrong in (None, 5, 2.5, ["db"]):
        with pytest.raises(TypeError):
            smql.connect(wrong)
    with pytest.raises(ValueError):
        smql.connect(str(tmp_path / "a\x00b"))
    assert sorted(p.name for p in tmp_path.iterdir()) == []  # no folder 'None', '5' or 'a'
    smql.import_scene(REPLICA, tmp_path / "db", format="replica")
    with smql.connect(os.fsencode(tmp_path / "db")) as db:
        sofas = db.execute("COUNT sofa").fetchone()[0]
        with pytest.raises(smql.ProgrammingError, match="NUL"):
            db.execute("COUNT sofa\x00 WHERE on(floor)")
        with pytest.raises(smql.ProgrammingError, match="NUL"):
            db.execute("COUNT ?", ("sofa\x00junk",))
        with pytest.raises(smql.ProgrammingError, match="NUL"):
            db.executescript("COUNT sofa;\x00 DROP SCENE 'replica-room0'")
        # What cannot be bound is a PEP 249 error, never pybind's RuntimeError or TypeError.
        with pytest.raises(smql.DataError, match="parameter 1 is outside 64-bit integers"):
            db.execute("FIND object LIMIT ?", (2**70,))
        with pytest.raises(smql.DataError, match="parameter 1 is text that has no UTF-8 form"):
            db.execute("COUNT ?", ("\ud800",))
        with pytest.raises(smql.ProgrammingError, match="sequence"):
            db.execute("COUNT ?", {"category": "sofa"})
        assert db.execute("FIND object LIMIT ?", (2**63 - 1,)).fetchall()
    assert db.execute("COUNT sofa").fetchone()[0] == sofas  # still open after the block
    db.close()
    with pytest.raises(smql.ProgrammingError):
        db.execute("COUNT sofa")
