"""Speed-dependent Campbell diagram: each tracked mode's band over the crank cycle at each crank
speed, from the operating-point modes (``studies.running.modes_at_speed``) at every pose, against the
frozen-pose (static) bands.

At crank speed Omega and crank angular acceleration qddot every operating-point term of a pose
is a sum of powers of the two: the rigid accelerations (a = p'' Omega^2 + p' qddot,
alpha = L Omega^2 + K qddot), hence the d'Alembert preload, its axial forces and K_g(N), and
the circulatory alpha S are Omega^2 times their values at 1 rad/s plus qddot times their
values at 1 rad/s^2 from rest, the centrifugal -omega^2 Mt is Omega^2 times its value and the
gyroscopic G is Omega times its value (``fe.speed_terms``). So per pose
    M x'' + Omega G1 x' + (K + K_ext + Omega^2 K2 + qddot K1) x = 0,
with K_ext the geometric stiffness of the scene's constant [[loads]]; the same qddot is taken
at every speed and pose (the modes at that instant of a crank speeding up, not a run-up). Each
pose is projected once onto its lowest static modes Phi (mass normalised, ``basis`` of them:
Galerkin projection, M -> I, K -> diag(omega_i^2)), and every speed is then a small dense
quadratic eigenproblem. The projection is checked against the full ``operating_modes`` solve
in the tests.

Modes are tracked through the cycle at the first grid speed as the static cycle map tracks
them (``tracking.track``), and from there through the speeds at every pose: the modes at each
speed are paired with the previous speed's by MAC (each complex shape's phase fixed, largest
component real, its real and imaginary parts stacked), so a line is one mode continued in
speed, and two modes whose frequencies cross as the speed rises cross instead of swapping
lines. A line whose best MAC with the previous speed is below ``tracking.PAIR_MAC`` is
counted as ambiguous.

A divergence is where the stiffness at speed K + K_ext + Omega^2 K2 turns singular at some
pose: a mode's frequency falls to 0 Hz there and a real root pair +-sigma follows (the mode
grows). Its speed at each pose is the smallest real positive Omega^2 with
det(K + K_ext + Omega^2 K2) = 0, a small generalised eigenproblem of the projected matrices;
the diagram reports the lowest over the sampled poses, the line whose mode it is (the MAC of
the singular direction with the lines' shapes below it) and the growth rate sigma at the first
grid speed past it. Harmonic n is critical for mode j at speed Omega when
n Omega / (2 pi) lies in [f_min(Omega) (1 - m), f_max(Omega) (1 + m)]; the range edges are found
on the speed grid and interpolated linearly.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from flexlink.analysis.frame_motion import pose_speed_terms
from flexlink.analysis.runs import true_runs
from flexlink.analysis.mac import link_frame, link_frame_mass, mac_matrix, pair_modes
from flexlink.analysis.modal import pose_modes
from flexlink.analysis.solve import MECHANISM
from flexlink.errors import InputError, NumericalError
from flexlink.fe.assembly import (assemble_reduced_dense, eliminating_assembler,
                                  reduced_columns, rigid_elimination)
from flexlink.fe.geometric import GeometricForm
from flexlink.fe.speed_terms import speed_linear, speed_quadratic
from flexlink.scene import Scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.bands import Band, CriticalSpeed, bands, critical_speeds
from flexlink.studies.cycle.modal_map import kinematic_cycle
from flexlink.studies.cycle.tracking import PAIR_MAC, SPARE, track

EXTRA = 8  # static modes in each pose's basis beyond the ones solved at speed


@dataclasses.dataclass(frozen=True)
class ProjectedPose:
    """One pose's operating-point matrices on its static modes Phi (full DOFs, mass
    normalised): k0 = Phi^T (K + K_ext) Phi, k2, g1 and k1 the Omega^2, Omega and crank
    acceleration coefficients [1/s^2, -, 1/s, -]; ``frame``: Phi in link frames, for the MAC."""

    static_hz: np.ndarray  # the pose's static frequencies of the basis [Hz]
    k0: np.ndarray
    k2: np.ndarray
    g1: np.ndarray
    k1: np.ndarray
    frame: np.ndarray

    def __post_init__(self):
        n = len(self.static_hz)
        check_shape("ProjectedPose", "static_hz", self.static_hz, (n,))
        for name in ("k0", "k2", "g1", "k1"):
            check_shape("ProjectedPose", name, getattr(self, name), (n, n))
        check_shape("ProjectedPose", "frame", self.frame, (None, n))

    def stiffness(self, acceleration: float = 0.0) -> np.ndarray:
        """k0 + qddot k1: the stiffness at speed less its Omega^2 part [1/s^2]."""
        return self.k0 + acceleration * self.k1 if acceleration else self.k0

    def roots(self, speed: float, acceleration: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """(every root s (2 n,) [1/s], its shape (n,) in the basis) at crank ``speed`` [rad/s]
        and crank ``acceleration`` [rad/s^2]."""
        n = len(self.k0)
        K = speed_quadratic(speed, self.k0, self.k2, acceleration, self.k1)
        G = speed_linear(speed, 0.0, self.g1)
        s, Z = la.eig(np.block([[np.zeros((n, n)), np.eye(n)], [-K, -G]]))
        return s, Z[:n]

    def modes(self, speed: float, count: int, acceleration: float = 0.0):
        """(s (count,) with Im(s) > 0 by |s| [1/s], link-frame shapes (n_dofs, count) complex)
        at crank ``speed`` [rad/s] and ``acceleration`` [rad/s^2]; None at a divergence (a real
        root pair: the stiffness at speed is not definite), never returned as a frequency."""
        s, Y = self.roots(speed, acceleration)
        upper = np.flatnonzero(s.imag > 1e-9 * np.abs(s))
        if len(upper) < len(self.k0):
            return None
        pick = upper[np.argsort(np.abs(s[upper]))[:count]]
        Y = Y[:, pick]
        big = np.abs(Y).argmax(axis=0)
        Y = Y * np.exp(-1j * np.angle(Y[big, np.arange(count)]))
        return s[pick], self.frame @ Y

    def growth_rate(self, speed: float, acceleration: float = 0.0) -> float:
        """The largest real part of the roots at ``speed`` [rad/s] and ``acceleration``
        [rad/s^2] [1/s]."""
        return float(self.roots(speed, acceleration)[0].real.max())

    def divergence_speed(self, acceleration: float = 0.0) -> tuple[float, np.ndarray | None]:
        """(the lowest crank speed [rad/s] at which the stiffness at speed
        k0 + qddot k1 + Omega^2 k2 is singular (inf if none), the link-frame shape of its null
        direction)."""
        mu, X = la.eig(self.stiffness(acceleration), -self.k2)
        real = np.isfinite(mu) & (np.abs(mu.imag) <= 1e-9 * np.abs(mu)) & (mu.real > 0)
        if not real.any():
            return math.inf, None
        k = np.flatnonzero(real)[np.argmin(mu.real[real])]
        x = X[:, k] * np.exp(-1j * np.angle(X[np.abs(X[:, k]).argmax(), k]))
        return math.sqrt(mu.real[k]), self.frame @ x.real


def project_pose(scene: Scene, state, topology, basis: int,
                 form: GeometricForm = GeometricForm.CONSISTENT) -> tuple[ProjectedPose, object]:
    """(the pose ``state`` projected onto its lowest ``basis`` static modes, its link-frame
    mass matrix)."""
    model, static, _ = pose_modes(topology, state.points, basis)
    if MECHANISM in static.kinds:
        raise NumericalError(
            f"{scene.path}: the frame has a rigid-body/mechanism mode at crank angle "
            f"{math.degrees(state.q):.4g} deg: modes at speed need the crank held by its drive")
    T = rigid_elimination(model)
    column, n = reduced_columns(T, model.n_dofs)
    Kr, _ = assemble_reduced_dense(model, T)
    terms = pose_speed_terms(scene, topology, state, model, Kr, T,
                             eliminating_assembler(column, n, dense=True), form,
                             accelerating=True)
    Phi = static.shapes[:, static.elastic[:basis]]
    keep = column >= 0
    P = np.zeros((n, Phi.shape[1]))
    P[column[keep]] = Phi[keep]  # the eliminated coordinates of the static modes
    lam = (2 * math.pi * static.elastic_frequencies[:basis]) ** 2
    pose = ProjectedPose(static_hz=static.elastic_frequencies[:basis],
                         k0=np.diag(lam) + P.T @ terms.constant() @ P,
                         k2=P.T @ terms.squared() @ P, g1=P.T @ terms.linear() @ P,
                         k1=P.T @ terms.accelerated() @ P, frame=link_frame(model, Phi))
    return pose, link_frame_mass(model)


@dataclasses.dataclass(frozen=True)
class Divergence:
    """A mode that diverges within the speed grid: at crank speed ``speed`` [rad/s] the
    stiffness at speed turns singular at the pose of crank angle ``q`` [rad] (the lowest such
    speed over the sampled poses), tracked line ``line`` (1-based; None if none of the lines)
    falls to 0 Hz there, and at ``grid_speed`` [rad/s], the first grid speed where some pose
    has a real root pair, the largest root is ``growth_rate`` [1/s] > 0."""

    speed: float | None
    q: float
    line: int | None
    grid_speed: float
    growth_rate: float

    def __post_init__(self):
        for name in ("speed", "q", "grid_speed", "growth_rate"):
            value = getattr(self, name)
            if not (value is None and name == "speed"):
                check_shape("Divergence", name, value, ())
        if self.line is not None and self.line < 1:
            raise ValueError(f"Divergence.line is {self.line}, expected a 1-based line or None")


@dataclasses.dataclass(frozen=True)
class DynamicCampbell:
    """frequencies[k, i, j] [Hz] of tracked line j at pose i and speed speeds[k] [rad/s] (NaN
    from the first speed where some pose diverges); ``static``: the frozen-pose tracked lines
    (poses, lines) [Hz]; crank angles q [rad]; ``divergence`` within the grid, or None;
    ``crank_acceleration`` [rad/s^2] the same at every speed;
    ``ambiguous``: how many (speed, pose, line) steps paired with the previous speed below
    ``tracking.PAIR_MAC``."""

    scene: str
    q: np.ndarray
    speeds: np.ndarray
    frequencies: np.ndarray
    static: np.ndarray
    basis: int
    divergence: Divergence | None = None
    ambiguous: int = 0
    crank_acceleration: float = 0.0  # [rad/s^2], the same at every speed and pose

    def __post_init__(self):
        poses, speeds = len(self.q), len(self.speeds)
        check_shape("DynamicCampbell", "q", self.q, (poses,))
        check_shape("DynamicCampbell", "speeds", self.speeds, (speeds,))
        check_shape("DynamicCampbell", "frequencies", self.frequencies, (speeds, poses, None))
        check_shape("DynamicCampbell", "static", self.static,
                    (poses, np.shape(self.frequencies)[2]))

    @property
    def stable_speeds(self) -> int:
        """How many grid speeds, from the first, have no divergence."""
        return int(np.isfinite(self.frequencies).all(axis=(1, 2)).sum())

    def bands(self) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) (speeds, lines) [Hz]: each line's band over the cycle at each speed."""
        return self.frequencies.min(axis=1), self.frequencies.max(axis=1)


