"""flexlink's own exceptions. Messages name the file, the field and the expected unit or range."""

from __future__ import annotations


class FlexlinkError(Exception):
    """Base class of every error flexlink raises on purpose."""


class InputError(FlexlinkError, ValueError):
    """A scene, material or command-line value is missing, malformed or out of range.

    ``source`` is the file (or "command line"), ``field`` the dotted key, ``expected`` what
    would have been accepted (unit, range, type).
    """

    def __init__(self, message: str, *, source: str | None = None, field: str | None = None,
                 expected: str | None = None):
        self.source, self.field, self.expected = source, field, expected
        where = ": ".join(p for p in (source, field) if p)
        text = f"{where}: {message}" if where else message
        if expected:
            text += f" (expected {expected})"
        super().__init__(text)


class KinematicsError(FlexlinkError):
    """The linkage cannot close, the requested pose is unreachable, or it is a dead centre."""


class NumericalError(FlexlinkError):
    """The eigenproblem is ill-posed or the answer fails its own checks (residual, orthogonality,
    negative or NaN eigenvalues, singular mass)."""


class OutputError(FlexlinkError):
    """An output folder or file cannot be written."""
