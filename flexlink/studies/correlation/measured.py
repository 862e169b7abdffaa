"""A modal test read from a file: sensor points, measuring directions, real mode shapes, and
each mode's frequency and damping.

Two formats, one reader each behind ``READERS`` (chosen by the file's suffix):

- Universal File Format (``.uff``, ``.unv``), read by pyuff (flexlink has no UFF parser of its
  own): dataset 55 (data at nodes), one per mode, normal modes (analysis type 2) or complex
  modes (3, 7); the test geometry from dataset 15 or 2411; the length unit from dataset 164
  when present. A 55 dataset holds X, Y, Z per node (data characteristic 2, or the first three
  of 6); a direction that reads zero in every mode was not measured and makes no channel (the
  format writes zeros for DOFs it does not have). Complex shapes are turned real by the phase
  of their largest entry; their frequency is |lambda| / 2 pi and damping -Re(lambda) / |lambda|.
- CSV (``.csv``): a header ``sensor, x [unit], y [unit], z [unit], dx, dy, dz, <mode>...``,
  then a row ``frequency [Hz]`` and optionally a row ``damping`` (viscous ratio) with values
  under the mode columns only, then one row per channel: its sensor, the sensor's position,
  its measuring direction (normalised here) and the shape's value in each mode. A sensor with
  several directions takes several rows.

Each problem is an InputError naming the file and the dataset or row and column: no dataset
55, a shape that is zero at every channel, a node without geometry, a binary or truncated file,
a cell that is not a number.
"""

from __future__ import annotations

import csv
import dataclasses
import io
import math
import re
from pathlib import Path

import numpy as np

from flexlink.errors import InputError
from flexlink.scene.contract import ModalTestFrame
from flexlink.studies.array_shapes import check_shape
from flexlink.units import UNITS

AXES = ("X", "Y", "Z")
GEOMETRY_SETS = (15, 2411)
UNIT_MATCH = 1e-6  # relative: a file's 1000.0 per metre is mm


@dataclasses.dataclass(frozen=True)
class ModalTest:
    """A modal test as read. ``labels`` (P,) name the sensor points (UFF node numbers, CSV
    sensor names); ``coordinates`` (P, 3) in the file's unit; ``metres_per_unit`` that unit
    [m] as the file states it, None where it states none, with ``unit_field`` saying where it
    did (e.g. "dataset 164 length"); ``channel_point`` (C,) indexes ``labels``;
    ``channel_direction`` (C, 3) unit vectors in the test's frame; ``shapes`` (C, k) real;
    ``frequencies`` (k,) [Hz]; ``damping`` (k,) viscous ratios [-], NaN where not given;
    ``mode_fields`` (k,) where each mode came from (dataset number or column)."""

    source: str
    labels: tuple[str, ...]
    coordinates: np.ndarray
    metres_per_unit: float | None
    unit_field: str
    channel_point: np.ndarray
    channel_direction: np.ndarray
    shapes: np.ndarray
    frequencies: np.ndarray
    damping: np.ndarray
    mode_fields: tuple[str, ...]

    def __post_init__(self):
        p, (c, k) = len(self.labels), np.shape(self.shapes)
        check_shape("ModalTest", "coordinates", self.coordinates, (p, 3))
        check_shape("ModalTest", "channel_point", self.channel_point, (c,))
        check_shape("ModalTest", "channel_direction", self.channel_direction, (c, 3))
        for name in ("frequencies", "damping"):
            check_shape("ModalTest", name, getattr(self, name), (k,))
        if len(self.mode_fields) != k:
            raise ValueError(f"ModalTest.mode_fields has {len(self.mode_fields)} entries, "
                             f"expected {k}")
        for j in range(k):
            if not np.any(self.shapes[:, j]):
                raise InputError("the mode shape is zero at every channel", source=self.source,
                                 field=self.mode_fields[j],
                                 expected="a measured mode shape")
            if not (math.isfinite(self.frequencies[j]) and self.frequencies[j] > 0):
                raise InputError(f"frequency {self.frequencies[j]!r} Hz", source=self.source,
                                 field=self.mode_fields[j], expected="a frequency > 0 Hz")

    @property
    def n_modes(self) -> int:
        return self.shapes.shape[1]

    def channel_names(self) -> tuple[str, ...]:
        """"<sensor> <axis>" per channel (the axis: X, Y, Z for a file axis, else dx,dy,dz)."""
        out = []
        for p, d in zip(self.channel_point, self.channel_direction):
            axis = [a for a, v in zip(AXES, d) if v != 0]
            name = f"+{axis[0]}" if len(axis) == 1 and d[AXES.index(axis[0])] > 0 else (
                f"-{axis[0]}" if len(axis) == 1 else "(" + ",".join(f"{v:.3g}" for v in d) + ")")
            out.append(f"{self.labels[p]} {name}")
        return tuple(out)

    def metres_in_scene(self, frame: ModalTestFrame, scene_path: str) -> float:
        """The file's length unit [m]: the scene's [test] unit, which must agree with the
        unit the file states; the file's own when the scene declares none."""
        declared = UNITS["length"][frame.unit] if frame.unit else None
        if declared is not None and self.metres_per_unit is not None:
            if abs(declared / self.metres_per_unit - 1.0) > UNIT_MATCH:
                raise InputError(
                    f"the file's length unit is {self.metres_per_unit:g} m but the scene's "
                    f"[test] unit is '{frame.unit}' ({scene_path})", source=self.source,
                    field=self.unit_field, expected=f"coordinates in '{frame.unit}', or "
                                                    "[test] unit set to the file's")
        if declared is None and self.metres_per_unit is None:
            raise InputError("the file states no length unit", source=self.source,
                             field=self.unit_field,
                             expected=f"test.unit in the scene ({scene_path}), e.g. 'mm'")
        return declared if declared is not None else self.metres_per_unit


