"""Warnings once per run: each kind of warning is shown the first time it comes, repeats are
counted and reported at the end, and the many model evaluations of a fit or a Monte Carlo run
(also in worker processes) are collected silently and summarised in one line.

A warning's kind is its logger and its text with the numbers masked ("L/h = 4.1" and
"L/h = 3.9" are one kind; "case1.toml" and "case2.toml" are not, a digit inside a word is
kept), so a fit that moves a dimension does not make a new kind per evaluation.
"""

from __future__ import annotations

import collections
import contextlib
import logging
import re
import sys
from collections.abc import Iterator

ROOT = "flexlink"
FORMAT = "%(level)s: %(message)s"  # "warning: ...", as the commands' own result lines
VERBOSE_FORMAT = "%(levelname)s %(name)s: %(message)s"  # -v: which module said it
_NUMBER = re.compile(r"(?<![\w.])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w])")

log = logging.getLogger(__name__)

# (logger name, level, message): a record as it crosses a process boundary
Record = tuple[str, int, str]


def kind(name: str, message: str) -> tuple[str, str]:
    """What makes two warnings the same: the logger and the message with numbers masked."""
    return name, _NUMBER.sub("#", message)


class OncePerKind(logging.Filter):
    """Handler filter: passes the first warning of each kind, counts the rest."""

    def __init__(self):
        super().__init__()
        self.counts: collections.Counter = collections.Counter()
        self.first: dict[tuple[str, str], str] = {}

    def filter(self, record: logging.LogRecord) -> bool:
        if record.levelno < logging.WARNING:
            return True
        key = kind(record.name, record.getMessage())
        self.counts[key] += 1
        self.first.setdefault(key, record.getMessage())
        return self.counts[key] == 1

    def repeats(self) -> list[str]:
        """One line per kind that came more than once."""
        return [f"the warning '{_short(self.first[key])}' came {n} times in all"
                for key, n in self.counts.items() if n > 1]


def _short(text: str, width: int = 100) -> str:
    return text if len(text) <= width else text[:width - 3] + "..."


class _Stderr(logging.StreamHandler):
    """A stream handler writing to whatever ``sys.stderr`` is when a record comes (a test
    runner swaps it per command)."""

    @property
    def stream(self):
        return sys.stderr

    @stream.setter
    def stream(self, value):
        pass


class _Plain(logging.Formatter):
    """The level in lower case ahead of the message, no logger name."""

    def format(self, record: logging.LogRecord) -> str:
        record.level = record.levelname.lower()
        return super().format(record)


_installed: _Stderr | None = None


def configure(verbose: bool = False) -> OncePerKind:
    """Log to stderr with warnings once per kind; INFO too when ``verbose``. Calling it again
    replaces the earlier set-up (one handler, on the root logger as ``logging.basicConfig``
    would put it). Returns the filter, whose repeats the caller reports when the run ends
    (``report_repeats``)."""
    global _installed
    root = logging.getLogger()
    if _installed is not None:
        root.removeHandler(_installed)
    _installed = _Stderr()
    _installed.setFormatter(logging.Formatter(VERBOSE_FORMAT) if verbose else _Plain(FORMAT))
    once = OncePerKind()
    _installed.addFilter(once)
    root.addHandler(_installed)
    root.setLevel(logging.INFO if verbose else logging.WARNING)
    return once


def report_repeats(once: OncePerKind) -> None:
    for line in once.repeats():
        log.warning("%s", line)


# -- silent batches -----------------------------------------------------------------------------
class _Collector(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.records: list[Record] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append((record.name, record.levelno, record.getMessage()))


_stack: list[_Collector] = []


@contextlib.contextmanager
def collecting() -> Iterator[list[Record]]:
    """Inside the block flexlink's warnings are not shown but appended to the yielded list
    (the innermost block takes them)."""
    logger = logging.getLogger(ROOT)
    collector = _Collector()
    propagate, level, handlers = logger.propagate, logger.level, list(logger.handlers)
    for h in handlers:  # our console handler, or the enclosing block's collector
        logger.removeHandler(h)
    _stack.append(collector)
    logger.addHandler(collector)
    logger.propagate = False
    if logger.getEffectiveLevel() > logging.WARNING:
        logger.setLevel(logging.WARNING)
    try:
        yield collector.records
    finally:
        _stack.pop()
        logger.removeHandler(collector)
        for h in handlers:
            logger.addHandler(h)
        logger.propagate = propagate
        logger.setLevel(level)


def report(records: list[Record], during: str) -> None:
    """Hand ``records`` collected during ``during`` (e.g. "18 fits") to an enclosing
    ``collecting`` block, or log their one-line summary (and, at INFO, one line per kind)."""
    if _stack:
        _stack[-1].records.extend(records)
        return
    if not records:
        return
    kinds = collections.Counter(kind(name, message) for name, _, message in records)
    first = records[0][2]
    log.warning("%d warning%s of %d kind%s during %s; first: %s", len(records),
                "" if len(records) == 1 else "s", len(kinds), "" if len(kinds) == 1 else "s",
                during, first)
    firsts = {}
    for name, _, message in records:
        firsts.setdefault(kind(name, message), message)
    for key, n in kinds.items():
        log.info("%d x %s", n, firsts[key])


@contextlib.contextmanager
def quiet(during: str) -> Iterator[None]:
    """Collect flexlink's warnings inside the block and summarise them at its end."""
    records: list[Record] = []
    try:
        with collecting() as records:
            yield
    finally:  # also when the block fails: what it warned about may explain why
        report(records, during)
