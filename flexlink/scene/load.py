"""Loading a scene file: read (``source.py``), validate against the declared schema
(``schema.py``), build the one ``Scene`` contract through the builder of the scene's kind, and
check plausibility. Every error is an InputError naming the file, the key path and what would be
accepted; a key or table the schema does not declare is an error with the nearest valid names."""

from __future__ import annotations

import dataclasses
import types
import typing
from pathlib import Path

import pydantic
from pydantic import BaseModel

from flexlink.errors import InputError
from flexlink.scene import fourbar, general, parts, schema
from flexlink.scene.contract import Scene, SceneKind
from flexlink.scene.kinetostatics import build_kinetostatics
from flexlink.scene.loads import build_loads
from flexlink.scene.plausibility import check_scene
from flexlink.scene.source import SceneSource, overridden, read_scene_source

BUILDERS = {SceneKind.FOUR_BAR: fourbar.build_four_bar, SceneKind.GENERAL: general.build_general}


def _members(tp) -> list:
    """The non-None alternatives of an annotation, Annotated and Optional unwrapped."""
    while typing.get_origin(tp) is typing.Annotated:
        tp = typing.get_args(tp)[0]
    if typing.get_origin(tp) in (typing.Union, types.UnionType):
        out = []
        for arg in typing.get_args(tp):
            if arg is not type(None):
                out += _members(arg)
        return out
    return [tp]


def _tag(cls) -> str | None:
    """The word (``type = ...``, ``method = ...``) that picks ``cls`` among the alternatives
    of a choice of tables, as written in a file; None for a plain table."""
    for name in ("type", "method"):
        field = cls.model_fields.get(name)
        if field is not None and typing.get_origin(field.annotation) is typing.Literal:
            return str(typing.get_args(field.annotation)[0])
    return None


def _walk(loc) -> tuple[list[str], list]:
    """The dotted-path parts of a pydantic error location (union tags dropped) and the types
    the last part may hold (models, dict or list types)."""
    current, path = [schema.SceneFile], []
    for item in loc:
        models = [t for t in current if isinstance(t, type) and issubclass(t, BaseModel)]
        tagged = {_tag(m): m for m in models if _tag(m)}
        if isinstance(item, str) and item in tagged and len(models) > 1:
            current = [tagged[item]]
            continue
        nxt = []
        for t in current:
            if isinstance(t, type) and issubclass(t, BaseModel):
                if isinstance(item, str) and item in t.model_fields:
                    nxt += _members(t.model_fields[item].annotation)
                elif schema.extra_type(t) is not None:
                    nxt += _members(schema.extra_type(t))
            elif typing.get_origin(t) is dict:
                nxt += _members(typing.get_args(t)[1])
            elif typing.get_origin(t) in (list, tuple):
                args = typing.get_args(t)
                nxt += _members(args[0] if args else typing.Any)
        if isinstance(item, int):
            path[-1] = f"{path[-1]}[{item}]" if path else f"[{item}]"
        else:
            path.append(str(item))
        current = nxt
    return path, current


def _declared(path_types: list) -> list[str]:
    names = []
    for t in path_types:
        if isinstance(t, type) and issubclass(t, BaseModel):
            names += [n for n in t.model_fields if n not in names]
    return names


def _other_kinds(loc, key: str) -> list[str]:
    """The tags (``type = ...``) of the other alternatives of the tagged table at ``loc`` that
    declare ``key``: a key of a general linkage written in a four-bar, say."""
    if len(loc) < 2:
        return []
    _, alternatives = _walk(loc[:-1])
    models = [t for t in alternatives if isinstance(t, type) and issubclass(t, BaseModel)]
    return [_tag(m) for m in models if _tag(m) and _tag(m) != loc[-1] and key in m.model_fields]


