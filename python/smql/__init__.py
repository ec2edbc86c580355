"""smql from Python: the spatial memory engine through PEP 249, as Python's sqlite3 module.

    import smql
    with smql.connect("room.smql", read_only=True) as db:
        cur = db.execute("FIND ? WHERE on(?) PATH", ("cushion", "sofa"))
        for row in cur:
            print(row)
        boxes = cur.boxes()            # numpy (N, 7): cx, cy, cz, sx, sy, sz, yaw

    smql.ingest("captures/kitchen", "room.smql", scene="kitchen", objects="cluster")

Every call goes through the C API (libsmql.so, docs/c-api.md); statements and ingests run with the
GIL released. docs/python.md is the guide.
"""

import collections
import collections.abc
import contextlib
import datetime
import json
import os
import threading
import time

from . import _smql
from .errors import (
    DatabaseError,
    DataError,
    Error,
    IntegrityError,
    InterfaceError,
    InternalError,
    NotSupportedError,
    OperationalError,
    ProgrammingError,
    Warning,
)

__all__ = [
    "connect", "ingest", "import_scene", "Connection", "Cursor", "Progress", "version",
    "Warning", "Error", "InterfaceError", "DatabaseError", "DataError", "OperationalError",
    "IntegrityError", "InternalError", "ProgrammingError", "NotSupportedError",
    "NULL", "INTEGER", "REAL", "TEXT", "BOX",
    "STRING", "BINARY", "NUMBER", "DATETIME", "ROWID",
    "Date", "Time", "Timestamp", "DateFromTicks", "TimeFromTicks", "TimestampFromTicks", "Binary",
]

apilevel = "2.0"
# Threads may share the module and connections: the engine serialises the calls on one
# connection (docs/c-api.md, "Thread safety"). For parallel queries, one connection per thread.
threadsafety = 2
paramstyle = "qmark"
version = _smql.version()

# The type codes of Cursor.description.
NULL = _smql.TYPE_NULL
INTEGER = _smql.TYPE_INTEGER
REAL = _smql.TYPE_REAL
TEXT = _smql.TYPE_TEXT
BOX = _smql.TYPE_BOX


class _TypeObject:
    """A PEP 249 type object: equal to each type code of Cursor.description it stands for."""

    def __init__(self, name, *codes):
        self.name, self.codes = name, frozenset(codes)

    def __eq__(self, other):
        return other in self.codes if isinstance(other, int) else other is self

    def __hash__(self):
        return hash(self.name)

    def __repr__(self):
        return f"smql.{self.name}"


# PEP 249's type objects over smql's type codes. No column holds bytes, and times are ISO 8601 text
# (a scene's capture_time): BINARY and DATETIME match no column, as the PEP allows.
STRING = _TypeObject("STRING", TEXT)
BINARY = _TypeObject("BINARY")
NUMBER = _TypeObject("NUMBER", INTEGER, REAL)
DATETIME = _TypeObject("DATETIME")
ROWID = _TypeObject("ROWID", INTEGER)

# PEP 249's constructors. A date, time or timestamp is bound as its ISO 8601 text, as sqlite3's
# adapters bind it; bytes have no SMQL value and are refused when bound.
Date = datetime.date
Time = datetime.time
Timestamp = datetime.datetime
Binary = bytes


def DateFromTicks(ticks):
    return Date(*time.localtime(ticks)[:3])


def TimeFromTicks(ticks):
    return Time(*time.localtime(ticks)[3:6])


def TimestampFromTicks(ticks):
    return Timestamp(*time.localtime(ticks)[:6])

# One event of an ingest's progress; `kind` is "stage_started", "advanced", "stage_finished" or "note".
Progress = collections.namedtuple("Progress", "kind stage done total seconds text")
_PROGRESS_KINDS = ("stage_started", "advanced", "stage_finished", "note")


def connect(path, read_only=False, cached_statements=128):
    """Opens the database in the directory `path` (a str, bytes or os.PathLike; created when missing,
    unless read_only)."""
    return Connection(path, read_only=read_only, cached_statements=cached_statements)


def _path(path):
    """A database path as the C API takes it: str, bytes or os.PathLike, without NUL."""
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise TypeError(f"a database path is a str, bytes or os.PathLike, not {type(path).__name__}")
    text = os.fsdecode(path)
    if "\0" in text:
        raise ValueError("embedded null character in the database path")
    return text


def _no_nul(text, what):
    if "\0" in text:
        raise ProgrammingError(f"the {what} contains a NUL character")
    return text


def ingest(capture, database, progress=None, **options):
    """Turns a capture into a new scene of `database` (smql ingest CAPTURE --db DATABASE); the
    options are those of `smql ingest --help` with '_' for '-': scene="kitchen", objects="cluster",
    max_size=0, update="kitchen" ... `progress(event)` gets each Progress event and returns a
    true value to stop the ingest. Returns the name of the scene written."""
    with contextlib.closing(connect(database)) as connection:
        return connection.ingest(capture, progress=progress, **options)


