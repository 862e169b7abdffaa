"""Outputs compared by what they say, within a stated tolerance, not byte for byte.

Two runs of the same computation in two processes agree only to round-off: a BLAS kernel
chosen for another CPU, another thread count or another memory alignment sums in another
order, and an eigen solve passes that last bit on, amplified by its conditioning. So numbers
are compared relative to the scale of the array (or column) they belong to, text and integers
exactly, and a picture by what a reader sees: its size, and its pixels to within an
anti-aliased edge moved by one pixel.
"""

import csv
import io
import json
import math
import numbers
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

# Round-off of a float64 eigen solve and what is computed from its results, amplified by the
# conditioning of the case models (measured across BLAS thread counts: below 1e-12 relative
# on the shipped cases); 1e-9 leaves room for that and fails any change of physics.
RTOL = 1e-9
# Mean absolute difference of a picture's channels [0..255] allowed between two renderings of
# the same result: an edge moved by one pixel changes a few hundred of ~10^6 values by at most
# 255, about 0.1 on average; a different picture differs by tens.
PIXEL_TOLERANCE = 1.0


def _is_number(x) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


def _number_array(values) -> np.ndarray | None:
    """``values`` as a float array when it is a (nested) list of numbers, else None."""
    if not isinstance(values, (list, tuple)) or not values:
        return None
    try:
        array = np.asarray(values)
    except ValueError:  # ragged
        return None
    return array.astype(float) if array.dtype.kind in "iuf" else None


def mismatches(a, b, rtol: float = RTOL, path: str = "") -> list[str]:
    """Where ``a`` and ``b`` (JSON-like: dicts, lists, arrays, numbers, text) differ: text,
    integers, booleans and None exactly, floats to ``rtol`` of the largest magnitude of the
    array they sit in (a scalar: of itself). Empty when they agree."""
    where = path or "(top)"
    if isinstance(a, dict) or isinstance(b, dict):
        if not (isinstance(a, dict) and isinstance(b, dict)):
            return [f"{where}: {type(a).__name__} against {type(b).__name__}"]
        if set(a) != set(b):
            return [f"{where}: keys differ: {sorted(set(a) ^ set(b))}"]
        return [m for k in a for m in mismatches(a[k], b[k], rtol, f"{path}/{k}")]
    array_a, array_b = (x if isinstance(x, np.ndarray) else _number_array(x) for x in (a, b))
    if array_a is not None or array_b is not None:
        if array_a is None or array_b is None or array_a.shape != array_b.shape:
            return [f"{where}: arrays of different shapes or kinds"]
        if array_a.dtype.kind not in "iuf" or array_b.dtype.kind not in "iuf":
            return [] if np.array_equal(array_a, array_b) else [f"{where}: entries differ"]
        if array_a.dtype.kind in "iu" and array_b.dtype.kind in "iu":
            return [] if np.array_equal(array_a, array_b) else [f"{where}: integers differ"]
        finite = np.isfinite(array_a)
        if not np.array_equal(finite, np.isfinite(array_b)) or not np.array_equal(
                array_a[~finite], array_b[~finite], equal_nan=True):
            return [f"{where}: non-finite entries differ"]
        scale = np.abs(array_a[finite]).max(initial=0.0)
        gap = np.abs(array_a[finite] - array_b[finite]).max(initial=0.0)
        return [] if gap <= rtol * scale else [f"{where}: differ by {gap:.3g} (scale {scale:.3g})"]
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        if len(a) != len(b):
            return [f"{where}: {len(a)} entries against {len(b)}"]
        return [m for i, (x, y) in enumerate(zip(a, b)) for m in mismatches(x, y, rtol,
                                                                             f"{path}[{i}]")]
    if isinstance(a, float) or isinstance(b, float):
        if not (_is_number(a) and _is_number(b)):
            return [f"{where}: {a!r} against {b!r}"]
        if math.isfinite(a) and math.isfinite(b):
            close = abs(a - b) <= rtol * max(abs(a), abs(b))
        else:
            close = a == b or (math.isnan(a) and math.isnan(b))
        return [] if close else [f"{where}: {a!r} against {b!r}"]
    return [] if a == b else [f"{where}: {a!r} against {b!r}"]


def csv_columns(text: str) -> dict:
    """A CSV's comment lines and, per header name, its column: numbers as one array, else the
    cells as text."""
    lines = text.splitlines()
    comments = [line for line in lines if line.startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(l for l in lines if not l.startswith("#")))))
    if not rows:
        return {"comments": comments}
    header, body = rows[0], rows[1:]
    columns = {}
    for j, name in enumerate(header):
        cells = [row[j] if j < len(row) else "" for row in body]
        try:
            columns[name] = np.array([float(c) for c in cells])
        except ValueError:
            columns[name] = cells
    return {"comments": comments, "header": header, "columns": columns}


def _vtu(path: Path) -> dict:
    import meshio

    mesh = meshio.read(path)
    return {"points": mesh.points, "cells": {c.type: c.data for c in mesh.cells},
            "point_data": dict(mesh.point_data),
            "cell_data": {k: np.concatenate(v) for k, v in mesh.cell_data.items()},
            "field_data": dict(mesh.field_data)}


def _xml(text: str):
    """An XML file (a .pvd collection) as nested (tag, attributes, children), numeric
    attributes as floats."""
    def node(e):
        attributes = {}
        for k, v in e.attrib.items():
            try:
                attributes[k] = float(v)
            except ValueError:
                attributes[k] = v
        return {"tag": e.tag, "attributes": attributes, "children": [node(c) for c in e]}
    return node(ET.fromstring(text))


def _picture(path: Path) -> dict:
    from PIL import Image

    with Image.open(path) as image:
        image.load()
        return {"picture": np.asarray(image.convert("RGB"), dtype=float), "size": image.size}


def content(path: Path, replace: dict[str, str] | None = None):
    """What the file at ``path`` says, parsed by its kind (JSON, CSV, VTU, PVD, PNG; other
    files as text), with each key of ``replace`` in its text replaced by its value (a run's
    folder, which differs from run to run)."""
    if path.suffix == ".png":
        return _picture(path)
    if path.suffix == ".vtu":
        return _vtu(path)
    text = path.read_text()
    for old, new in (replace or {}).items():
        text = text.replace(old, new)
    if path.suffix == ".json":
        return json.loads(text)
    if path.suffix == ".csv":
        return csv_columns(text)
    if path.suffix in (".pvd", ".xml"):
        return _xml(text)
    return text


def folder_contents(folder: Path, replace: dict[str, str] | None = None) -> dict:
    """Every file under ``folder`` (relative path -> ``content``)."""
    return {str(p.relative_to(folder)): content(p, replace)
            for p in sorted(folder.rglob("*")) if p.is_file()}


def content_mismatches(a: dict, b: dict, rtol: float = RTOL) -> list[str]:
    """``mismatches`` of two ``folder_contents``, pictures compared by size and by their mean
    absolute pixel difference (``PIXEL_TOLERANCE``)."""
    if set(a) != set(b):
        return [f"files differ: {sorted(set(a) ^ set(b))}"]
    out = []
    for name in a:
        x, y = a[name], b[name]
        if isinstance(x, dict) and "picture" in x:
            if not (isinstance(y, dict) and "picture" in y) or x["size"] != y["size"]:
                out.append(f"{name}: pictures of different sizes")
            elif (gap := np.abs(x["picture"] - y["picture"]).mean()) > PIXEL_TOLERANCE:
                out.append(f"{name}: pixels differ by {gap:.3g} on average")
            continue
        out += mismatches(x, y, rtol, name)
    return out