def _check_text(path: Path) -> str:
    """The file's text; a binary file (NUL bytes, not UTF-8) is refused."""
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", source=str(path)) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"binary content at byte {exc.start}", source=str(path),
                         field="file", expected="a text (ASCII) file") from None
    if "\0" in text:
        raise InputError(f"binary content at byte {text.index(chr(0))}", source=str(path),
                         field="file", expected="a text (ASCII) file")
    return text


def _real_shape(values: np.ndarray) -> np.ndarray:
    """A complex shape turned real by the phase of its largest entry."""
    if not np.iscomplexobj(values):
        return values.astype(float)
    flat = values.ravel()
    phase = flat[np.argmax(np.abs(flat))] / abs(flat[np.argmax(np.abs(flat))])
    return (values / phase).real


def _uff_sets(path: Path) -> list[tuple[int, dict]]:
    """(dataset number (1-based, file order), pyuff's dict) of every dataset pyuff reads."""
    import pyuff

    text = _check_text(path)
    markers = sum(1 for line in text.splitlines() if line.strip() == "-1")
    if markers == 0:
        raise InputError("no UFF datasets (no '    -1' delimiters)", source=str(path),
                         field="file", expected="a Universal File Format file")
    if markers % 2:
        raise InputError(f"truncated: {markers} dataset delimiters, the last dataset is not "
                         "closed", source=str(path), field=f"dataset {markers // 2 + 1}",
                         expected="each dataset between two '    -1' lines")
    try:
        uff = pyuff.UFF(str(path))
        types, formats = uff.get_set_types(), uff.get_set_formats()
    except Exception as exc:  # pyuff raises bare Exceptions
        raise InputError(f"pyuff cannot read it: {exc}", source=str(path), field="file") from None
    out = []
    for i, (kind, form) in enumerate(zip(types, formats)):
        if form:
            raise InputError(f"dataset {kind} is in binary form", source=str(path),
                             field=f"dataset {i + 1}", expected="ASCII datasets")
        try:
            dset = uff.read_sets(i)
        except Exception as exc:
            raise InputError(f"pyuff cannot read dataset {kind}: {exc}", source=str(path),
                             field=f"dataset {i + 1}") from None
        out.append((i + 1, dset))
    return out


def _uff_geometry(path: Path, sets) -> dict[int, np.ndarray]:
    nodes: dict[int, np.ndarray] = {}
    for number, dset in sets:
        if dset.get("type") not in GEOMETRY_SETS:
            continue
        xyz = np.column_stack([dset["x"], dset["y"], dset["z"]]).astype(float)
        for label, point in zip(np.asarray(dset["node_nums"]).astype(int), xyz):
            if label in nodes and not np.allclose(nodes[label], point):
                raise InputError(f"node {label} has two positions", source=str(path),
                                 field=f"dataset {number} ({dset['type']})",
                                 expected="one position per node")
            nodes[label] = point
    return nodes


