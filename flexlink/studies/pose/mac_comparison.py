"""Two scenes or meshes compared mode by mode: the MAC matrix of their lowest elastic modes
at their poses and the pairing it gives (``analysis.mac``), within one model part.

The in-plane part is the frame model (``analysis.modal``); the out-of-plane part the strip
model (``analysis.outofplane``). Their shapes live on different DOFs, so shapes are compared
only within one part: ``mac_part`` picks it from the scenes' ``model.family`` (or takes
the one asked for) and refuses a comparison across parts.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.families import IN_PLANE, OUT_OF_PLANE
from flexlink.analysis.identity import mode_identity
from flexlink.analysis.mac import STATIONS, compare_models, pair_modes
from flexlink.analysis.modal import analyze
from flexlink.analysis.outofplane import analyze_out_of_plane
from flexlink.errors import InputError
from flexlink.fe.model import FrameModel
from flexlink.fe.motions import ModelFamily, Part
from flexlink.fe.model_at_pose import pose_model
from flexlink.scene import Scene

PART_OF_FAMILY = {ModelFamily.PLANAR: IN_PLANE, ModelFamily.OUT_OF_PLANE: OUT_OF_PLANE}  # 3d: both


@dataclasses.dataclass(frozen=True)
class Side:
    """One side of a comparison: the scene, its mesh, and its lowest elastic modes of one
    part: frequencies [Hz], labels, the model (its mesh and links) and the mass-normalised
    shapes (n_dofs, k) on that part's DOFs."""

    scene: Scene
    elements_per_link: int
    frequencies: np.ndarray
    labels: tuple[str, ...]
    model: FrameModel
    shapes: np.ndarray


@dataclasses.dataclass(frozen=True)
class ShapeComparison:
    """mac[i, j]: MAC of mode i of ``a`` with mode j of ``b`` (elastic modes, lowest first);
    pairs: (i, j, MAC) of the best one-to-one pairing; part: the model part compared."""

    a: Side
    b: Side
    mac: np.ndarray
    pairs: tuple[tuple[int, int, float], ...]
    part: Part = IN_PLANE


def mac_part(scene_a: Scene, scene_b: Scene, requested: Part | None = None) -> Part:
    """The part to compare: ``requested`` (every scene has both models), or with None the part
    of the family both scenes declare in ``model.family``."""
    if requested is not None:
        return requested
    declared = [(s.path, s.options.family) for s in (scene_a, scene_b)]
    for path, family in declared:
        if family not in PART_OF_FAMILY:
            raise InputError(f"model.family = '{family}' holds both the in-plane and the "
                             "out-of-plane modes, which MAC cannot compare with each other",
                             source=path, field="model.family",
                             expected=f"--part {IN_PLANE} or --part {OUT_OF_PLANE}")
    families = {PART_OF_FAMILY[f] for _, f in declared}
    if len(families) > 1:
        listing = ", ".join(f"{p}: {f}" for p, f in declared)
        raise InputError(f"the scenes declare different model families ({listing}); in-plane "
                         "and out-of-plane shapes move different DOFs, so a MAC between them "
                         "means nothing", source="command line", field="--part",
                         expected=f"scenes of one family, or --part {IN_PLANE} or "
                                  f"--part {OUT_OF_PLANE} to compare both in that part")
    return families.pop()


def _in_plane(scene: Scene, n_modes: int, elements: int | None) -> Side:
    r = analyze(scene, n_modes, elements)
    shapes = r.modes.shapes[:, r.modes.elastic[:n_modes]]
    labels = mode_identity(r.model, shapes).labels
    return Side(scene, r.elements_per_link, r.elastic_frequencies(n_modes), labels, r.model,
                shapes)


def _out_of_plane(scene: Scene, n_modes: int, elements: int | None) -> Side:
    modes = analyze_out_of_plane(scene, n_modes, elements)
    topology = scene.topology(elements)
    model = pose_model(topology, scene.rigid_pose().joints, warn=False)  # its mesh and links
    chosen = modes.elastic[:n_modes]
    # the out-of-plane part has no energy labels (analysis/identity.py is in-plane)
    return Side(scene, topology.links[0].elements, modes.frequencies[chosen],
                (OUT_OF_PLANE,) * len(chosen), model, modes.shapes[:, chosen])


SIDES = {IN_PLANE: _in_plane, OUT_OF_PLANE: _out_of_plane}


def compare_scenes(scene_a: Scene, scene_b: Scene, n_modes: int, elements_a: int | None,
                   elements_b: int | None, per_link: int = STATIONS,
                   part: Part = IN_PLANE) -> ShapeComparison:
    """The lowest ``n_modes`` elastic modes of ``part`` of both scenes at their poses,
    compared at ``per_link`` + 1 stations along each link (the scenes must name the same
    links)."""
    a = SIDES[part](scene_a, n_modes, elements_a)
    b = SIDES[part](scene_b, n_modes, elements_b)
    mac = compare_models(a.model, a.shapes, b.model, b.shapes, per_link, part)
    p = pair_modes(mac)
    return ShapeComparison(a, b, mac, tuple((int(i), int(j), float(m))
                                            for i, j, m in zip(p.a, p.b, p.mac)), part)