def import_scene(path, database, format="json", scene=None, update=False):
    """Imports a scene file (formats of `smql import`: json, replica, spatiallm, vsibench) into
    `database`; with update=True the file becomes the next version of `scene`."""
    with contextlib.closing(connect(database)) as connection:
        connection.import_scene(path, format=format, scene=scene, update=update)


class Connection:
    Warning = Warning
    Error = Error
    InterfaceError = InterfaceError
    DatabaseError = DatabaseError
    DataError = DataError
    OperationalError = OperationalError
    IntegrityError = IntegrityError
    InternalError = InternalError
    ProgrammingError = ProgrammingError
    NotSupportedError = NotSupportedError

    def __init__(self, path, read_only=False, cached_statements=128):
        self._db = _smql.Database(_path(path), read_only)
        self.read_only = read_only
        # Parsed statements by text, least recently used first, as sqlite3's statement cache.
        self._statements = collections.OrderedDict()
        self._cache_size = cached_statements
        self._lock = threading.RLock()

    # Each statement is atomic and committed when it returns: there is nothing to commit or roll back.
    in_transaction = False

    def commit(self):
        self._check_open()

    def rollback(self):
        self._check_open()

    def close(self):
        with self._lock:
            if self._db is None:
                return
            self._statements.clear()  # finalized before the handle closes
            self._db.close()
            self._db = None

    # As sqlite3's: the block's statements are committed (each already is) and the connection stays
    # open; contextlib.closing(smql.connect(...)) closes it.
    def __enter__(self):
        self._check_open()
        return self

    def __exit__(self, *exc):
        return False

    def cursor(self):
        self._check_open()
        return Cursor(self)

    def execute(self, sql, parameters=()):
        return self.cursor().execute(sql, parameters)

    def executemany(self, sql, seq_of_parameters):
        return self.cursor().executemany(sql, seq_of_parameters)

    def executescript(self, script):
        return self.cursor().executescript(script)

    def interrupt(self):
        """Stops the statement or ingest running on this connection in another thread."""
        if self._db is not None:
            self._db.interrupt()

    @property
    def translator(self):
        """What ASK translates with on this connection: a language model's endpoint URL, or
        "built-in". Setting it is SET translator = '...': a URL (http://127.0.0.1:8080/v1), or
        None or "built-in" for the built-in reader (docs/ask.md)."""
        self._check_open()
        return self._db.translator()

    @translator.setter
    def translator(self, url):
        with self._lock:
            self._check_open()
            self._db.set_translator(url)

    def ingest(self, capture, progress=None, **options):
        """As smql.ingest, into this connection's database; the scene becomes the current one."""
        callback = None
        if progress is not None:
            def callback(kind, stage, done, total, seconds, text):
                return progress(Progress(_PROGRESS_KINDS[kind], stage, done, total, seconds, text))
        with self._lock:
            self._check_open()
            self._db.ingest(str(capture), json.dumps(options) if options else "", callback)
        return self.execute("SHOW SCENES").current_scene()

    def import_scene(self, path, format="json", scene=None, update=False):
        with self._lock:
            self._check_open()
            self._db.import_file(format, str(path), scene, update)

    def export(self, path, format="json", scene=None, points=False):
        """Writes a stored scene (default: the current one) to `path` in a format of `smql export`
        (json, glb, ply, geojson, spark-dsg ..., or html: the view's page as one file). With
        points=True (format ply), the capture's coloured points instead of the boxes."""
        with self._lock:
            self._check_open()
            if points and format != "ply":
                raise ProgrammingError(f"points are exported as ply, not as {format}")
            if points:
                self._db.export_points(scene, str(path))
            else:
                self._db.export(format, scene, str(path))

    def evaluate(self, suite=None, scene=None):
        """The research system's metrics (docs/eval.md) as a list of dicts: task, metric, value,
        episodes, median_us. Without a suite the scene is its own truth."""
        with self._lock:
            self._check_open()
            columns, rows = self._db.evaluate(None if suite is None else str(suite), scene)
        return [dict(zip(columns, row)) for row in rows]

    def check_ingest(self, truth=None, scene=None):
        """A stored scene against its synthetic capture's truth.json, or without one whether it
        looks like a room (docs/ingest.md, "Plausibility"): {figure: value}."""
        with self._lock:
            self._check_open()
            _, rows = self._db.check_ingest(None if truth is None else str(truth), scene)
        return dict(rows)

    def _check_open(self):
        if self._db is None:
            raise ProgrammingError("Cannot operate on a closed database.")

    def _run(self, sql, parameters):
        _no_nul(sql, "statement")
        parameters = [value.isoformat() if isinstance(value, (datetime.date, datetime.time)) else value
                      for value in parameters]
        for value in parameters:
            if isinstance(value, str):
                _no_nul(value, "bound text")
        with self._lock:
            self._check_open()
            statements = self._statements
            statement = statements.get(sql)
            if statement is None:
                statement = statements[sql] = _smql.Statement(self._db, sql)
                if len(statements) > self._cache_size:
                    statements.popitem(last=False)
            else:
                statements.move_to_end(sql)
            if len(parameters) != statement.parameter_count:
                raise ProgrammingError(
                    f"Incorrect number of bindings supplied. The current statement uses "
                    f"{statement.parameter_count}, and there are {len(parameters)} supplied.")
            return statement.execute(parameters)


