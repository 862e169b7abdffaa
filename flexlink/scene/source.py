"""The text side of a scene file: TOML reading, ``base`` files, overrides and noted values.

What comes out is plain data ready for the schema (``schema.py``), plus where each key came
from (so an error names the right file) and the notes written beside values.

- ``base = "file.toml"`` merges a shared file underneath the scene: the scene's own keys win,
  tables merge key by key, except ``material``, which a scene replaces whole (mixing two
  materials' keys would describe neither).
- Any value may be written ``{ value = ..., note = "..." }``. A note starting with "assumed"
  makes the value one of the scene's assumptions, reported with every result. An assumed
  value may also carry ``range = [low, high]`` (written like the value) and the ``reason``
  for that range; ``flexlink modes --sensitivity`` evaluates both ends and samples between.
- Overrides (``{"section.width": "25 mm"}``) are applied as if written in the file, before
  validation, so a sweep or a fit goes through the same checks as a file.
- A file is parsed once per process while it is unchanged (``_parsed``, keyed by path,
  modification time and size): a calibration or a Monte Carlo loads the same scene thousands of
  times with different overrides, and parsing dominated each load.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import tomllib
from pathlib import Path

from flexlink.errors import InputError

REPLACED_WHOLE = {"material"}
OVERRIDES = "overrides"  # the source name of values set by a caller rather than a file
MAX_BASE_DEPTH = 5
NOTED_KEYS = {"value", "note", "range", "reason"}


@dataclasses.dataclass(frozen=True)
class Assumption:
    """A value the scene marks as assumed: ``field`` (dotted key), its ``value`` as written,
    the ``note`` and the file it came from."""

    field: str
    value: str
    note: str
    source: str
    range: tuple = ()  # (low, high) as written in the file, or () when no range is given
    reason: str = ""  # why the range is plausible


@dataclasses.dataclass(frozen=True)
class SceneSource:
    """Merged scene data with notes stripped, ``origin`` (dotted key -> file) and assumptions."""

    path: Path
    data: dict
    origin: dict[str, str]
    assumptions: tuple[Assumption, ...]

    def file_of(self, field: str) -> str:
        """The file a dotted key (or any key below it) came from; the scene file otherwise."""
        return file_of(self.origin, field, str(self.path))


def read_toml(path: Path) -> dict:
    """A TOML file as a dict; InputError (naming the file) when missing, unreadable or invalid.
    Parsed once while the file is unchanged; each call gets its own copy."""
    try:
        stat = path.stat()
    except OSError:
        return _parse_toml(path)  # not there (or unreadable): _parse_toml names the problem
    return copy.deepcopy(_parsed(str(path), stat.st_mtime_ns, stat.st_size))


@functools.lru_cache(maxsize=256)
def _parsed(path: str, mtime_ns: int, size: int) -> dict:
    """``_parse_toml`` of ``path`` as it was at (mtime_ns, size), the cache key."""
    return _parse_toml(Path(path))


def _parse_toml(path: Path) -> dict:
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise InputError("file not found", source=str(path)) from None
    except IsADirectoryError:
        raise InputError("is a folder, not a scene file", source=str(path)) from None
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror}", source=str(path)) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        raise InputError(f"not UTF-8 text (byte {exc.start}, line {line}): is this a scene file?",
                         source=str(path), expected="a TOML file in UTF-8") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", source=str(path)) from None


def _is_noted(value) -> bool:
    return isinstance(value, dict) and "value" in value


def merge(base: dict, top: dict) -> dict:
    """Deep-merge ``top`` over ``base``; ``top``'s keys win, REPLACED_WHOLE tables are replaced."""
    out = dict(base)
    for key, value in top.items():
        if (isinstance(value, dict) and not _is_noted(value) and isinstance(out.get(key), dict)
                and key not in REPLACED_WHOLE):
            out[key] = merge(out[key], value)
        else:
            out[key] = value
    return out


def _origins(data: dict, file: str, prefix: str = "") -> dict[str, str]:
    out = {}
    for key, value in data.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, dict) and not _is_noted(value):
            out.update(_origins(value, file, dotted + "."))
        else:
            out[dotted] = file
    return out


def _with_bases(path: Path, depth: int = 0) -> tuple[dict, dict]:
    if depth > MAX_BASE_DEPTH:
        raise InputError("base files nest too deeply (a loop?)", source=str(path), field="base")
    data = read_toml(path)
    base_name = data.pop("base", None)
    origin = _origins(data, str(path))
    if base_name is None:
        return data, origin
    if not isinstance(base_name, str):
        raise InputError(f"got {base_name!r}", source=str(path), field="base",
                         expected="a file name relative to this file, e.g. '_table2.toml'")
    base_data, base_origin = _with_bases(path.parent / base_name, depth + 1)
    # a table the scene replaces whole takes its origin from the scene alone
    kept = {k: v for k, v in base_origin.items()
            if not any(k == t or k.startswith(t + ".") for t in REPLACED_WHOLE if t in data)}
    return merge(base_data, data), {**kept, **origin}


def _set_dotted(data: dict, origin: dict, field: str, value) -> None:
    node = data
    parts = field.split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict) or _is_noted(node):
            raise InputError("cannot override inside a plain value", source=OVERRIDES, field=field)
    node[parts[-1]] = value
    origin[field] = OVERRIDES