def _uff_unit(path: Path, sets) -> tuple[float | None, str]:
    units = [(n, d) for n, d in sets if d.get("type") == 164]
    if not units:
        return None, "dataset 164"
    number, dset = units[0]
    factor = float(dset["length"])  # UFF: file units per SI unit
    if not (math.isfinite(factor) and factor > 0):
        raise InputError(f"length factor {factor!r}", source=str(path),
                         field=f"dataset {number} (164) length", expected="a factor > 0")
    return 1.0 / factor, f"dataset {number} (164) length"


def _uff_mode(path: Path, number: int, dset: dict):
    """(node labels, values (nodes, 3), frequency [Hz], damping ratio) of one 55 dataset."""
    field = f"dataset {number} (55)"
    kind, character = dset.get("analysis_type"), dset.get("data_ch")
    if character not in (2, 3):
        raise InputError(f"data characteristic {character}: no measuring directions",
                         source=str(path), field=f"{field} data_ch",
                         expected="2 (X, Y, Z per node) or 3 (X, Y, Z, RX, RY, RZ)")
    values = np.column_stack([dset["r1"], dset["r2"], dset["r3"]])
    if kind == 2:
        frequency = float(dset["freq"])
        damping = float(dset.get("modal_damp_vis", 0.0)) or float(
            dset.get("modal_damp_his", 0.0)) / 2.0  # loss factor eta = 2 zeta
    elif kind in (3, 7):
        eig = complex(dset["eig"])
        frequency, damping = abs(eig) / (2 * math.pi), -eig.real / abs(eig)
    else:
        raise InputError(f"analysis type {kind} is not a mode", source=str(path),
                         field=f"{field} analysis_type",
                         expected="2 (normal mode) or 3, 7 (complex mode)")
    return np.asarray(dset["node_nums"]).astype(int), _real_shape(values), frequency, damping


def read_uff(path) -> ModalTest:
    """A modal test from a UFF file (module docstring)."""
    path = Path(path)
    sets = _uff_sets(path)
    modes = [(n, d) for n, d in sets if d.get("type") == 55]
    if not modes:
        found = ", ".join(str(d.get("type")) for _, d in sets) or "none"
        raise InputError(f"no dataset 55 (mode shapes); datasets found: {found}",
                         source=str(path), field="dataset 55",
                         expected="one dataset 55 per measured mode")
    geometry = _uff_geometry(path, sets)
    if not geometry:
        raise InputError("no test geometry", source=str(path), field="dataset 15",
                         expected="node coordinates in dataset 15 or 2411")
    read = [_uff_mode(path, n, d) for n, d in modes]
    labels = sorted({int(x) for nodes, *_ in read for x in nodes})
    for (number, _), (nodes, *_) in zip(modes, read):
        missing = sorted(set(nodes.tolist()) - set(geometry))
        if missing:
            raise InputError(f"node {missing[0]} has no coordinates", source=str(path),
                             field=f"dataset {number} (55) node {missing[0]}",
                             expected="every node of a dataset 55 in dataset 15 or 2411")
    row = {label: i for i, label in enumerate(labels)}
    full = np.zeros((len(labels), 3, len(read)))
    for j, (nodes, values, _, _) in enumerate(read):
        full[[row[n] for n in nodes], :, j] = values
    point, axis = np.nonzero(np.any(full != 0, axis=2))  # measured: non-zero in some mode
    metres, unit_field = _uff_unit(path, sets)
    return ModalTest(
        source=str(path), labels=tuple(str(x) for x in labels),
        coordinates=np.array([geometry[x] for x in labels]), metres_per_unit=metres,
        unit_field=unit_field, channel_point=point, channel_direction=np.eye(3)[axis],
        shapes=full[point, axis, :], frequencies=np.array([f for *_, f, _ in read]),
        damping=np.array([z for *_, z in read]),
        mode_fields=tuple(f"dataset {n} (55)" for n, _ in modes))


_HEADER_UNIT = re.compile(r"^\s*(?P<name>[^\[]*?)\s*(?:\[(?P<unit>[^\]]*)\])?\s*$")
CSV_POSITION = ("x", "y", "z")
CSV_DIRECTION = ("dx", "dy", "dz")


def _number(path: Path, text: str, row: int, column: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"got {text!r}", source=str(path), field=f"row {row}, column {column!r}",
                         expected="a number") from None
    if not math.isfinite(value):
        raise InputError(f"got {text!r}", source=str(path), field=f"row {row}, column {column!r}",
                         expected="a finite number")
    return value


