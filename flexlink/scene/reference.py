"""Documents generated from the scene schema: the JSON Schema that TOML editors use for
completion and checking (``flexlink schema``), and the Markdown reference
``docs/scene-reference.md`` (a test fails when the committed file is stale)."""

from __future__ import annotations

import typing

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from flexlink.scene import schema

SCHEMA_ID = "https://flexlink.invalid/scene.schema.json"  # an identifier, not a download


def _noted(prop: dict) -> dict:
    """A property schema that also accepts ``{ value = ..., note = "..." }``, with an assumed
    value's optional ``range = [low, high]`` and ``reason``."""
    noted = {"type": "object", "properties": {
                 "value": prop, "note": {"type": "string"},
                 "range": {"type": "array", "items": prop, "minItems": 2, "maxItems": 2},
                 "reason": {"type": "string"}},
             "required": ["value"], "additionalProperties": False}
    keep = {k: prop[k] for k in ("description", "default", "title") if k in prop}
    return {**keep, "anyOf": [prop, noted]}


def _accept_notes(node: dict) -> dict:
    """``node`` (a value's schema) also accepting the noted form, at every level below it:
    properties, free-named keys, list items and each alternative of a choice. Tables ($ref)
    stay tables."""
    if not isinstance(node, dict) or "$ref" in node:
        return node
    inner = dict(node)
    for key in ("items", "additionalProperties"):
        if isinstance(inner.get(key), dict):
            inner[key] = _accept_notes(inner[key])
    if "prefixItems" in inner:
        inner["prefixItems"] = [_accept_notes(item) for item in inner["prefixItems"]]
    for key in ("anyOf", "oneOf"):
        if key in inner:
            inner[key] = [item if item.get("type") == "null" else _accept_notes(item)
                          for item in inner[key]]
    if "anyOf" in inner or "oneOf" in inner or inner.get("type") == "object":
        return inner
    return _noted(inner)


