"""Documents generated from the scene schema: the JSON Schema that TOML editors use for
completion and checking (``flexlink schema``), and the Markdown reference
``docs/scene-reference.md`` (a test fails when the committed file is stale)."""

from __future__ import annotations

import enum
import typing

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from flexlink.scene import schema

SCHEMA_ID = "https://flexlink.invalid/scene.schema.json"  # an identifier, not a download


def _noted(prop: dict) -> dict:
    """A property schema that also accepts ``{ value = ..., note = "..." }``, with an assumed
    value's optional ``range = [low, high]`` and ``reason``. A table picks the noted form and
    anything else the plain one (if/then/else, not anyOf), so an editor's message is the
    plain value's own ("does not match pattern") or names the noted table's stray key."""
    noted = {"type": "object", "properties": {
                 "value": prop, "note": {"type": "string"},
                 "range": {"type": "array", "items": prop, "minItems": 2, "maxItems": 2},
                 "reason": {"type": "string"}},
             "required": ["value"], "additionalProperties": False}
    keep = {k: prop[k] for k in ("description", "default", "title") if k in prop}
    plain = {k: v for k, v in prop.items() if k not in keep}
    return {**keep, "if": {"type": "object"}, "then": noted, "else": plain}


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
    if "properties" in inner:
        inner["properties"] = {name: prop if name in ("type", "method") else _accept_notes(prop)
                               for name, prop in inner["properties"].items()}
    for key in ("anyOf", "oneOf"):
        if key in inner:
            inner[key] = [_accept_notes(item) for item in inner[key]]
    if "anyOf" in inner or "oneOf" in inner or inner.get("type") == "object":
        return inner
    return _noted(inner)


def _table(node: dict, defs: dict) -> dict | None:
    """The object schema ``node`` is or refers to; None when it is not a table."""
    if "$ref" in node:
        node = defs[node["$ref"].rsplit("/", 1)[1]]
    return node if node.get("type") == "object" and "properties" in node else None


def _merged(tables: list[dict]) -> dict:
    """One table holding every key of ``tables`` (the kinds of a choice such as [linkage]):
    the tag (``type``, ``method``) lists every kind, a key the kinds declare differently takes
    any of its forms. An editor then names a misspelt key instead of saying that no kind
    matched; which keys go with which kind is flexlink's own check."""
    properties: dict[str, dict] = {}
    for table in tables:
        for name, prop in table["properties"].items():
            if name not in properties:
                properties[name] = prop
            elif "const" in prop or "enum" in properties[name]:
                tags = properties[name].get("enum", [properties[name].get("const")])
                properties[name] = {"enum": [*tags, prop["const"]], "type": "string",
                                    **{k: v for k, v in properties[name].items()
                                       if k in ("description", "default")}}
            elif prop != properties[name]:
                forms = properties[name].get("anyOf", [properties[name]])
                properties[name] = {"anyOf": [*forms, prop]}
    return {"type": "object", "properties": properties, "additionalProperties": False}


def _for_editors(node, defs: dict):
    """``node`` as an editor can check it: no ``required`` (a base file may hold any key, and
    an editor cannot follow ``base``), no null alternatives (TOML has no null), each choice of
    tables merged into one table (``_merged``), and pairs of like values as plain ``items``."""
    if isinstance(node, list):
        return [_for_editors(item, defs) for item in node]
    if not isinstance(node, dict):
        return node
    out = {k: _for_editors(v, defs) for k, v in node.items()
           if k not in ("required", "discriminator")}
    for key in ("anyOf", "oneOf"):
        if key not in out:
            continue
        alternatives = [a for a in out.pop(key) if a != {"type": "null"}]
        tables = [_table(a, defs) for a in alternatives]
        if len(alternatives) > 1 and all(tables):
            alternatives = [_merged([_for_editors(t, defs) for t in tables])]
        if len(alternatives) == 1:
            out = {**alternatives[0], **{k: v for k, v in out.items() if k != "default"
                                         or v is not None}}
        else:
            out[key] = alternatives
    if out.get("default", 0) is None:
        del out["default"]
    prefix = out.get("prefixItems")
    if prefix and all(item == prefix[0] for item in prefix) and "items" not in out:
        # a pair of like values ([x, y]): one items schema, which editors that predate
        # prefixItems (taplo) also check
        out["items"] = out.pop("prefixItems")[0]
    return out