def _csv_unit(path: Path, header: list[str]) -> tuple[float | None, str]:
    units = {}
    for cell in header[1:4]:
        unit = (_HEADER_UNIT.match(cell)["unit"] or "").strip()
        if unit:
            if unit not in UNITS["length"]:
                raise InputError(f"unknown length unit {unit!r}", source=str(path),
                                 field=f"column {cell!r}",
                                 expected=f"one of {', '.join(UNITS['length'])}")
            units[cell] = unit
    if len(set(units.values())) > 1:
        raise InputError(f"the coordinates have different units ({', '.join(units)})",
                         source=str(path), field="header", expected="one length unit for x, y, z")
    if not units:
        return None, "header 'x [unit]'"
    cell, unit = next(iter(units.items()))
    return UNITS["length"][unit], f"column {cell!r}"


def read_csv(path) -> ModalTest:
    """A modal test from a CSV file (module docstring)."""
    path = Path(path)
    rows = list(csv.reader(io.StringIO(_check_text(path))))
    rows = [(i + 1, r) for i, r in enumerate(rows) if r and any(c.strip() for c in r)]
    if not rows:
        raise InputError("empty file", source=str(path), field="header")
    (_, header), body = rows[0], rows[1:]
    names = [(_HEADER_UNIT.match(c)["name"] or "").strip().lower() for c in header]
    if names[:7] != ["sensor", *CSV_POSITION, *CSV_DIRECTION] or len(header) < 8:
        raise InputError(f"header {','.join(header)!r}", source=str(path), field="header",
                         expected="sensor, x [unit], y [unit], z [unit], dx, dy, dz, then one "
                                  "column per mode")
    modes = [c.strip() for c in header[7:]]
    k = len(modes)
    frequencies = damping = None
    labels, coordinates, point, direction, values = [], [], [], [], []
    for number, r in body:
        if len(r) != len(header):
            raise InputError(f"{len(r)} cells, the header has {len(header)}", source=str(path),
                             field=f"row {number}", expected="complete rows (is the file cut short?)")
        first = (_HEADER_UNIT.match(r[0])["name"] or "").strip().lower()
        if first in ("frequency", "damping"):
            row_values = np.array([_number(path, c, number, m) for c, m in zip(r[7:], modes)])
            if first == "frequency":
                unit = (_HEADER_UNIT.match(r[0])["unit"] or "Hz").strip()
                if unit != "Hz":
                    raise InputError(f"frequency unit {unit!r}", source=str(path),
                                     field=f"row {number}", expected="'frequency [Hz]'")
                frequencies = row_values
            else:
                damping = row_values
            continue
        sensor = r[0].strip()
        xyz = [_number(path, c, number, h) for c, h in zip(r[1:4], header[1:4])]
        d = np.array([_number(path, c, number, h) for c, h in zip(r[4:7], header[4:7])])
        if not np.any(d):
            raise InputError("measuring direction (0, 0, 0)", source=str(path),
                             field=f"row {number}, columns dx, dy, dz", expected="a direction")
        if sensor not in labels:
            labels.append(sensor)
            coordinates.append(xyz)
        elif not np.allclose(coordinates[labels.index(sensor)], xyz):
            raise InputError(f"sensor {sensor} at two positions", source=str(path),
                             field=f"row {number}", expected="one position per sensor")
        point.append(labels.index(sensor))
        direction.append(d / np.linalg.norm(d))
        values.append([_number(path, c, number, m) for c, m in zip(r[7:], modes)])
    if frequencies is None:
        raise InputError("no frequency row", source=str(path), field="row 'frequency [Hz]'",
                         expected="a row 'frequency [Hz]' with one value per mode column")
    if not values:
        raise InputError("no sensor rows", source=str(path), field="rows",
                         expected="one row per sensor and direction")
    metres, unit_field = _csv_unit(path, header)
    return ModalTest(source=str(path), labels=tuple(labels), coordinates=np.array(coordinates),
                     metres_per_unit=metres, unit_field=unit_field,
                     channel_point=np.array(point), channel_direction=np.array(direction),
                     shapes=np.array(values), frequencies=frequencies,
                     damping=np.full(k, np.nan) if damping is None else damping,
                     mode_fields=tuple(f"column {m!r}" for m in modes))


READERS = {".uff": read_uff, ".unv": read_uff, ".csv": read_csv}


def read_test(path) -> ModalTest:
    """The modal test in ``path``, read by its suffix's reader (``READERS``)."""
    path = Path(path)
    reader = READERS.get(path.suffix.lower())
    if reader is None:
        raise InputError(f"unknown test file type {path.suffix!r}", source=str(path),
                         expected=f"one of {', '.join(READERS)}")
    if not path.is_file():
        raise InputError("no such test file", source=str(path))
    return reader(path)
