"""Mode shapes written in the formats test software reads: Universal File Format datasets 164
(units), 15 or 2411 (geometry) and 55 (one per mode, normal modes, X Y Z per node), all
through pyuff, and the CSV layout ``studies.correlation.measured`` reads back.

UFF 55 stores six significant digits (pyuff writes E13.5), so a value read back differs from
the one written by at most half a unit in the sixth digit; geometry in 2411 keeps 17 digits,
in 15 six. Units: dataset 164's length factor is file units per metre (1000 for mm).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexlink.fileio import write_atomic, write_atomic_with
from flexlink.studies.correlation.correlation import ModesAtPoints
from flexlink.units import UNITS

GEOMETRY_DATASETS = (15, 2411)
UNIT_CODES = {"m": 1, "mm": 3}  # I-DEAS unit systems: SI metre, mm-N; others "user" (0)


def uff_datasets(shapes: ModesAtPoints, title: str, damping=None, geometry: int = 15
                 ) -> list[dict]:
    """pyuff's dictionaries of datasets 164, ``geometry`` (15 or 2411) and one 55 per mode;
    ``title`` is every 55's ID line 1, ``damping`` (k,) viscous ratios (None: 0)."""
    import pyuff

    if geometry not in GEOMETRY_DATASETS:
        raise ValueError(f"geometry dataset {geometry}, expected one of {GEOMETRY_DATASETS}")
    per_metre = 1.0 / UNITS["length"][shapes.unit]
    labels = [int(x) for x in shapes.labels]
    zeros = [0] * len(labels)
    units = pyuff.prepare_164(units_code=UNIT_CODES.get(shapes.unit, 0),
                              units_description=shapes.unit, temp_mode=1, length=per_metre,
                              force=1.0, temp=1.0, temp_offset=273.15)
    prepare = pyuff.prepare_15 if geometry == 15 else pyuff.prepare_2411
    xyz = np.asarray(shapes.coordinates, dtype=float)
    points = prepare(node_nums=labels, def_cs=zeros, disp_cs=zeros, color=zeros,
                     x=xyz[:, 0].tolist(), y=xyz[:, 1].tolist(), z=xyz[:, 2].tolist())
    out = [units, points]
    for k, f in enumerate(shapes.frequencies):
        v = shapes.values[:, :, k]
        out.append(pyuff.prepare_55(
            id1=title[:80] or "NONE", id4=f"mode {k + 1}", model_type=1,
            analysis_type=2, data_ch=2, spec_data_type=8, data_type=2, n_data_per_node=3,
            r1=v[:, 0].astype(float), r2=v[:, 1].astype(float), r3=v[:, 2].astype(float),
            load_case=1, mode_n=k + 1, freq=float(f), modal_m=0.0,
            modal_damp_vis=0.0 if damping is None else float(damping[k]), modal_damp_his=0.0,
            node_nums=np.array(labels)))
    return out


def write_uff(path: str | Path, shapes: ModesAtPoints, title: str, damping=None,
              geometry: int = 15) -> Path:
    """``shapes`` as a UFF file (``uff_datasets``), written by pyuff, atomically."""
    import pyuff

    datasets = uff_datasets(shapes, title, damping, geometry)
    return write_atomic_with(path, lambda tmp: pyuff.UFF(str(tmp)).write_sets(
        datasets, mode="overwrite"))


def shapes_csv(shapes: ModesAtPoints, damping=None) -> str:
    """The CSV form (``studies.correlation.measured.read_csv``): one row per point and
    direction with a non-zero reading in some mode."""
    damping = np.zeros(len(shapes.frequencies)) if damping is None else damping
    unit = shapes.unit
    lines = [f"sensor,x [{unit}],y [{unit}],z [{unit}],dx,dy,dz,"
             + ",".join(f"mode {k + 1}" for k in range(len(shapes.frequencies)))]
    lines.append("frequency [Hz],,,,,,," + ",".join(f"{f:.9g}" for f in shapes.frequencies))
    lines.append("damping,,,,,,," + ",".join(f"{z:.6g}" for z in damping))
    for label, xyz, values in zip(shapes.labels, shapes.coordinates, shapes.values):
        for axis in range(3):
            if not np.any(values[axis]):
                continue
            d = np.eye(3)[axis]
            lines.append(f"{label}," + ",".join(f"{c:.9g}" for c in xyz) + ","
                         + ",".join(f"{c:g}" for c in d) + ","
                         + ",".join(f"{v:.9g}" for v in values[axis]))
    return "\n".join(lines) + "\n"


def write_shapes_csv(path: str | Path, shapes: ModesAtPoints, damping=None) -> Path:
    return write_atomic(path, shapes_csv(shapes, damping))