def _problem(src: SceneSource, error: dict) -> tuple[str, str]:
    """(dotted field, message) of one pydantic error."""
    loc = error["loc"]
    kind = error["type"]
    if kind in ("extra_forbidden", "model_type", "dict_type") and loc:
        parent_path, parent_types = _walk(loc[:-1])
        names = _declared(parent_types)
        key = str(loc[-1])
        if kind == "extra_forbidden" or key not in names:
            dotted = ".".join(parent_path + [key])
            if isinstance(error.get("input"), dict):
                prefix = "".join(f"{p}." for p in parent_path)
                return f"[{dotted}]", f"unknown table{parts.near(key, names, fmt='[' + prefix + '{}]')}"
            kinds = _other_kinds(loc[:-1], key)
            if kinds:
                tag = loc[-2]
                return dotted, (f"unknown key for {_tag_name(parent_types)} = {tag!r}: {key!r} "
                                f"belongs to {_tag_name(parent_types)} = {kinds[0]!r}")
            return dotted, f"unknown key{parts.near(key, names)}"
    path, _ = _walk(loc)
    dotted = ".".join(path) or "scene"
    message = error["msg"]
    cause = error.get("ctx", {}).get("error")
    if isinstance(cause, schema.MissingKey):
        dotted = f"{dotted}.{cause.key}" if dotted != "scene" else cause.key
        message = "missing" + (f" ({cause.hint})" if cause.hint else "")
    elif isinstance(cause, schema.ClashingKey):
        dotted, message = f"{dotted}.{cause.key}", cause.reason
    elif isinstance(cause, schema.UnknownKey):
        dotted = f"{dotted}.{cause.key}"
        near = parts.near(cause.key, cause.known)
        message = "unknown key" + (near if near.startswith("; did") else "") + (
            f" ({cause.hint})" if cause.hint else "")
    elif kind == "value_error":
        message = message.removeprefix("Value error, ")
    elif kind == "missing":
        message = "missing"
    elif kind == "union_tag_invalid":
        ctx = error.get("ctx", {})
        _, alternatives = _walk(loc)
        tags = ", ".join(repr(_tag(m)) for m in alternatives if _tag(m))
        message = (f"unknown {ctx.get('discriminator', 'kind').strip(chr(39))} "
                   f"{ctx.get('tag')!r} (expected one of {tags})")
    elif kind == "union_tag_not_found":
        message = "missing 'type' (or 'method')"
    else:
        message = f"got {error.get('input')!r}: {message}"
    return dotted, message


def _tag_name(models) -> str:
    """'type' or 'method': the key that picks an alternative among ``models``."""
    for m in models:
        for name in ("type", "method"):
            if name in getattr(m, "model_fields", {}):
                return name
    return "type"


def _input_error(src: SceneSource, errors: list[dict]) -> InputError:
    """One InputError for every problem pydantic found: the first names its file and field,
    the others follow on the same line, each with its own field and hint; unknown keys come
    first, as the missing key beside one is usually its misspelling."""
    problems = list(dict.fromkeys(_problem(src, e) for e in errors))
    problems.sort(key=lambda p: "unknown" not in p[1])
    (field, message), rest = problems[0], problems[1:]
    source = src.file_of(field[1:-1] if field.startswith("[") else field)
    if rest:
        also = "; ".join(f"{f}: {m}" for f, m in rest)
        message += f" (and {len(rest)} more problem{'s' if len(rest) > 1 else ''}: {also})"
    return InputError(message, source=source, field=field)


def validate(src: SceneSource) -> schema.SceneFile:
    """The scene data checked against the schema; the first problem as an InputError."""
    data = dict(src.data)
    linkage = data.get("linkage")
    if isinstance(linkage, dict) and "type" not in linkage:
        data["linkage"] = {"type": SceneKind.FOUR_BAR.value, **linkage}  # the default kind
    try:
        return schema.SceneFile.model_validate(data)
    except pydantic.ValidationError as exc:
        raise _input_error(src, exc.errors()) from None


def load_scene(path: str | Path, overrides: dict | None = None) -> Scene:
    """Read, validate and build a scene file (and its base). Raises InputError naming file and
    field.

    ``overrides`` maps dotted keys to values as they would be written in the file, e.g.
    ``{"section.width": "25 mm", "joints.Kt": "1e7 N/m"}``: sweeps, calibration and Monte Carlo
    vary inputs this way, through the same validation as a file."""
    return load_overridden(read_scene_source(path), overrides)


def load_overridden(src: SceneSource, overrides: dict | None = None) -> Scene:
    """``load_scene`` from an already read scene (``source.read_scene_source``): the overrides
    are applied to the read data (``source.overridden``), then validated and built exactly as
    from a file, so a caller varying inputs reads each file once."""
    src = overridden(src, overrides or {})
    sf = validate(src)
    scene = BUILDERS[sf.linkage.type](src, sf)
    if sf.loads:
        scene = dataclasses.replace(scene, loads=build_loads(src, sf, scene.linkage))
    if sf.kinetostatics is not None:
        scene = dataclasses.replace(scene, kinetostatics=build_kinetostatics(
            src, sf.kinetostatics, scene.linkage, scene.transmission, scene.loads))
    check_scene(scene)  # unit slips such as "300 m" for "300 mm" (plausibility.py)
    return scene


def scene_files(paths) -> list[Path]:
    """Expand files and folders into scene files (folders: *.toml not starting with '_')."""
    out = []
    for p in map(Path, paths):
        if p.is_dir():
            found = sorted(f for f in p.glob("*.toml") if not f.name.startswith("_"))
            if not found:
                bases = sorted(f.name for f in p.glob("_*.toml"))
                raise InputError(
                    f"folder holds only base files ({', '.join(bases)}): a name starting with "
                    "'_' marks a file other scenes merge underneath (base = '...'), never run "
                    "alone" if bases else "folder holds no scene files (*.toml)", source=str(p),
                    expected="a scene file not starting with '_'" if bases else None)
            out.extend(found)
        elif p.is_file():
            out.append(p)
        else:
            raise InputError("no such scene file or folder", source=str(p))
    return out
