"""The whole crank cycle of a scene: rigid poses over one revolution of the input, the natural
frequencies at every pose (the modal map), and a resonance check against crank harmonics.

The beam model's topology is fixed, so ``sweep.modal_sweep`` builds the link matrices once and
only rotates and assembles them per pose.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import InputError, NumericalError
from flexlink.kinematics.linkage import Cycle, crank_angles, crossings
from flexlink.scene import Scene
from flexlink.scene.contract import pose_transmission_angles
from flexlink.analysis.families import in_plane_only_note
from flexlink.analysis.sweep import SWEEP_SOLVER, Reduction, modal_sweep
from flexlink.parallel import on_cluster, run_tasks
from flexlink.units import rev_per_min


def kinematic_cycle(scene: Scene, n_poses: int = 360, progress=None) -> Cycle:
    """Rigid poses at ``n_poses`` input angles over one revolution from the scene's cycle
    origin (``Scene.cycle_origin``)."""
    scene.require_full_turn()
    start, guess = scene.cycle_origin()
    return scene.linkage.cycle(crank_angles(n_poses, start), guess, progress)


def transmission_angles(scene: Scene, cycle: Cycle) -> dict[str, np.ndarray]:
    """mu [rad] over the cycle for each body pair of ``scene.transmission``: the angle between
    the two bodies' lines at the joint they share (0 or 180 deg at a dead centre)."""
    per_pose = [pose_transmission_angles(scene.linkage, scene.transmission, s.points)
                for s in cycle.states]
    return {pair: np.array([mu[pair] for mu in per_pose]) for pair in per_pose[0]} \
        if per_pose and per_pose[0] else {}


@dataclasses.dataclass(frozen=True)
class ModalMap:
    """frequencies[i, j]: j-th elastic natural frequency [Hz] at input angle q[i] [rad];
    mu90: input angles [rad] where a transmission angle is 90 deg, by body pair; note: why the
    full model was solved instead of the reduction asked for, or that it holds only the
    in-plane modes of a scene of another family (None: as asked)."""

    scene: str
    q: np.ndarray
    frequencies: np.ndarray
    mechanism_counts: np.ndarray
    mu90: dict[str, np.ndarray]
    note: str | None = None


def modal_map(scene: Scene, n_poses: int = 360, n_modes: int = 3,
              elements_per_link: int | None = None, progress=None,
              reduction: Reduction | None = Reduction.CRAIG_BAMPTON) -> ModalMap:
    """The first ``n_modes`` elastic frequencies at ``n_poses`` input angles over the cycle.

    ``reduction``: as in ``sweep.modal_sweep``; by default the Craig-Bampton links
    (tests/fe/test_craig_bampton.py: within 1e-6 of the full model), None for the full model.
    Links the reduction cannot take (``sweep.craig_bampton_refusal``) are solved on the full
    model, and the map's ``note`` says so (as it says when the scene's family is not planar:
    ``families.in_plane_only_note``).
    Inside ``parallel.use_scheduler`` the sweep runs as one task on the cluster (the same
    computation: a Craig-Bampton basis fits the whole sweep, so it is not split)."""
    cycle = kinematic_cycle(scene, n_poses)
    sweep_task = (scene.topology(elements_per_link), [s.points for s in cycle.states], n_modes)
    if on_cluster():  # the whole sweep as one task: its basis fits all its poses together
        [sweep] = run_tasks(modal_sweep, [(*sweep_task, SWEEP_SOLVER, None, reduction)],
                            label="modal maps")
    else:
        sweep = modal_sweep(*sweep_task, progress=progress, reduction=reduction)
    missing = ~np.isfinite(sweep.frequencies).all(axis=1)
    if missing.any():  # never a silent gap in the map: the model has fewer modes than asked
        found = int(np.isfinite(sweep.frequencies[missing][0]).sum())
        raise NumericalError(
            f"{n_modes} elastic modes asked for (-n), but at {int(missing.sum())} of {n_poses} "
            f"crank angles (first {math.degrees(cycle.q[missing][0]):.1f} deg) the model has "
            f"only {found}: ask for fewer modes or use more elements per link")
    mu90 = {k: crossings(cycle.q, mu, math.pi / 2)
            for k, mu in transmission_angles(scene, cycle).items()}
    return ModalMap(scene=scene.name, q=cycle.q, frequencies=sweep.frequencies,
                    mechanism_counts=sweep.mechanism_counts, mu90=mu90,
                    note="; ".join(n for n in (in_plane_only_note(scene, "this map"), sweep.note)
                                  if n) or None)


