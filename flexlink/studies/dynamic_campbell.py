"""Speed-dependent Campbell diagram: each tracked mode's band over the crank cycle at each crank
speed, from the operating-point modes (``studies.operating_point``) at every pose, against the
frozen-pose (static) bands.

At constant crank speed Omega every operating-point term of a pose scales with a power of
Omega: the rigid accelerations, hence the d'Alembert preload, its axial forces and K_g(N), the
centrifugal -omega^2 Mt and the circulatory alpha S are Omega^2 times their values at 1 rad/s,
and the gyroscopic G is Omega times its value. So per pose
    M x'' + Omega G1 x' + (K + K_ext + Omega^2 K2) x = 0,
with K_ext the geometric stiffness of the scene's constant [[loads]]. Each pose is reduced once
onto its lowest static modes Phi (mass normalised, ``basis`` of them: Galerkin projection, M ->
I, K -> diag(omega_i^2)), and every speed is then a small dense quadratic eigenproblem. The
reduction is checked against the full ``operating_modes`` solve in the tests.

Modes are tracked pose to pose by MAC at each speed as the static cycle map tracks them
(``tracking.track``), with each complex shape's phase fixed (largest component real) and its
real and imaginary parts stacked. Harmonic n is critical for mode j at speed Omega when
n Omega / (2 pi) lies in [f_min(Omega) (1 - m), f_max(Omega) (1 + m)]; the range edges are found
on the speed grid and interpolated linearly.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from flexlink.analysis.mac import link_frame, link_frame_mass
from flexlink.analysis.modal import pose_modes
from flexlink.analysis.solve import MECHANISM
from flexlink.errors import InputError, NumericalError
from flexlink.fe.assembly import (assemble_reduced_dense, dense_slots, dense_sum,
                                  reduced_columns, rigid_elimination)
from flexlink.fe.geometric import GeometricForm, geometric_entries
from flexlink.fe.preload import axial_forces, inertia_loads, static_displacement
from flexlink.fe.rotating import rotating_entries
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.scene import Scene
from flexlink.studies.campbell import Band, CriticalSpeed, bands, critical_speeds
from flexlink.studies.cycle import kinematic_cycle
from flexlink.studies.operating_point import external_loads, link_motion
from flexlink.studies.tracking import SPARE, track

EXTRA = 8  # static modes in each pose's basis beyond the ones solved at speed


@dataclasses.dataclass(frozen=True)
class ReducedPose:
    """One pose's operating-point matrices on its static modes Phi (full DOFs, mass
    normalised): k0 = Phi^T (K + K_ext) Phi, k2 and g1 the Omega^2 and Omega coefficients
    [1/s^2, -, 1/s]; ``frame``: Phi in link frames, for the MAC."""

    static_hz: np.ndarray  # the pose's static frequencies of the basis [Hz]
    k0: np.ndarray
    k2: np.ndarray
    g1: np.ndarray
    frame: np.ndarray

    def modes(self, speed: float, count: int):
        """(s (count,) with Im(s) > 0 by |s| [1/s], link-frame shapes (n_dofs, count) complex)
        at crank ``speed`` [rad/s]; None at a divergence (a real root pair: the stiffness at
        speed is not definite), which is never returned as a frequency."""
        n = len(self.k0)
        K, G = self.k0 + speed**2 * self.k2, speed * self.g1
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -G]])
        s, Z = la.eig(A)
        upper = np.flatnonzero(s.imag > 1e-9 * np.abs(s))
        if len(upper) < n:
            return None
        pick = upper[np.argsort(np.abs(s[upper]))[:count]]
        Y = Z[:n, pick]
        big = np.abs(Y).argmax(axis=0)
        Y = Y * np.exp(-1j * np.angle(Y[big, np.arange(count)]))
        return s[pick], self.frame @ Y


def reduce_pose(scene: Scene, state, topology, basis: int,
                form: GeometricForm = GeometricForm.CONSISTENT) -> tuple[ReducedPose, object]:
    """(the pose ``state`` reduced onto its lowest ``basis`` static modes, its link-frame mass
    matrix)."""
    model, static, _ = pose_modes(topology, state.points, basis)
    if MECHANISM in static.kinds:
        raise NumericalError(
            f"{scene.path}: the frame has a rigid-body/mechanism mode at crank angle "
            f"{math.degrees(state.q):.4g} deg: modes at speed need the crank held by its drive")
    T = rigid_elimination(model)
    column, n = reduced_columns(T, model.n_dofs)
    Kr, _ = assemble_reduced_dense(model, T)
    motion = rigid_motion(scene.linkage, state, 1.0, 0.0)  # every term at 1 rad/s
    omega, alpha, acc = link_motion(scene, model, topology, motion)

    def reduce(rows, cols, vals):
        return dense_sum(dense_slots(column, n, rows, cols), vals, n)

    def geometric(loads):
        forces = axial_forces(model, static_displacement(Kr, T, loads))
        return reduce(*geometric_entries(model, forces, form))

    rows, cols, rot = rotating_entries(model, omega, alpha)
    K2 = reduce(rows, cols, rot[0] + rot[2]) + geometric(inertia_loads(model, acc, alpha))
    G1 = reduce(rows, cols, rot[1])
    external = external_loads(scene, model, topology, state)
    K_ext = geometric(external) if np.any(external) else np.zeros((n, n))
    Phi = static.shapes[:, static.elastic[:basis]]
    keep = column >= 0
    P = np.zeros((n, Phi.shape[1]))
    P[column[keep]] = Phi[keep]  # the reduced coordinates of the static modes
    lam = (2 * math.pi * static.elastic_frequencies[:basis]) ** 2
    pose = ReducedPose(static_hz=static.elastic_frequencies[:basis],
                       k0=np.diag(lam) + P.T @ K_ext @ P, k2=P.T @ K2 @ P, g1=P.T @ G1 @ P,
                       frame=link_frame(model, Phi))
    return pose, link_frame_mass(model)


@dataclasses.dataclass(frozen=True)
class DynamicCampbell:
    """frequencies[k, i, j] [Hz] of tracked line j at pose i and speed speeds[k] [rad/s] (NaN
    from the first speed where some pose diverges); ``static``: the frozen-pose tracked lines
    (poses, lines) [Hz]; crank angles q [rad]; ``divergence``: (speed [rad/s], crank angle
    [rad]) of the first divergence on the grid, or None."""

    scene: str
    q: np.ndarray
    speeds: np.ndarray
    frequencies: np.ndarray
    static: np.ndarray
    basis: int
    divergence: tuple[float, float] | None = None

    @property
    def stable_speeds(self) -> int:
        """How many grid speeds, from the first, have no divergence."""
        return int(np.isfinite(self.frequencies).all(axis=(1, 2)).sum())

    def bands(self) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) (speeds, lines) [Hz]: each line's band over the cycle at each speed."""
        return self.frequencies.min(axis=1), self.frequencies.max(axis=1)


