"""The crank-cycle study of ``flexlink cycle``: the modal map of a scene over one revolution
(tracked by shape, or in frequency order), the resonance check against the crank harmonics at a
crank speed, and the nearest harmonic when none resonates."""

from __future__ import annotations

import dataclasses

from flexlink.analysis.families import in_plane_only_note
from flexlink.analysis.mesh import MeshRule, choose_mesh
from flexlink.scene import Scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.bands import nearest_harmonic
from flexlink.studies.cycle.modal_map import ModalMap, Resonance, modal_map, resonance_speed, resonances
from flexlink.studies.cycle.tracking import TrackedMap, tracked_map


@dataclasses.dataclass(frozen=True)
class CycleStudy:
    """``map`` of the first elastic modes over ``poses`` crank angles on ``mesh``; the crank
    speed given (``crank_speed`` [rad/s], None: none), the speed the resonance check ran at
    (``check_speed`` [rad/s], None: skipped) and why it differs (``check_note``); the harmonics
    1 ... ``harmonics`` within the relative ``margin`` of a mode (``hits``), the nearest one
    (``nearest``: relative gap, mode, harmonic; None without a check) and a ``note`` when the
    map is not quite what was asked for."""

    map: ModalMap | TrackedMap
    mesh: MeshRule
    poses: int
    crank_speed: float | None
    check_speed: float | None
    check_note: str | None
    margin: float
    harmonics: int
    hits: tuple[Resonance, ...]
    nearest: tuple[float, int, int] | None
    note: str | None

    def __post_init__(self):
        lines = self.map.frequencies.shape[1] if self.map.frequencies.ndim == 2 else None
        check_shape("CycleStudy", "map.frequencies", self.map.frequencies, (self.poses, lines))
        check_shape("CycleStudy", "map.q", self.map.q, (self.poses,))
        if self.nearest is not None:
            check_shape("CycleStudy", "nearest", self.nearest, (3,))
        for hit in self.hits:
            if not 1 <= hit.mode <= lines or not 1 <= hit.harmonic <= self.harmonics:
                raise ValueError(f"CycleStudy.hits has mode {hit.mode} and harmonic "
                                 f"{hit.harmonic}, expected 1..{lines} and 1..{self.harmonics}")

    @property
    def tracked(self) -> bool:
        """Whether the lines are followed by shape (MAC) rather than frequency order."""
        return isinstance(self.map, TrackedMap)


def cycle_study(scene: Scene, n_modes: int, poses: int, elements: int | None, tol: float | None,
                crank_speed: float | None, margin: float, harmonics: int, track: bool = True,
                n_jobs: int = 1, progress=None) -> CycleStudy:
    """The first ``n_modes`` elastic modes of ``scene`` at ``poses`` crank angles, on
    ``elements`` per link (None: ``mesh.choose_mesh`` at the relative tolerance ``tol``),
    tracked by MAC (``track``) or sorted by frequency (the Craig-Bampton sweep), and the
    harmonics 1 ... ``harmonics`` of ``crank_speed`` [rad/s] (``cycle.resonance_speed``)
    within the relative ``margin`` of a mode anywhere in the cycle."""
    check_speed, check_note = resonance_speed(crank_speed)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    if track:
        found = tracked_map(scene, poses, n_modes, mesh.elements, progress=progress,
                            n_jobs=n_jobs)
        to_zero = [(j, r.pose) for r in found.tracks.reseeds for j in r.vanishing]
    else:
        found = modal_map(scene, poses, n_modes, mesh.elements, progress=progress)
        to_zero = []
    hits = resonances(found, check_speed, margin, harmonics, to_zero) if check_speed else []
    nearest = nearest_harmonic(found.frequencies, check_speed, harmonics) if check_speed else None
    return CycleStudy(map=found, mesh=mesh, poses=poses, crank_speed=crank_speed,
                      check_speed=check_speed, check_note=check_note, margin=margin,
                      harmonics=harmonics, hits=tuple(hits), nearest=nearest,
                      note=in_plane_only_note(scene, "this map") if track else found.note)
