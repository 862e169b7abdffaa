"""The Campbell study of ``flexlink campbell``: the tracked modes' bands over the crank cycle,
the critical speed ranges of the crank harmonics over a speed window (or the nearest margin
when there is none), and optionally the bands at speed (``dynamic_campbell``)."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.families import in_plane_only_note
from flexlink.analysis.mesh import MeshRule, choose_mesh
from flexlink.scene import Scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.bands import (Band, CriticalSpeed, NearestMargin, bands,
                                       critical_speeds, nearest_margin)
from flexlink.studies.running.dynamic_campbell import (CriticalShift, DynamicCampbell, critical_shifts,
                                               dynamic_campbell)
from flexlink.studies.cycle.tracking import TrackedMap, tracked_map, vanishing_lines


@dataclasses.dataclass(frozen=True)
class CampbellStudy:
    """The ``tracked`` map over ``poses`` crank angles on ``mesh``, one band per tracked line
    (``bands``), the ``critical`` speed ranges of harmonics 1 ... ``harmonics`` within the
    relative ``margin`` over the crank speed ``window`` (low, high) [rad/s], the ``nearest``
    margin, a ``note`` when the diagram is not the scene family's; with the speed-dependent
    diagram, ``at_speed`` and its ``shifts`` of the critical ranges."""

    tracked: TrackedMap
    mesh: MeshRule
    poses: int
    window: tuple[float, float]
    margin: float
    harmonics: int
    bands: tuple[Band, ...]
    critical: tuple[CriticalSpeed, ...]
    nearest: NearestMargin | None
    note: str | None = None
    at_speed: DynamicCampbell | None = None
    shifts: tuple[CriticalShift, ...] = ()

    def __post_init__(self):
        lines = len(self.bands)
        check_shape("CampbellStudy", "window", self.window, (2,))
        check_shape("CampbellStudy", "tracked.frequencies", self.tracked.frequencies,
                    (self.poses, lines))
        if self.at_speed is not None:
            check_shape("CampbellStudy", "at_speed.frequencies", self.at_speed.frequencies,
                        (None, None, lines))
        elif self.shifts:
            raise ValueError("CampbellStudy.shifts given without the diagram at speed")

    @property
    def labels(self) -> dict[int, str]:
        """Each tracked line's (1-based) identity label at the first pose."""
        return dict(enumerate(self.tracked.labels, start=1))


def speed_grid(window: tuple[float, float], steps: int, critical) -> np.ndarray:
    """The diagram at speed's crank speeds [rad/s]: ``steps`` across the ``window``, and the
    ends and middle of every frozen critical range in it, so that a range narrower than the
    grid's step is still sampled where it is looked for."""
    inside = [x for c in critical for x in (c.low, 0.5 * (c.low + c.high), c.high)
              if window[0] <= x <= window[1]]
    return np.unique(np.concatenate([np.linspace(*window, steps), inside]))


def campbell_study(scene: Scene, window: tuple[float, float], n_modes: int, poses: int,
                   elements: int | None, tol: float | None, margin: float, harmonics: int,
                   speed_steps: int | None = None, n_jobs: int = 1, progress=None,
                   progress_at_speed=None, crank_acceleration: float = 0.0) -> CampbellStudy:
    """The Campbell diagram of the first ``n_modes`` tracked modes of ``scene`` at ``poses``
    crank angles (``tracking.tracked_map``) on ``elements`` per link (None: ``choose_mesh`` at
    the relative tolerance ``tol``), against the crank speeds ``window`` [rad/s]; with
    ``speed_steps``, also the diagram at that many speeds across the window, with the crank's
    angular acceleration ``crank_acceleration`` [rad/s^2] at every speed."""
    mesh = choose_mesh(scene, n_modes, elements, tol)
    tracked = tracked_map(scene, poses, n_modes, mesh.elements, progress=progress,
                          n_jobs=n_jobs)
    found = bands(tracked.frequencies, vanishing_lines(tracked))
    critical = critical_speeds(found, window, margin, harmonics)  # checks the window first
    nearest = nearest_margin(found, window, harmonics)
    at_speed = None if speed_steps is None else dynamic_campbell(
        scene, speed_grid(window, speed_steps, critical), poses, n_modes, mesh.elements,
        progress=progress_at_speed, crank_acceleration=crank_acceleration)
    return CampbellStudy(
        tracked=tracked, mesh=mesh, poses=poses, window=window, margin=margin,
        harmonics=harmonics, bands=tuple(found), critical=tuple(critical), nearest=nearest,
        note=in_plane_only_note(scene, "this diagram"), at_speed=at_speed,
        shifts=() if at_speed is None else tuple(critical_shifts(at_speed, margin, harmonics)))