def _range(node: dict, origin: dict, prefix: str) -> tuple:
    """The noted value's (low, high) as written, checked for shape; () without a range."""
    if "range" not in node:
        if "reason" in node:
            raise InputError("a reason without a range", source=origin.get(prefix),
                             field=f"{prefix}.reason", expected="range = [low, high] with it")
        return ()
    span, reason = node["range"], node.get("reason")
    if not (isinstance(span, list) and len(span) == 2):
        raise InputError(f"got {span!r}", source=origin.get(prefix), field=f"{prefix}.range",
                         expected="[low, high], each written like the value")
    if not (isinstance(reason, str) and reason.strip()):
        raise InputError("a range needs its reason", source=origin.get(prefix),
                         field=f"{prefix}.reason", expected="a text saying why the range is plausible")
    return tuple(span)


def _strip_notes(node, origin: dict, prefix: str, found: list[Assumption]):
    """``node`` with every ``{value, note}`` replaced by its value; assumed notes collected."""
    if _is_noted(node):
        extra = set(node) - NOTED_KEYS
        if extra:
            raise InputError(f"a noted value holds only {sorted(NOTED_KEYS)}, not {sorted(extra)}",
                             source=origin.get(prefix), field=prefix)
        span = _range(node, origin, prefix)
        note = node.get("note", "")
        if not isinstance(note, str):
            raise InputError(f"got {note!r}", source=origin.get(prefix), field=f"{prefix}.note",
                             expected="a text")
        if note.strip().lower().startswith("assumed"):
            found.append(Assumption(prefix, str(node["value"]), note.strip(),
                                    origin.get(prefix, ""), span, node.get("reason", "")))
        elif span:
            raise InputError("a range belongs to an assumed value", source=origin.get(prefix),
                             field=f"{prefix}.range", expected='a note starting "assumed"')
        return _strip_notes(node["value"], origin, prefix, found)
    if isinstance(node, dict):
        return {k: _strip_notes(v, origin, f"{prefix}.{k}" if prefix else k, found)
                for k, v in node.items()}
    if isinstance(node, list):
        return [_strip_notes(v, origin, f"{prefix}[{i}]", found) for i, v in enumerate(node)]
    return node


def read_scene_source(path: str | Path, overrides: dict | None = None) -> SceneSource:
    """Read ``path`` with its base files, apply ``overrides`` (dotted key -> value as written in
    a file) and strip the notes. The files are read once while they are unchanged
    (``_READ``); the overrides are applied to a copy (``overridden``)."""
    path = Path(path)
    key = str(path)
    known = _READ.get(key)
    if known is None or _stamps(known[0]) != known[1]:
        data, origin = _with_bases(path)
        found: list[Assumption] = []
        plain = _strip_notes(data, origin, "", found)
        unique = {(a.field, a.value): a for a in found}
        src = SceneSource(path=path, data=plain, origin=origin,
                          assumptions=tuple(unique.values()))
        files = tuple(sorted(set(origin.values()) | {key}))
        if len(_READ) >= 256:
            _READ.clear()
        # stamped after reading: a file changed while being read is read again next time
        known = _READ[key] = (files, _stamps(files), src)
    return overridden(known[2], overrides or {})


_READ: dict[str, tuple[tuple[str, ...], tuple, SceneSource]] = {}  # path -> (files, stamps, src)


def _stamps(files) -> tuple:
    """(modification time, size) of each file, None for one that is gone."""
    out = []
    for file in files:
        try:
            stat = Path(file).stat()
            out.append((stat.st_mtime_ns, stat.st_size))
        except OSError:
            out.append(None)
    return tuple(out)


def _covers(field: str, key: str) -> bool:
    """Whether overriding ``field`` replaces ``key`` (the same key or one inside it)."""
    return key == field or key.startswith(field + ".") or key.startswith(field + "[")


def overridden(src: SceneSource, overrides: dict) -> SceneSource:
    """``src`` with ``overrides`` applied, as ``read_scene_source(src.path, overrides)`` would
    give, without reading any file: for callers that vary a few keys of one scene many times
    (``load.load_overridden``). Only the tables on each overridden key's path are copied; an
    assumption whose value an override replaces is dropped, as re-reading would drop it."""
    if not overrides:
        return src
    data, origin = dict(src.data), dict(src.origin)
    found: list[Assumption] = []
    for field, value in overrides.items():
        node, parts = data, field.split(".")
        for part in parts[:-1]:
            inner = node.get(part, {})
            if not isinstance(inner, dict):
                raise InputError("cannot override inside a plain value", source=OVERRIDES,
                                 field=field)
            node[part] = node = dict(inner)
        node[parts[-1]] = _strip_notes(value, {field: OVERRIDES}, field, found)
        origin[field] = OVERRIDES
    kept = [a for a in src.assumptions if not any(_covers(f, a.field) for f in overrides)]
    unique = {(a.field, a.value): a for a in [*kept, *found]}
    return dataclasses.replace(src, data=data, origin=origin, assumptions=tuple(unique.values()))


def file_of(origin: dict[str, str], field: str, default: str) -> str:
    """The file a dotted key came from in ``origin`` (dotted key -> file): its own entry, else
    that of the first key below it (a table's file is that of its keys), else ``default``."""
    if field in origin:
        return origin[field]
    below = [f for f in origin if f.startswith(field + ".")]
    return origin[below[0]] if below else default