def dynamic_campbell(scene: Scene, speeds: np.ndarray, n_poses: int = 72, n_modes: int = 3,
                     elements_per_link: int | None = None, basis: int | None = None,
                     progress=None) -> DynamicCampbell:
    """The lowest ``n_modes`` operating-point modes at every pose of ``n_poses`` over the cycle
    and every crank speed of ``speeds`` [rad/s] (constant speed, ascending), each pose reduced
    onto its lowest ``basis`` static modes (default n_modes + SPARE + EXTRA), tracked by MAC
    per speed. Speeds from the first where a pose diverges on are left out (NaN)."""
    speeds = np.asarray(speeds, dtype=float)
    if (speeds.ndim != 1 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0)
            or np.any(np.diff(speeds) <= 0)):
        raise InputError("crank speeds must be finite, >= 0 and ascending", field="--speeds",
                         expected="0 <= low < high")
    count = n_modes + SPARE
    basis = basis or count + EXTRA
    if basis < count:
        raise ValueError(f"a basis of {basis} static modes cannot give {count} modes")
    cycle = kinematic_cycle(scene, n_poses)
    topology = scene.topology(elements_per_link)
    f = np.full((len(speeds), n_poses, count), np.nan)
    static = np.empty((n_poses, count))
    shapes = [[None] * n_poses for _ in speeds]
    static_shapes = []
    W, stop, divergence = None, len(speeds), None
    states = progress(cycle.states) if progress else cycle.states
    for i, state in enumerate(states):
        pose, mass = reduce_pose(scene, state, topology, basis)
        W = W if W is not None else sp.block_diag([mass, mass]).tocsr()
        static[i] = pose.static_hz[:count]
        frame = pose.frame[:, :count]
        static_shapes.append(np.vstack([frame, np.zeros_like(frame)]))
        for k in range(stop):
            found = pose.modes(speeds[k], count)
            if found is None:  # this speed and every higher one are out
                stop, divergence = k, (float(speeds[k]), float(state.q))
                break
            f[k, i] = np.abs(found[0].imag) / (2 * math.pi)
            shapes[k][i] = np.vstack([found[1].real, found[1].imag])
    f[stop:] = np.nan
    lines = np.full((len(speeds), n_poses, n_modes), np.nan)
    for k in range(stop):
        lines[k] = track(f[k], shapes[k], n_modes, W).frequencies
    frozen = track(static, static_shapes, n_modes, W).frequencies
    return DynamicCampbell(scene=scene.name, q=cycle.q, speeds=speeds, frequencies=lines,
                           static=frozen, basis=basis, divergence=divergence)