def _used(doc: dict) -> set[str]:
    """Names of the $defs that ``doc`` refers to, directly or through other $defs."""
    defs, seen, todo = doc.get("$defs", {}), set(), [doc]
    while todo:
        node = todo.pop()
        if isinstance(node, dict):
            ref = node.get("$ref", "")
            name = ref.rsplit("/", 1)[1] if ref.startswith("#/$defs/") else None
            if name and name not in seen:
                seen.add(name)
                todo.append(defs[name])
            todo += [v for k, v in node.items() if k != "$defs"]
        elif isinstance(node, list):
            todo += node
    return seen


def _four_bar_names() -> dict:
    """What a four-bar scene's free-named keys may be: its links and joints (``fourbar.LINKS``).
    A general scene names its own, which an editor cannot check."""
    from flexlink.scene.fourbar import LINKS

    links = [name for name, *_ in LINKS]
    joints = list(dict.fromkeys(j for _, *ends in LINKS for j in ends))
    shared = list(schema.JointsTable.model_fields)
    return {"properties": {
        "links": {"propertyNames": {"enum": links}},
        "joints": {"propertyNames": {"enum": shared + joints}},
        "drive": {"properties": {"link": {"enum": links}, "joint": {"enum": joints}}}}}


def json_schema() -> dict:
    """JSON Schema (2020-12) of a scene file for TOML editors: every value may also be a noted
    value, every key is optional (a base file may supply it), quantities are checked as a
    number and a unit (``units.quantity_pattern``), and a four-bar's links and joints are
    checked by name."""
    raw = schema.SceneFile.model_json_schema()
    defs = raw.get("$defs", {})
    doc = _for_editors(raw, defs)
    doc = _accept_notes(doc)
    doc["$defs"] = {name: _accept_notes(table) for name, table in doc["$defs"].items()}
    used = _used(doc)
    doc["$defs"] = {k: v for k, v in doc["$defs"].items() if k in used}
    general = {"properties": {"linkage": {"properties": {"type": {"const": "general"}},
                                          "required": ["type"]}},
               "required": ["linkage"]}
    doc.update({"if": general, "else": _four_bar_names()})
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
            names.append(" or ".join(repr(str(v)) for v in typing.get_args(alt)))
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
    needed = (field.json_schema_extra or {}).get("needed")
    if needed:
        return f"required ({needed})"
    value = field.default
    if value is None or value is PydanticUndefined or isinstance(value, BaseModel):
        return "-"
    if isinstance(value, float) and value == 0.0:
        return "0"
    if isinstance(value, enum.StrEnum):
        value = value.value
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
        accepted = _accepted(field, unit)
        text = (field.description or "").replace("|", "\\|")
        rows.append(f"| `{name}` | {kind} | {accepted} | {_default_text(field)} | {text} |")
    return rows


def _tag_text(model: type[BaseModel]) -> str:
    """" (type = 'general')" for one kind of a choice of tables, "" for a plain table."""
    for name in ("type", "method"):
        field = model.model_fields.get(name)
        if field is not None and typing.get_origin(field.annotation) is typing.Literal:
            return f" ({name} = {str(typing.get_args(field.annotation)[0])!r})"
    return ""


def _accepted(field, unit) -> str:
    """The "accepted" column: the unit's range, and a list's least length."""
    shortest = [m.min_length for m in field.metadata if type(m).__name__ == "MinLen"]
    text = unit.range if unit else ""
    if shortest:
        text += ("; " if text else "") + f"at least {shortest[0]} item{'s' if shortest[0] > 1 else ''}"
    return text


def _sections(model: type[BaseModel], path: str, seen: set, out: list[str]):
    key = (path, model)
    if key in seen:
        return
    seen.add(key)
    title = f"[{path}]" if path else "top level"
    out += ["", f"### `{title}`" + _tag_text(model), ""]
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


def _materials_text() -> list[str]:
    """The shipped materials, as ``isotropic = "NAME"`` and a composite's ``fiber``/``matrix``
    take them, with the values their files hold."""
    from flexlink.materials.mixtures import load_constituent, shipped_names

    rows = []
    for name in shipped_names():
        c = load_constituent(name)
        rows.append(f"| `{name}` | {c.E / 1e9:g} GPa | {c.G / 1e9:g} GPa | {c.density:g} kg/m^3 |")
    return ["Shipped materials (`isotropic = \"NAME\"`, or a composite's `fiber` and `matrix`; "
            "any other material is a path to a .toml file of the same form, or `E` and "
            "`density`):", "", "| name | E | G | density |", "|---|---|---|---|", *rows]


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
           "underneath (the scene's keys win; `[material]` is replaced whole).", "",
           *_materials_text()]
    _sections(schema.SceneFile, "", set(), out)
    return "\n".join(out) + "\n"
