"""The ``[[loads]]`` tables: external loads on the bodies, for the driving torque. A constant
load comes from the table itself; a load over the crank angle from a CSV file (header row,
crank angle [deg] first, evenly spaced over one full turn; then the torque, or Fx and Fy, in
the table's ``unit``). A CSV with a gap in its angles, a partial turn, or a missing or
unreadable value is refused with the file, the field and the row."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics import Linkage
from flexlink.kinematics.inverse import Wrench
from flexlink.kinematics.linkage import State
from flexlink.scene import parts, schema
from flexlink.scene.contract import LoadFrame, LoadKind, LoadSpec
from flexlink.scene.source import SceneSource
from flexlink.units import parse_quantity

ANGLE_TOL = 1e-6  # [deg] an angle's distance from the even grid that still counts as on it
COLUMNS = {"torque": ("torque",), "force": ("Fx", "Fy")}


def _rows(path: Path, field: str, width: int) -> tuple[list[str], np.ndarray]:
    expected = f"a header row, then crank_angle_deg and {width} value column(s) per row"
    if path.is_dir():
        raise InputError("this is a folder, not a file", source=str(path), field=field,
                         expected=f"a CSV file beside the scene: {expected}")
    if not path.is_file():
        raise InputError("no such file", source=str(path), field=field,
                         expected=f"a CSV file beside the scene: {expected}")
    with path.open(newline="") as handle:
        rows = [r for r in csv.reader(handle) if any(cell.strip() for cell in r)]
    if not rows:
        raise InputError("the file is empty", source=str(path), field=field, expected=expected)
    header, body = rows[0], rows[1:]
    if len(header) != 1 + width:
        raise InputError(f"the header has {len(header)} column(s)", source=str(path),
                         field=field, expected=expected)
    data = np.empty((len(body), 1 + width))
    for i, row in enumerate(body, start=2):
        if len(row) != 1 + width:
            raise InputError(f"row {i} has {len(row)} column(s)", source=str(path), field=field,
                             expected=expected)
        for k, cell in enumerate(row):
            try:
                data[i - 2, k] = float(cell)
            except ValueError:
                data[i - 2, k] = math.nan
            if not math.isfinite(data[i - 2, k]):
                what = "missing" if not cell.strip() else f"unreadable ({cell.strip()!r})"
                raise InputError(f"row {i}, column {header[k].strip()!r}: {what} value",
                                 source=str(path), field=field, expected="a finite number")
    return header, data


def _one_turn(path: Path, field: str, data: np.ndarray) -> np.ndarray:
    """The rows on an even grid over one turn [deg] (a closing row at +360 deg dropped)."""
    angles = data[:, 0]
    if len(angles) < 3:
        raise InputError(f"{len(angles)} row(s)", source=str(path), field=field,
                         expected="at least 3 crank angles over a full turn")
    if np.any(np.diff(angles) <= 0):
        i = int(np.argmax(np.diff(angles) <= 0)) + 3
        raise InputError(f"crank angles do not increase at row {i}", source=str(path),
                         field=field, expected="increasing crank angles [deg]")
    if abs(angles[-1] - angles[0] - 360.0) <= ANGLE_TOL:  # the turn closed by a repeated row
        if not np.allclose(data[-1, 1:], data[0, 1:], rtol=1e-9, atol=0.0):
            raise InputError(f"the row at {angles[-1]:g} deg differs from the one at "
                             f"{angles[0]:g} deg, a full turn earlier", source=str(path),
                             field=field, expected="the same value a turn apart")
        data, angles = data[:-1], angles[:-1]
    steps = np.diff(angles)
    step = steps.min()
    gap = int(np.argmax(steps))
    if steps[gap] - step > ANGLE_TOL:
        raise InputError(f"missing crank angle(s): the rows step by {step:g} deg but jump by "
                         f"{steps[gap]:g} deg after {angles[gap]:g} deg", source=str(path),
                         field=field, expected="evenly spaced angles over a full turn")
    covered = len(angles) * step
    if abs(covered - 360.0) > ANGLE_TOL * len(angles):
        raise InputError(f"the crank angles cover {angles[0]:g} to {angles[-1]:g} deg in steps "
                         f"of {step:g} deg: not one full turn", source=str(path), field=field,
                         expected="evenly spaced angles over 360 deg")
    return data


def load_spec(src: SceneSource, table: schema.LoadTable, i: int, names: list[str]) -> LoadSpec:
    field = f"loads[{i}]"
    if table.link not in names:
        raise parts.unknown_name(src, f"{field}.link", "body", table.link, names)
    at = tuple(table.at) if table.at is not None else (0.0, 0.0)
    kind, frame = table.kind, table.frame
    if table.csv is None:
        value = (table.torque,) if kind is LoadKind.TORQUE else tuple(table.force)
        return LoadSpec(kind, table.link, np.array([value], float), None, at, frame, field)
    scale = parse_quantity(f"1 {table.unit}", table.kind, source=src.file_of("loads"),
                           field=f"{field}.unit")
    path = Path(src.file_of("loads")).parent / table.csv
    _, data = _rows(path, f"{field}.csv", len(COLUMNS[table.kind]))
    data = _one_turn(path, f"{field}.csv", data)
    return LoadSpec(kind, table.link, data[:, 1:] * scale, np.radians(data[:, 0]), at, frame,
                    field)


def build_loads(src: SceneSource, sf: schema.SceneFile, linkage: Linkage) -> tuple[LoadSpec, ...]:
    """The scene's ``[[loads]]`` checked against the linkage's bodies, CSV files read."""
    names = [b.name for b in linkage.bodies]
    return tuple(load_spec(src, table, i, names) for i, table in enumerate(sf.loads))


def wrench(linkage: Linkage, state: State, load: LoadSpec) -> Wrench:
    """The load at the pose ``state``, in global components at a global point."""
    body = linkage.body(load.body)
    p0, p1 = (np.asarray(state.points[j], float) for j in body.joints[:2])
    e = (p1 - p0) / np.linalg.norm(p1 - p0)
    n = np.array([-e[1], e[0]])
    value = load.value_at(state.q)
    if load.kind is LoadKind.TORQUE:
        return Wrench(load.body, torque=float(value[0]))
    force = value[0] * e + value[1] * n if load.frame is LoadFrame.BODY else value
    point = p0 + load.at[0] * e + load.at[1] * n
    return Wrench(load.body, force=(float(force[0]), float(force[1])),
                  point=(float(point[0]), float(point[1])))
