"""Mode shapes as VTK files for ParaView: one ``.vtu`` per scene and pose, and per mode a ``.pvd``
animation over one period. Written with meshio; every file goes through ``write_atomic``.

Cells: one cell per frame element, a VTK Lagrange curve through the element's sampled points
(``modeshape.py``). meshio cannot write VTK's plain poly-line cell, and the Lagrange curve is the
better cell here anyway: with 3 or more subdivisions its polynomial contains the element's exact
shape (a cubic in the bending direction, linear along the axis), so a viewer that draws it as a
curve draws the computed shape itself. VTK orders a Lagrange curve's points: both ends, then the
interior points in order.

Arrays of the ``.vtu`` (2D model padded with z = 0, as VTK wants 3D points):
- point data ``mode<n>_displacement`` (3 components [m/sqrt(kg)], z = 0) and
  ``mode<n>_rotation`` [rad/sqrt(kg)]: the mass-normalised shapes exactly as solved, for the
  elastic modes numbered as in the ``modes`` table; the names hold no frequency, so a ParaView
  state file survives a change of input (the frequency is field data ``mode<n>_frequency_Hz``);
- the ground and the joints: the fixed ground pivots are points after the sampled ones (zero
  displacement in every mode); a ``line`` cell joins consecutive ground pivots (the frame,
  O2-O4 in a four-bar); every joint spring is a ``line`` cell between the points it joins (a
  bearing: pivot to link end; a pin: its first link end to each other one; zero length at rest,
  so Warp By Vector and the animation show a joint's stretch); every joint is a ``vertex``
  cell (the pivot of a bearing, the first link end of a pin);
- cell data ``part`` (``PARTS``: 0 link element, 1 ground line, 2 joint spring, 3 joint),
  ``link_id`` (index of the link), ``element_id`` (global element number), ``joint_id`` (index
  of the joint); -1 where they do not apply;
- field data ``frequencies_Hz``, ``mode_numbers``, ``warp_scale`` (per mode, the factor for
  ParaView's Warp By Vector that gives the animation's amplitude), ``theta2_deg``, ``mu_deg``,
  ``link_<name>`` = [link_id] for every link, ``joint_<name>`` = [joint_id] for every joint and
  ``part_<name>`` = [code] (meshio writes numeric arrays only, so names travel as array names).
Animation frames hold the deformed positions themselves (ParaView plays them as they are) with
the same cells and, as point data, ``applied_displacement_magnitude`` [m] and
``applied_rotation`` [rad]: scalars, no displacement vector, so Warp By Vector cannot apply the
deformation twice (it is for the ``.vtu``: ``mode<n>_displacement`` times ``warp_scale`` gives
frame 0 exactly). The ``.pvd`` time is in seconds, or the fraction of the period with
``common_phase``.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from xml.sax.saxutils import quoteattr

import meshio
import numpy as np

from flexlink.analysis.modal import CaseResult
from flexlink.errors import OutputError
from flexlink.fileio import write_atomic, write_atomic_with
from flexlink.fe.modeshape import SampledShapes, sample_shapes

CELL_TYPE = "VTK_LAGRANGE_CURVE"


@dataclasses.dataclass(frozen=True)
class JointPoints:
    """A joint of the linkage as drawn: its rest position [m] and the sampled points (indices
    into ``SampledShapes.points``) of the link ends that meet there, first the end the joint's
    springs attach the others to (``fe/model.py``). A ground joint's springs run from the fixed
    pivot at ``position`` to every link end."""

    name: str
    ground: bool
    position: tuple[float, float]
    points: tuple[int, ...]


@dataclasses.dataclass(frozen=True)
class ModeSet:
    """The elastic modes to export: numbers (1-based, as in the ``modes`` table), frequencies
    [Hz], their samples along the elements, and the joints."""

    numbers: tuple[int, ...]
    frequencies: np.ndarray
    sampled: SampledShapes
    size: float  # mechanism size [m]: diagonal of the joints' bounding box, ground included
    joints: tuple[JointPoints, ...] = ()

    def scale(self, i: int, fraction: float) -> float:
        """Factor that makes mode i's largest displacement ``fraction`` of the mechanism size."""
        peak = np.linalg.norm(self.sampled.displacement[:, :, i], axis=1).max()
        return fraction * self.size / peak if peak > 0 else 0.0

    def label(self, i: int) -> str:
        """The stable array name stem of mode i: ``mode<n>``, no frequency in it."""
        return f"mode{self.numbers[i]}"


def mode_set(result: CaseResult, n_modes: int, subdivisions: int = 4) -> ModeSet:
    """The first ``n_modes`` elastic modes of ``result``, sampled ``subdivisions`` times per
    element."""
    modes = result.modes
    chosen = modes.elastic[:n_modes]
    joints = np.array(list(result.pose.joints.values()), dtype=float)
    size = float(np.linalg.norm(joints.max(axis=0) - joints.min(axis=0)))
    sampled = sample_shapes(result.model, modes.shapes[:, chosen], subdivisions)
    return ModeSet(numbers=tuple(range(1, len(chosen) + 1)),
                   frequencies=modes.frequencies[chosen], sampled=sampled, size=size,
                   joints=joint_points(result, sampled))