def dynamic_campbell(scene: Scene, speeds: np.ndarray, n_poses: int = 72, n_modes: int = 3,
                     elements_per_link: int | None = None, basis: int | None = None,
                     progress=None, crank_acceleration: float = 0.0) -> DynamicCampbell:
    """The lowest ``n_modes`` operating-point modes at every pose of ``n_poses`` over the cycle
    and every crank speed of ``speeds`` [rad/s] (ascending) with the crank angular acceleration
    ``crank_acceleration`` [rad/s^2] (default 0: constant speed), each pose projected
    onto its lowest ``basis`` static modes (default n_modes + SPARE + EXTRA), tracked by MAC
    through the cycle at the first speed and through the speeds at every pose. Speeds from the
    first where a pose diverges on are left out (NaN)."""
    speeds = np.asarray(speeds, dtype=float)
    if (speeds.ndim != 1 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0)
            or np.any(np.diff(speeds) <= 0)):
        raise InputError("crank speeds must be finite, >= 0 and ascending", field="speeds",
                         expected="0 <= low < high")
    if not math.isfinite(crank_acceleration):
        raise InputError(f"got {crank_acceleration!r} rad/s^2", field="crank_acceleration",
                         expected="a finite angular acceleration")
    count = n_modes + SPARE
    basis = basis or count + EXTRA
    if basis < count:
        raise ValueError(f"a basis of {basis} static modes cannot give {count} modes")
    cycle = kinematic_cycle(scene, n_poses)
    topology = scene.topology(elements_per_link)
    # f[k, i, m]: mode m of pose i at the first speed, continued to speed k by MAC
    f = np.full((len(speeds), n_poses, count), np.nan)
    paired = np.ones((len(speeds), n_poses, count))
    static = np.empty((n_poses, count))
    first, static_shapes = [], []
    W, stop = None, len(speeds)
    lowest = (math.inf, None, None, None)  # (speed, pose, continued mode, pose's projection)
    states = progress(cycle.states) if progress else cycle.states
    for i, state in enumerate(states):
        pose, mass = project_pose(scene, state, topology, basis)
        W = W if W is not None else sp.block_diag([mass, mass]).tocsr()
        static[i] = pose.static_hz[:count]
        frame = pose.frame[:, :count]
        static_shapes.append(np.vstack([frame, np.zeros_like(frame)]))
        previous = None
        for k in range(min(stop + 1, len(speeds))):
            found = pose.modes(speeds[k], count, crank_acceleration)
            if found is None:  # this speed and every higher one are out
                stop = k
                break
            if k == stop:
                break
            shapes = np.vstack([found[1].real, found[1].imag])
            order, paired[k, i] = np.arange(count), 1.0
            if previous is not None:
                pairs = pair_modes(np.nan_to_num(mac_matrix(previous, shapes, W)))
                order, paired[k, i] = pairs.b, pairs.mac
            f[k, i] = np.abs(found[0].imag)[order] / (2 * math.pi)
            previous = shapes[:, order]
            if k == 0:
                first.append(previous)
        critical, null = pose.divergence_speed(crank_acceleration)
        if critical < lowest[0] and previous is not None:
            shape = np.concatenate([null, np.zeros_like(null)])[:, None]
            m = int(np.argmax(np.nan_to_num(mac_matrix(previous, shape, W))[:, 0]))
            lowest = (critical, i, m, pose)
        elif critical < lowest[0]:
            lowest = (critical, i, None, pose)
    f[stop:] = np.nan
    lines = np.full((len(speeds), n_poses, n_modes), np.nan)
    ambiguous, start = 0, None
    if stop > 0:
        start = track(f[0], first, n_modes, W).rank  # (poses, lines): the mode of each line
        lines[:stop] = np.take_along_axis(f[:stop], start[None], axis=2)
        ambiguous = int((np.take_along_axis(paired[:stop], start[None], axis=2)
                         < PAIR_MAC).sum())
    frozen = track(static, static_shapes, n_modes, W).frequencies
    return DynamicCampbell(scene=scene.name, q=cycle.q, speeds=speeds, frequencies=lines,
                           static=frozen, basis=basis, ambiguous=ambiguous,
                           crank_acceleration=float(crank_acceleration),
                           divergence=_divergence(speeds, stop, cycle.q, lowest, start,
                                                  crank_acceleration))


def _divergence(speeds, stop: int, q, lowest, start, acceleration) -> Divergence | None:
    """The divergence record, when some pose diverges on the grid (``stop`` < len)."""
    if stop == len(speeds):
        return None
    critical, i, m, pose = lowest
    if pose is None:
        return Divergence(None, float(q[0]), None, float(speeds[stop]), math.nan)
    line = None
    if start is not None and m is not None and m in start[i]:
        line = int(np.flatnonzero(start[i] == m)[0]) + 1
    return Divergence(speed=float(critical) if math.isfinite(critical) else None,
                      q=float(q[i]), line=line, grid_speed=float(speeds[stop]),
                      growth_rate=pose.growth_rate(float(speeds[stop]), acceleration))


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
            for start, stop in true_runs(c <= 0):
                k = stop - 1
                a = w[start] if start == 0 else _root(w, c, start - 1)
                b = w[k] if k == len(w) - 1 else _root(w, c, k)
                out.append(CriticalSpeed(j + 1, n, float(a), float(b)))
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
