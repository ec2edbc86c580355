"""PEP 249's exceptions. Each failure of the engine carries, besides its message (the full text
the shell prints: the position, the offending line with a caret, the hint):

- ``status``: the C API's status code, ``status_name`` its name ("syntax error", ...)
- ``line``, ``column``: 1-based position in the statement text, 0 when there is none
- ``hint``: what to do, "" when the engine gave none
"""


class Warning(Exception):  # noqa: A001 - the name PEP 249 gives it
    pass


class Error(Exception):
    status = 0
    status_name = ""
    line = 0
    column = 0
    hint = ""


class InterfaceError(Error):
    """The package or the C API used wrongly (a closed connection, a bad parameter type)."""


class DatabaseError(Error):
    pass


class DataError(DatabaseError):
    """A malformed or missing input file (an import, a capture)."""


class OperationalError(DatabaseError):
    """The database cannot be opened or written, a limit was reached, or the statement was interrupted."""


class IntegrityError(DatabaseError):
    pass


class InternalError(DatabaseError):
    """A bug in smql, or memory ran out."""


class ProgrammingError(DatabaseError):
    """A statement that does not parse, a name that does not resolve, an option used wrongly."""


class NotSupportedError(DatabaseError):
    pass