@dataclasses.dataclass(frozen=True)
class CriticalShift:
    """A critical speed range [rad/s] of mode ``mode`` and harmonic ``harmonic``: ``frozen``
    from the static bands, ``dynamic`` from the bands at speed (None where one has none)."""

    mode: int
    harmonic: int
    frozen: tuple[float, float] | None
    dynamic: tuple[float, float] | None


def dynamic_critical(result: DynamicCampbell, margin: float = 0.05,
                     harmonics: int = 10) -> list[CriticalSpeed]:
    """Crank speed ranges within result.speeds where harmonic n is within ``margin`` of mode
    j's band at that speed, edges interpolated linearly between grid speeds."""
    stable = result.stable_speeds
    low, high = (b[:stable] for b in result.bands())
    w = result.speeds[:stable]
    out = []
    for j in range(low.shape[1]):
        for n in range(1, harmonics + 1):
            f_n = n * w / (2 * math.pi)
            # <= 0 inside the band with its margin: the larger of the two edge excesses
            c = np.maximum(low[:, j] * (1 - margin) - f_n, f_n - high[:, j] * (1 + margin))
            inside = c <= 0
            k = 0
            while k < len(w):
                if not inside[k]:
                    k += 1
                    continue
                start = k
                while k + 1 < len(w) and inside[k + 1]:
                    k += 1
                a = w[start] if start == 0 else _root(w, c, start - 1)
                b = w[k] if k == len(w) - 1 else _root(w, c, k)
                out.append(CriticalSpeed(j + 1, n, float(a), float(b)))
                k += 1
    return out


def _root(w: np.ndarray, c: np.ndarray, k: int) -> float:
    """The zero of c between grid speeds k and k + 1 by linear interpolation."""
    return w[k] + (w[k + 1] - w[k]) * c[k] / (c[k] - c[k + 1])


def frozen_bands(result: DynamicCampbell) -> list[Band]:
    """The static (frozen-pose) bands, as ``campbell.bands``."""
    return bands(result.static)


def critical_shifts(result: DynamicCampbell, margin: float = 0.05,
                    harmonics: int = 10) -> list[CriticalShift]:
    """The critical ranges of the frozen-pose and the at-speed diagrams side by side, paired by
    mode, harmonic and overlap, over the grid's speeds below any divergence."""
    if result.stable_speeds < 2:
        return []
    window = (float(result.speeds[0]), float(result.speeds[result.stable_speeds - 1]))
    frozen = critical_speeds(frozen_bands(result), window, margin, harmonics)
    dynamic = dynamic_critical(result, margin, harmonics)
    out, used = [], set()
    for c in frozen:
        match = next((i for i, d in enumerate(dynamic) if i not in used and d.mode == c.mode
                      and d.harmonic == c.harmonic and d.low <= c.high and d.high >= c.low), None)
        if match is not None:
            used.add(match)
        d = dynamic[match] if match is not None else None
        out.append(CriticalShift(c.mode, c.harmonic, (c.low, c.high),
                                 None if d is None else (d.low, d.high)))
    out += [CriticalShift(d.mode, d.harmonic, None, (d.low, d.high))
            for i, d in enumerate(dynamic) if i not in used]
    return sorted(out, key=lambda s: (s.mode, s.harmonic))