@dataclasses.dataclass(frozen=True)
class Resonance:
    """Harmonic ``harmonic`` of the crank frequency, ``frequency`` [Hz], lies within the margin
    of mode ``mode`` (1-based) at the input angles ``angles`` [rad]; ``closest`` is the smallest
    relative gap |f_mode - f_harmonic| / f_mode over the cycle."""

    harmonic: int
    frequency: float
    mode: int
    angles: np.ndarray
    closest: float


def resonance_speed(crank_speed: float | None) -> tuple[float | None, str | None]:
    """The crank speed [rad/s] the resonance check runs at (None: no check), and a note saying
    why it is not the speed given. A negative speed turns the crank the other way: the poses
    are the same and their natural frequencies do not depend on the speed, so the harmonics
    that matter are those of |speed|. A zero speed has no harmonics to check."""
    if crank_speed is None:
        return None, "no crank speed given: resonance check skipped"
    if crank_speed == 0:
        return None, "crank speed 0: no crank harmonics, resonance check skipped"
    if crank_speed < 0:
        rpm = rev_per_min(-crank_speed)
        return -crank_speed, (f"crank speed -{rpm:g} rev/min turns the crank the opposite way; "
                              f"the resonance check runs at |speed| = {rpm:g} rev/min (the "
                              "natural frequencies at a pose do not depend on the speed)")
    return crank_speed, None


def resonances(result: ModalMap, crank_speed: float, margin: float = 0.05,
               harmonics: int = 10, to_zero=()) -> list[Resonance]:
    """Harmonics n = 1 ... ``harmonics`` of the crank frequency (``crank_speed`` [rad/s], > 0:
    see ``resonance_speed``) that come within ``margin`` (relative) of an elastic frequency
    anywhere in the cycle. Besides the sampled poses, a mode curve that crosses the harmonic
    between two poses counts there. ``to_zero``: (mode, pose) pairs (1-based mode) where a
    mode turns into a mechanism (``tracking.Reseed.vanishing``): its frequency falls to 0 Hz
    there, so every harmonic below its neighbouring values crosses it at that pose."""
    if not crank_speed > 0:
        raise InputError(f"resonance check needs a positive crank speed, got {crank_speed} rad/s",
                         field="crank_speed", expected="a positive angular speed (see "
                         "resonance_speed for the sign)")
    f_crank = crank_speed / (2 * math.pi)
    found = []
    for n in range(1, harmonics + 1):
        f_n = n * f_crank
        for j in range(result.frequencies.shape[1]):
            f = result.frequencies[:, j]
            gap = np.abs(f - f_n) / f
            near = np.remainder(result.q[gap <= margin], 2 * math.pi)  # as crossings are
            crossed = crossings(result.q, f, f_n)
            falls = [np.remainder(result.q[i], 2 * math.pi) for mode, i in to_zero
                     if mode == j + 1 and f_n < np.nanmin(f[[i - 1, (i + 1) % len(f)]])]
            crossed = np.concatenate([crossed, falls])
            angles = np.unique(np.concatenate([near, crossed]))
            if angles.size:
                closest = 0.0 if crossed.size else float(np.nanmin(gap))
                found.append(Resonance(n, f_n, j + 1, angles, closest))
    return found


def runs(angles: np.ndarray, step: float) -> list[tuple[float, float]]:
    """Sorted input angles [rad] grouped into (first, last) runs whose neighbours are at most
    1.5 ``step`` apart, so a resonance reads as crank-angle ranges."""
    out = []
    for a in np.sort(angles):
        if out and a - out[-1][1] <= 1.5 * step:
            out[-1][1] = a
        else:
            out.append([a, a])
    return [(float(a), float(b)) for a, b in out]