class Cursor:
    __slots__ = ("connection", "arraysize", "description", "rowcount", "lastrowid", "message", "_rows", "_next",
                 "_closed")

    def __init__(self, connection):
        self.connection = connection
        self.arraysize = 1
        self.description = None
        self.rowcount = -1
        self.lastrowid = None
        self.message = ""  # the statement's sentence (RELATE, USE, SET ...), "" for none
        self._rows = None  # None until a statement with a result set has run
        self._next = 0
        self._closed = False

    def execute(self, sql, parameters=()):
        if self._closed:
            raise ProgrammingError("Cannot operate on a closed cursor.")
        if isinstance(parameters, (str, bytes, collections.abc.Mapping)) or not hasattr(parameters, "__len__"):
            raise ProgrammingError("parameters are a sequence, one value per ? in the statement")
        self.description, rows, self.message = self.connection._run(sql, parameters)
        self._rows = rows if self.description is not None else None
        self._next = 0
        self.rowcount = -1
        return self

    def executemany(self, sql, seq_of_parameters):
        for parameters in seq_of_parameters:
            self.execute(sql, parameters)
        return self

    def executescript(self, script):
        """Every ';'-separated statement of the script, in order, each atomic on its own."""
        self._check_open()
        with self.connection._lock:
            self.connection._check_open()
            messages = self.connection._db.execute_script(_no_nul(script, "script"))
        self.description, self._rows, self._next = None, None, 0
        self.message = messages[-1] if messages else ""
        return self

    def fetchone(self):
        self._check_result()
        if self._next >= len(self._rows):
            return None
        self._next += 1
        return self._rows[self._next - 1]

    def fetchmany(self, size=None):
        self._check_result()
        size = self.arraysize if size is None else size
        rows = self._rows[self._next:self._next + size]
        self._next += len(rows)
        return rows

    def fetchall(self):
        self._check_result()
        rows = self._rows[self._next:]
        self._next = len(self._rows)
        return rows

    def __iter__(self):
        return self

    def __next__(self):
        row = self.fetchone()
        if row is None:
            raise StopIteration
        return row

    def close(self):
        self._closed = True
        self._rows = []

    def setinputsizes(self, sizes):
        pass

    def setoutputsize(self, size, column=None):
        pass

    def boxes(self, column=None):
        """The boxes of every row of the last statement as a numpy array (N, 7): centre x, y, z,
        size x, y, z (full extents along the box's axes, metres), yaw (radians, about +z). The
        column is the first box column unless named."""
        try:
            import numpy
        except ImportError:
            raise ImportError("Cursor.boxes needs numpy: pip install numpy, or make the environment with "
                              "`python3 -m venv --system-site-packages` to use Debian's python3-numpy") from None

        index = self._column_index(column, BOX)
        return numpy.array([row[index] if row[index] is not None else (numpy.nan,) * 7 for row in self._rows],
                           dtype=numpy.float64).reshape(-1, 7)

    def column(self, name):
        """One column of every row of the last statement, as a list."""
        index = self._column_index(name, None)
        return [row[index] for row in self._rows]

    def current_scene(self):
        """After SHOW SCENES: the name of the current scene (None when there is none)."""
        current = self._column_index("current", None)
        name = self._column_index("name", None)
        return next((row[name] for row in self._rows if row[current]), None)

    def _column_index(self, name, code):
        for index, described in enumerate(self.description or ()):
            if (name is None and described[1] == code) or described[0] == name:
                return index
        wanted = f"column named {name!r}" if name else "box column"
        raise ProgrammingError(f"the last statement has no {wanted}")

    def _check_open(self):
        if self._closed:
            raise ProgrammingError("Cannot operate on a closed cursor.")
        self.connection._check_open()

    def _check_result(self):
        """PEP 249: fetching is an error before any statement, and after one without a result set."""
        self._check_open()
        if self._rows is None:
            raise ProgrammingError("no result set to fetch from: execute a statement that returns rows first")