def joint_points(result: CaseResult, sampled: SampledShapes) -> tuple[JointPoints, ...]:
    """Every joint of ``result``'s scene with the sampled points of its link ends."""
    point_of = {int(node): p for p, node in enumerate(sampled.point_node) if node >= 0}
    joints = []
    for spec in result.scene.joints:
        nodes = result.model.joint_nodes.get(spec.name, ())
        xy = result.pose.joints[spec.name]
        joints.append(JointPoints(name=spec.name, ground=spec.ground,
                                  position=(float(xy[0]), float(xy[1])),
                                  points=tuple(point_of[n] for n in nodes)))
    return tuple(joints)


def _pad(xy: np.ndarray) -> np.ndarray:
    return np.column_stack([xy, np.zeros(len(xy))])


def _lagrange_order(cells: np.ndarray) -> np.ndarray:
    # along-the-element order -> VTK's: first, last, then the interior points
    return np.column_stack([cells[:, 0], cells[:, -1], cells[:, 1:-1]])


# cell data ``part``: what a cell is (the codes are also field data ``part_<name>``)
PARTS = {"link": 0, "ground": 1, "joint_spring": 2, "joint": 3}


@dataclasses.dataclass(frozen=True)
class _Cells:
    """Points appended after the sampled ones (the fixed ground pivots) and every cell block
    with its cell data, for the .vtu and the animation frames alike."""

    pivots: np.ndarray  # (G, 2) [m]
    blocks: list
    cell_data: dict


def _cells(modes: ModeSet) -> _Cells:
    s = modes.sampled
    ground = [j for j in modes.joints if j.ground]
    pivot_index = {j.name: len(s.points) + k for k, j in enumerate(ground)}
    blocks, data = [(CELL_TYPE, _lagrange_order(s.cells))], [
        (PARTS["link"], s.cell_link, s.cell_element, np.full(len(s.cells), -1))]
    if len(ground) >= 2:  # the frame between consecutive ground pivots
        chain = [pivot_index[j.name] for j in ground]
        blocks.append(("line", np.column_stack([chain[:-1], chain[1:]])))
        data.append((PARTS["ground"], None, None, np.full(len(chain) - 1, -1)))
    springs, spring_joint, anchors = [], [], []
    for k, joint in enumerate(modes.joints):
        # a bearing's springs hold each link end to the fixed pivot; a pin's hold the other
        # link ends to the first one (fe/model.py)
        anchor = pivot_index[joint.name] if joint.ground else joint.points[0]
        ends = joint.points if joint.ground else joint.points[1:]
        springs += [(anchor, p) for p in ends]
        spring_joint += [k] * len(ends)
        anchors.append(anchor)
    if springs:
        blocks.append(("line", np.array(springs)))
        data.append((PARTS["joint_spring"], None, None, np.array(spring_joint)))
    if anchors:
        blocks.append(("vertex", np.array(anchors)[:, None]))
        data.append((PARTS["joint"], None, None, np.arange(len(anchors))))
    cell_data = {"part": [], "link_id": [], "element_id": [], "joint_id": []}
    for (part, link, element, joint), (_, cells) in zip(data, blocks):
        n = len(cells)
        cell_data["part"].append(np.full(n, part, dtype=np.int64))
        cell_data["link_id"].append(np.full(n, -1, dtype=np.int64) if link is None
                                    else link.astype(np.int64))
        cell_data["element_id"].append(np.full(n, -1, dtype=np.int64) if element is None
                                       else element.astype(np.int64))
        cell_data["joint_id"].append(np.asarray(joint, dtype=np.int64))
    pivots = np.array([j.position for j in ground], dtype=float).reshape(-1, 2)
    return _Cells(pivots=pivots, blocks=blocks, cell_data=cell_data)


def _name_fields(modes: ModeSet) -> dict:
    # meshio writes numeric arrays only, so names travel as array names
    return {**{f"link_{name}": np.array([i]) for i, name in enumerate(modes.sampled.link_names)},
            **{f"joint_{j.name}": np.array([k]) for k, j in enumerate(modes.joints)},
            **{f"part_{name}": np.array([code]) for name, code in PARTS.items()}}


def _with_pivots(values: np.ndarray, cells: _Cells) -> np.ndarray:
    """Per-point values followed by zeros for the pivots (they never move)."""
    values = np.asarray(values)
    return np.concatenate([values, np.zeros((len(cells.pivots),) + values.shape[1:])])