def json_schema() -> dict:
    """JSON Schema (2020-12) of a scene file; every value may also be a noted value."""
    doc = schema.SceneFile.model_json_schema()
    for definition in [doc, *doc.get("$defs", {}).values()]:
        props = definition.get("properties", {})
        for name, prop in props.items():
            props[name] = prop if name in ("type", "method") else _accept_notes(prop)
        if isinstance(definition.get("additionalProperties"), dict):
            definition["additionalProperties"] = _accept_notes(definition["additionalProperties"])
    doc["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    doc["$id"] = SCHEMA_ID
    doc["title"] = "flexlink scene"
    return doc


def _unit(annotation, metadata=()) -> schema.Unit | None:
    """The Unit metadata of a field (pydantic moves a required field's metadata out of its
    annotation into ``metadata``), of an optional one, or of a list's or dict's items."""
    for meta in metadata:
        if isinstance(meta, schema.Unit):
            return meta
    for tp in _alternatives(annotation, keep_annotated=True):
        if typing.get_origin(tp) is typing.Annotated:
            for meta in typing.get_args(tp)[1:]:
                if isinstance(meta, schema.Unit):
                    return meta
        if typing.get_origin(tp) in (list, tuple, dict):
            inner = _unit(typing.get_args(tp)[-1 if typing.get_origin(tp) is dict else 0])
            if inner:
                shape = "NAME = " if typing.get_origin(tp) is dict else "list, each "
                return schema.Unit(inner.kind, shape + inner.range)
    return None


def _alternatives(tp, keep_annotated=False) -> list:
    if typing.get_origin(tp) is typing.Annotated:
        inner = typing.get_args(tp)[0]
        if not keep_annotated or typing.get_origin(inner) in (typing.Union, typing.Annotated):
            return _alternatives(inner, keep_annotated)
        return [tp]
    if typing.get_origin(tp) in (typing.Union, __import__("types").UnionType):
        return [a for arg in typing.get_args(tp) if arg is not type(None)
                for a in _alternatives(arg, keep_annotated)]
    return [tp]


def _models(tp) -> list[tuple[str, type[BaseModel]]]:
    """(suffix, model) for tables reachable through ``tp``: "" for a table, ".NAME" for a
    table of named tables, "[[]]" for an array of tables."""
    out = []
    for alt in _alternatives(tp):
        if isinstance(alt, type) and issubclass(alt, BaseModel):
            out.append(("", alt))
        elif typing.get_origin(alt) is dict:
            out += [(".NAME" + s, m) for s, m in _models(typing.get_args(alt)[1])]
        elif typing.get_origin(alt) is list:
            out += [("[[]]" + s, m) for s, m in _models(typing.get_args(alt)[0])]
    return out


def _type_text(annotation) -> str:
    names = []
    for alt in _alternatives(annotation):
        origin = typing.get_origin(alt)
        if origin is typing.Literal:
            names.append(" or ".join(repr(v) for v in typing.get_args(alt)))
        elif origin in (list, tuple):
            names.append("list of " + ", ".join(_type_text(a) for a in typing.get_args(alt)
                                                if a is not Ellipsis))
        elif isinstance(alt, type):
            names.append({"str": "text", "bool": "true/false", "float": "number",
                          "int": "whole number", "list": "list"}.get(alt.__name__, alt.__name__))
        else:
            names.append("value")
    return " or ".join(names)


def _default_text(field) -> str:
    if field.is_required():
        return "required"
    value = field.default
    if value is None or value is PydanticUndefined or isinstance(value, BaseModel):
        return "-"
    if isinstance(value, float) and value == 0.0:
        return "0"
    return f"`{value!r}`" if value != [] else "none"


def _table_rows(model: type[BaseModel]) -> list[str]:
    rows = []
    for name, field in model.model_fields.items():
        if _models(field.annotation):
            continue  # sub-tables get their own section
        unit = _unit(field.annotation, field.metadata)
        kind = unit.kind if unit and unit.kind != "-" else _type_text(field.annotation)
        if unit and unit.kind == "-":
            kind = "number (no unit)"
        accepted = unit.range if unit else ""
        text = (field.description or "").replace("|", "\\|")
        rows.append(f"| `{name}` | {kind} | {accepted} | {_default_text(field)} | {text} |")
    return rows


def _sections(model: type[BaseModel], path: str, seen: set, out: list[str]):
    key = (path, model)
    if key in seen:
        return
    seen.add(key)
    title = f"[{path}]" if path else "top level"
    out += ["", f"### `{title}`" + (f" ({model.__name__})" if path.startswith("linkage")
                                    and model.__name__.endswith("Linkage") else ""), ""]
    if model.__doc__ and model is not schema.Table:
        out += [" ".join(model.__doc__.split()), ""]
    rows = _table_rows(model)
    if rows:
        out += ["| key | unit kind / type | accepted | default | meaning |",
                "|---|---|---|---|---|", *rows]
    for name, field in model.model_fields.items():
        for suffix, sub in _models(field.annotation):
            sub_path = f"{path}.{name}" if path else name
            if suffix.startswith("[[]]"):
                sub_path = f"[{sub_path}]"
            _sections(sub, sub_path + suffix.replace("[[]]", ""), seen, out)
    extra = schema.extra_type(model)
    if extra is not None:
        for suffix, sub in _models(extra):
            _sections(sub, f"{path}.NAME{suffix}", seen, out)


def reference_markdown() -> str:
    """The scene reference, generated from ``schema.py``."""
    out = ["# Scene file reference", "",
           "Generated from `flexlink/scene/schema.py` by `flexlink schema --markdown`; do not "
           "edit by hand (a test fails when this file is stale).", "",
           "Quantities are strings with a unit (`\"20 mm\"`, `\"1e6 N/m\"`); stiffnesses may "
           "be `\"rigid\"`. Any value may be written `{ value = ..., note = \"...\" }`; a note "
           "that starts with \"assumed\" lists the value among the scene's assumptions, and "
           "such a value may add `range = [low, high]` (written like the value) with the "
           "`reason` for it, used by `flexlink modes --sensitivity`. A key "
           "or table not listed here is an error. `base = \"file.toml\"` merges a shared file "
           "underneath (the scene's keys win; `[material]` is replaced whole)."]
    _sections(schema.SceneFile, "", set(), out)
    return "\n".join(out) + "\n"