def modes_mesh(result: CaseResult, modes: ModeSet, fraction: float) -> meshio.Mesh:
    """Undeformed linkage with every mode's shape as point data (see module docstring)."""
    s = modes.sampled
    cells = _cells(modes)
    point_data = {}
    for i in range(len(modes.numbers)):
        point_data[f"{modes.label(i)}_displacement"] = _pad(_with_pivots(s.displacement[:, :, i], cells))
        point_data[f"{modes.label(i)}_rotation"] = _with_pivots(s.rotation[:, i], cells)
    field_data = {
        "frequencies_Hz": np.asarray(modes.frequencies, dtype=float),
        "mode_numbers": np.asarray(modes.numbers, dtype=np.int64),
        "warp_scale": np.array([modes.scale(i, fraction) for i in range(len(modes.numbers))]),
        "theta2_deg": np.array([math.degrees(result.pose.crank_angle)]),
        # a linkage with no transmission angle (a single rotor) has no mu to record
        **({} if result.pose.mu is None else {"mu_deg": np.array([math.degrees(result.pose.mu)])}),
        **{f"{modes.label(i)}_frequency_Hz": np.array([float(modes.frequencies[i])])
           for i in range(len(modes.numbers))},
        **_name_fields(modes),
    }
    return meshio.Mesh(_pad(np.vstack([s.points, cells.pivots])), cells.blocks,
                       point_data=point_data, cell_data=cells.cell_data, field_data=field_data)


def frame_mesh(modes: ModeSet, i: int, factor: float) -> meshio.Mesh:
    """Mode i deformed by ``factor`` times its shape: one animation frame. The points are the
    deformed positions; the frame carries no displacement vector, only its length and the
    rotation as applied, so ParaView's Warp By Vector has nothing to add a second time."""
    s = modes.sampled
    cells = _cells(modes)
    displacement = _with_pivots(factor * s.displacement[:, :, i], cells)
    return meshio.Mesh(_pad(np.vstack([s.points, cells.pivots]) + displacement), cells.blocks,
                       point_data={"applied_displacement_magnitude":
                                       np.linalg.norm(displacement, axis=1),
                                   "applied_rotation": _with_pivots(factor * s.rotation[:, i], cells)},
                       cell_data=cells.cell_data,
                       field_data={"frequency_Hz": np.array([modes.frequencies[i]]),
                                   "mode_number": np.array([modes.numbers[i]]),
                                   **_name_fields(modes)})


def _field_data_xml(field_data: dict) -> str:
    arrays = []
    for name, values in field_data.items():
        values = np.asarray(values).ravel()
        if values.dtype.kind == "f":
            kind, text = "Float64", " ".join(repr(float(v)) for v in values)
        else:
            kind, text = "Int64", " ".join(str(int(v)) for v in values)
        arrays.append(f'<DataArray type="{kind}" Name={quoteattr(name)} NumberOfTuples="{len(values)}"'
                      f' format="ascii">{text}</DataArray>')
    return "<FieldData>\n" + "\n".join(arrays) + "\n</FieldData>\n"


def _write_vtu_now(path: Path, mesh: meshio.Mesh) -> None:
    meshio.write(path, mesh, file_format="vtu")
    if not mesh.field_data:
        return
    # meshio 5.3 reads a .vtu's FieldData but does not write it: add the block where VTK's XML
    # format puts it, first inside <UnstructuredGrid>.
    text = path.read_text(encoding="utf-8")
    tag = "<UnstructuredGrid>"
    if text.count(tag) != 1:
        raise OutputError(f"unexpected meshio output in {path}: cannot add field data")
    path.write_text(text.replace(tag, tag + "\n" + _field_data_xml(mesh.field_data)), encoding="utf-8")


def write_vtu(path: str | Path, mesh: meshio.Mesh) -> Path:
    """Write ``mesh`` as a binary, zlib-compressed .vtu (with its field data), atomically."""
    return write_atomic_with(path, lambda tmp: _write_vtu_now(tmp, mesh))


def pvd_text(entries: list[tuple[float, str]]) -> str:
    """A ParaView collection: (time [s], file relative to the .pvd) per frame."""
    rows = "".join(f'    <DataSet timestep="{t:.9g}" group="" part="0" file={quoteattr(f)}/>\n'
                   for t, f in entries)
    return ('<?xml version="1.0"?>\n'
            '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f"  <Collection>\n{rows}  </Collection>\n</VTKFile>\n")


def write_animation(folder: Path, stem: str, modes: ModeSet, i: int, phases: int,
                    fraction: float, common_phase: bool = False) -> list[Path]:
    """Frames of mode i at ``phases`` equally spaced phases over one period (cosine, so frame 0
    is the largest deflection), in ``folder/<stem>_mode<n>/``, then ``<stem>_mode<n>.pvd``
    (written last, so it never names a missing frame). The .pvd time is in seconds, or with
    ``common_phase`` the phase as a fraction of the period, 0 ... (phases - 1) / phases, the
    same for every mode so that modes play side by side. Returns the files written."""
    name = f"{stem}_mode{modes.numbers[i]}"
    frames = folder / name
    try:
        frames.mkdir(exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot create {frames}: {exc.strerror or exc}") from None
    period = (1.0 if common_phase or modes.frequencies[i] <= 0
              else 1.0 / modes.frequencies[i])
    scale = modes.scale(i, fraction)
    written, entries = [], []
    for k in range(phases):
        file = frames / f"phase{k:02d}.vtu"
        written.append(write_vtu(file, frame_mesh(modes, i, scale * math.cos(2 * math.pi * k / phases))))
        entries.append((k * period / phases, f"{name}/{file.name}"))
    written.append(write_atomic(folder / f"{name}.pvd", pvd_text(entries)))
    return written
