"""Parametric stability of the running linkage over crank speed (Floquet).

Model: at crank speed Omega the elastic motion about the rigid motion obeys, with
theta = Omega t the crank angle,
    M(theta) x'' + (C + Omega G1(theta)) x' + (K(theta) + K_ext(theta) + Omega^2 K2(theta)) x = 0,
the operating-point matrices of ``studies.running.modes_at_speed`` taken at each crank angle (frozen
configuration at each instant; at constant crank speed the inertia preload, the centrifugal and
the link angular-acceleration terms all scale with Omega^2, the Coriolis matrix with Omega).
The matrices are assembled once, at ``poses`` equally spaced crank angles, at Omega = 0 and 1
rad/s, and interpolated in theta by their Fourier series (exact for a trigonometric
polynomial of degree below poses/2), in co-rotating node coordinates. They are projected on
the basis of ``analysis.pose_basis`` (the static modes of the poses over the turn, reduced by
SVD and checked against every pose's own lowest frequencies), given as the scene pose's Ritz
vectors, in which the damping is modal: C = diag(2 zeta_i omega_i), a ratio per vector from
``studies.running.periodic_damping`` (given, else the scene's declared damping, else a default). The
period is one revolution, T = 2 pi / Omega.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import logging

import numpy as np

from flexlink.analysis import adiabatic
from flexlink.analysis.floquet import FloquetResult, floquet, monodromy
from flexlink.analysis.fourier import fourier_coefficients
from flexlink.analysis.modal import pose_modes
from flexlink.analysis.pose_basis import DEFAULT_TOLERANCE, PoseBasis, pose_basis
from flexlink.analysis.solve import MECHANISM
from flexlink.errors import InputError, NumericalError
from flexlink.fe.assembly import reduced_columns, rigid_elimination
from flexlink.fe.geometric import GeometricForm, geometric_entries
from flexlink.fe.co_rotating import co_rotating_turn, link_angles
from flexlink.fe.model_at_pose import pose_model
from flexlink.fe.preload import axial_forces, inertia_loads, static_displacement
from flexlink.fe.rotating import rotating_entries
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.parallel import on_cluster, run_tasks, workers
from flexlink.scene import Scene
from flexlink.studies.running.modes_at_speed import external_loads, link_motion, reduced_pair, reducer
from flexlink.studies.running.periodic_damping import basis_damping, checked_ratio

log = logging.getLogger(__name__)
ADIABATIC_GRID = 2048  # crank angles of the adiabatic basis per turn: 1024 steps at most
ADIABATIC_STEPS = 64  # equal adiabatic steps a turn at least, then halved where Q needs:
# ln |mu| per turn within the map's 1e-3 (docs/critical-speeds.md, "Convergence")
FLOOR_POINTS = 4  # crank angles per sampled pose where the stiffness floor is sought


class Integrator(enum.Enum):
    """How a speed's monodromy is integrated: ADIABATIC (the default), the
    interaction-picture steps of ``analysis.adiabatic``, whose count does not follow the
    stiffest frequency; MAGNUS, the fourth-order Magnus steps of ``analysis.floquet`` (h
    omega_max <= step_phase), as accurate and many times slower below a few thousand rev/min
    (docs/critical-speeds.md, "Speed")."""

    MAGNUS = "magnus"
    ADIABATIC = "adiabatic"


@dataclasses.dataclass(frozen=True)
class PeriodicModel:
    """The periodic equations in a reduced basis, sampled at ``angles`` [rad].

    mass, coriolis (per rad/s), stiffness (at Omega = 0), speed_stiffness (per (rad/s)^2):
    (poses, n, n); frequencies (n,): the basis vectors' Ritz frequencies at the scene's pose
    [Hz], which set the modal damping C = diag(2 zeta_i omega_i); damping_ratio (n,) [-]: zeta_i
    per basis vector (a single number is taken for every vector); basis: how the basis was
    built and its check (``analysis.pose_basis``), None for equations given directly; then the
    first ``checked`` frequencies are those the check covers (all of them without a basis);
    damping_source: where the ratios came from, for the outputs."""

    angles: np.ndarray
    mass: np.ndarray
    coriolis: np.ndarray
    stiffness: np.ndarray
    speed_stiffness: np.ndarray
    frequencies: np.ndarray
    damping_ratio: np.ndarray
    basis: PoseBasis | None = None
    damping_source: str = "given with the equations"

    def __post_init__(self):
        ratios = np.broadcast_to(np.asarray(self.damping_ratio, dtype=float),
                                 np.shape(self.frequencies)).copy()
        if not (np.all(np.isfinite(ratios)) and np.all(ratios >= 0.0)):
            raise ValueError(f"damping ratios must be finite and >= 0, got {ratios}")
        object.__setattr__(self, "damping_ratio", ratios)

    @property
    def checked(self) -> np.ndarray:
        """The scene pose's lowest frequencies [Hz] the basis was checked on (the modes the
        unstable ranges are labelled with)."""
        return self.frequencies if self.basis is None else self.basis.exact[0]

    def matrices_at(self, theta: np.ndarray) -> tuple[np.ndarray, ...]:
        """(M, G1, K, K2) at crank angles theta (m,) [rad] by Fourier interpolation."""
        relative = np.asarray(theta, dtype=float) - self.angles[0]
        return tuple(fourier_series(a, relative) for a in
                     (self.mass, self.coriolis, self.stiffness, self.speed_stiffness))

    def stiffness_floor(self, speed: float) -> float:
        """The lowest eigenvalue [(rad/s)^2] over the turn (FLOOR_POINTS points per sampled
        pose) of the symmetric part of K + speed^2 K2, mass weighted: negative where the
        frozen frame buckles under its own inertia at that speed (a quasi-static divergence,
        not a parametric resonance), or at rest where the interpolation between poses fails."""
        at_rest, per_speed = self._floor_pencil
        return float(np.linalg.eigvalsh(at_rest + speed**2 * per_speed)[:, 0].min())

    @functools.cached_property
    def _floor_pencil(self) -> tuple[np.ndarray, np.ndarray]:
        """L sym(K) L^T and L sym(K2) L^T at FLOOR_POINTS points per sampled pose, L L^T =
        M^-1 (the mass weighting is the same at every speed)."""
        theta = self.angles[0] + np.linspace(0.0, 2.0 * np.pi, FLOOR_POINTS * len(self.angles),
                                             endpoint=False)
        M, _, K, K2 = self.matrices_at(theta)
        L = np.linalg.inv(np.linalg.cholesky(M))
        return tuple(L @ (0.5 * (A + np.swapaxes(A, -1, -2))) @ np.swapaxes(L, -1, -2)
                     for A in (K, K2))

    @functools.cached_property
    def _first_order_samples(self) -> np.ndarray:
        """(poses, 4, n, n): M^-1 C, M^-1 G1, M^-1 K, M^-1 K2 at each sampled pose, the blocks
        of A that are interpolated (linear in C + Omega G1 and K + Omega^2 K2, so one series
        serves every speed; exact at the samples like the matrices' own series)."""
        damping = np.diag(2.0 * self.damping_ratio * 2.0 * np.pi * self.frequencies)
        blocks = np.stack(np.broadcast_arrays(damping, self.coriolis, self.stiffness,
                                              self.speed_stiffness), axis=1)
        return np.linalg.solve(self.mass[:, None], blocks)

    @functools.cached_property
    def energy_scale(self) -> np.ndarray:
        """R (n, n) [rad/s]: the symmetric square root of the turn's mean mass-weighted
        stiffness at rest, L sym(K) L^T (L L^T = M^-1, ``_floor_pencil``: positive definite
        at every point, as the model refuses it otherwise; the symmetric part of M^-1 K need
        not be, on the wiper it is not). In the coordinates (R q, q') the stiffness and
        velocity parts of the state weigh alike, so A's norm is near its spectral radius
        there (in (q, q') it is up to 65 times larger on Table II case 1, and each doubling
        is one more squaring in every step's exponential)."""
        values, vectors = np.linalg.eigh(self._floor_pencil[0].mean(axis=0))
        return (vectors * np.sqrt(values)) @ vectors.T

    @property
    def adiabatic(self) -> adiabatic.AdiabaticBasis:
        """A0, A0', A1, A2 of dx/dtheta = (A0 / Omega + A1 + Omega A2) x, x = (q, q'),
        decomposed over ADIABATIC_GRID crank angles (``analysis.adiabatic``): built once, used
        at every speed; its refusal (NumericalError) is kept and raised again, not rebuilt."""
        built = self._adiabatic_or_refusal
        if isinstance(built, NumericalError):
            raise built.with_traceback(None)  # a kept refusal, not a growing traceback
        return built

    @functools.cached_property
    def _adiabatic_or_refusal(self) -> adiabatic.AdiabaticBasis | NumericalError:
        samples = self._first_order_samples
        n = samples.shape[-1]
        theta = 2.0 * np.pi * np.arange(ADIABATIC_GRID + 1) / ADIABATIC_GRID
        a0, a0_prime, a1, a2 = (np.zeros((len(theta), 2 * n, 2 * n)) for _ in range(4))
        a0[:, :n, n:] = np.eye(n)
        for order, out in ((0, a0), (1, a0_prime)):
            out[:, n:, :n] = -fourier_series(samples[:, 2], theta, order)
            out[:, n:, n:] = -fourier_series(samples[:, 0], theta, order)
        a1[:, n:, n:] = -fourier_series(samples[:, 1], theta)
        a2[:, n:, :n] = -fourier_series(samples[:, 3], theta)
        try:
            return adiabatic.adiabatic_basis(self.angles[0] + theta, a0, a0_prime, a1, a2)
        except NumericalError as refusal:
            return refusal

    def system(self, speed: float, *, energy_coordinates: bool = False):
        """times (m,) [s] -> A(t) (m, 2n, 2n) at crank speed ``speed`` [rad/s], t = 0 at the
        scene's pose, for the state (q, q'), or with ``energy_coordinates`` for (R q, q'), R
        the ``energy_scale`` (the same multipliers; a similarity, exact)."""
        samples = self._first_order_samples
        n = samples.shape[-1]
        weights = np.array([1.0, speed, 1.0, speed**2])[:, None, None]
        damping = (samples[:, :2] * weights[:2]).sum(axis=1)
        stiffness = (samples[:, 2:] * weights[2:]).sum(axis=1)
        coupling = np.eye(n)
        if energy_coordinates:  # [[0, R], [-K R^-1, -D]] = S A S^-1, S = diag(R, I)
            coupling = self.energy_scale
            stiffness = np.linalg.solve(coupling, np.swapaxes(stiffness, -1, -2))
            stiffness = np.swapaxes(stiffness, -1, -2)

        def a(t):
            theta = speed * np.asarray(t, dtype=float)
            out = np.zeros(theta.shape + (2 * n, 2 * n))
            out[..., :n, n:] = coupling
            out[..., n:, :n] = -fourier_series(stiffness, theta)
            out[..., n:, n:] = -fourier_series(damping, theta)
            return out
        return a


def fourier_series(samples: np.ndarray, theta: np.ndarray, derivative: int = 0) -> np.ndarray:
    """Trigonometric interpolation over one turn of samples (N, ...) taken at N equal steps
    from angle 0, at angles theta (m,) [rad]: N odd, so every harmonic has its pair and the
    interpolant is real; evaluated as a real cosine-sine sum. ``derivative``: 0 for the
    interpolant, 1 for its exact derivative in theta [per rad]."""
    c = fourier_coefficients(samples)
    k = np.arange(c.shape[0])
    angle = np.outer(theta, k)
    flat = c.reshape(c.shape[0], -1)
    weights = np.full(c.shape[0], 2.0)
    weights[0] = 1.0
    if derivative:  # d/dtheta (a cos k theta - b sin k theta) = -k (a sin + b cos)
        values = -np.sin(angle) @ ((k * weights)[:, None] * flat.real) \
            - np.cos(angle) @ ((k * weights)[:, None] * flat.imag)
        return values.reshape(np.shape(theta) + samples.shape[1:])
    values = np.cos(angle) @ (weights[:, None] * flat.real) \
        - np.sin(angle) @ (weights[:, None] * flat.imag)
    return values.reshape(np.shape(theta) + samples.shape[1:])


def periodic_model(scene: Scene, n_modes: int = 6, poses: int = 37,
                   damping_ratio: float | None = None,
                   elements_per_link: int | None = None, basis_size: int | None = None,
                   tolerance: float = DEFAULT_TOLERANCE) -> PeriodicModel:
    """The periodic equations of ``scene`` over one crank turn, sampled at ``poses`` (odd)
    crank angles from the scene's pose, in the basis of ``analysis.pose_basis``: the lowest
    ``n_modes`` static modes of every other pose in co-rotating coordinates, reduced by SVD
    to ``basis_size`` vectors (None: the fewest whose lowest ``n_modes`` frequencies match the
    full model's at every pose to ``tolerance``), given as the scene pose's Ritz vectors.
    ``damping_ratio`` [-]: every vector's, else (None) the scene's declared damping
    (``studies.running.periodic_damping``)."""
    if poses < 3 or poses % 2 == 0:
        raise InputError(f"poses must be an odd count of at least 3, got {poses}")
    if damping_ratio is not None:  # refused before any work
        checked_ratio(damping_ratio)
    topology = scene.topology(elements_per_link)
    state0 = scene.rigid_state(None)
    model0, static, _ = pose_modes(topology, state0.points, n_modes)
    if MECHANISM in static.kinds:
        raise NumericalError(f"{scene.path}: the frame has a mechanism mode at its pose: the "
                             "stability map needs the crank held by its drive")
    T = rigid_elimination(model0)
    column, n = reduced_columns(T, model0.n_dofs)
    reduce = reducer(column, n, dense=True)
    angles = state0.q + 2.0 * np.pi * np.arange(poses) / poses
    full = np.empty((5, poses, n, n))  # M, G1, K, K_ext, K2 in co-rotating DOFs
    for p, angle in enumerate(angles):
        full[:, p] = _pose_matrices(scene, topology, angle, T, n, reduce, link_angles(model0))
    basis = pose_basis(full[2], full[0], n_modes, basis_size, tolerance)
    M, G1, K, K_ext, K2 = (basis.vectors.T @ A @ basis.vectors for A in full)
    # at the scene's pose the co-rotating DOFs are the global ones
    shapes = basis.vectors if T is None else np.asarray(T @ basis.vectors)
    damping = basis_damping(scene, damping_ratio, 2.0 * np.pi * basis.frequencies, model0,
                            shapes)
    model = PeriodicModel(angles=angles, mass=M, coriolis=G1, stiffness=K + K_ext,
                          speed_stiffness=K2, frequencies=basis.frequencies,
                          damping_ratio=damping.ratios, basis=basis,
                          damping_source=damping.source)
    floor = model.stiffness_floor(0.0)
    if floor <= 0.0:
        raise NumericalError(
            f"{scene.path}: between the {poses} sampled poses the interpolated stiffness is "
            f"indefinite (lowest eigenvalue {floor:.3g} (rad/s)^2 at rest): the basis' stiff "
            "directions change faster than the poses resolve; use more poses")
    return model


def _pose_matrices(scene, topology, angle, T, n, reduce, reference):
    """(M, G1, K, K_ext, K2) at crank ``angle`` [rad], dense, in co-rotating reduced DOFs."""
    state = scene.rigid_state(angle)
    model = pose_model(topology, state.points)
    K, M = reduced_pair(model, T, n, reduce)
    K = K.toarray() if hasattr(K, "toarray") else K
    M = M.toarray() if hasattr(M, "toarray") else M
    K_ext = _geometric(model, K, T, reduce, external_loads(scene, model, topology, state))
    omega, alpha, acc = link_motion(scene, model, topology, rigid_motion(
        scene.linkage, state, 1.0, 0.0))
    rows, cols, rot = rotating_entries(model, omega, alpha)
    G1 = reduce(rows, cols, rot[1])
    K2 = reduce(rows, cols, rot[0] + rot[2]) + _geometric(model, K, T, reduce,
                                                          inertia_loads(model, acc, alpha))
    R = co_rotating_turn(model, reference, T)
    return tuple(R.T @ np.asarray(A) @ R for A in (M, G1, K, K_ext, K2))


def _geometric(model, Kr, T, reduce, loads):
    """Reduced K_g of the axial forces that ``loads`` put in the frame held by its drive."""
    forces = axial_forces(model, static_displacement(Kr, T, loads))
    return reduce(*geometric_entries(model, forces, GeometricForm.CONSISTENT))


STEP_PHASE = 2.0  # h omega_max bound [rad]: ln|mu| within 1.3e-4 per turn of h omega_max 0.5


def speed_multipliers(model: PeriodicModel, speed: float, steps: int = 200,
                      step_phase: float = STEP_PHASE,
                      integrator: Integrator = Integrator.ADIABATIC,
                      adiabatic_steps: int = ADIABATIC_STEPS) -> FloquetResult:
    """Floquet multipliers over one revolution at crank ``speed`` [rad/s] (> 0). With
    ``Integrator.ADIABATIC``, by ``adiabatic_steps`` equal adiabatic steps at least (more
    where the damping needs them), each halved where the couplings need it
    (``adiabatic.step_bounds``), and by the Magnus steps where the adiabatic basis
    refuses or its grid cannot give them (logged). With ``Integrator.MAGNUS``, by at least
    ``steps`` Magnus steps, and more where needed to keep h max|eig A| <= ``step_phase``: at
    low speed one revolution spans many periods of the highest basis frequency, and the
    Magnus step's error grows with h omega_max (docs/critical-speeds.md, convergence)."""
    return _multipliers(model, speed, steps, step_phase, integrator, adiabatic_steps)[0]


def _multipliers(model, speed, steps, step_phase, integrator, adiabatic_steps):
    """``speed_multipliers`` and the integrator that gave them."""
    if integrator is Integrator.ADIABATIC:
        try:
            return (adiabatic.adiabatic_monodromy(model.adiabatic, speed, adiabatic_steps),
                    Integrator.ADIABATIC)
        except NumericalError as error:
            log.warning("adiabatic steps refused at %.6g rad/s (%s): Magnus steps there",
                        speed, error)
    period = 2.0 * np.pi / speed
    system = model.system(speed, energy_coordinates=True)
    size = np.abs(np.linalg.eigvals(system((model.angles - model.angles[0]) / speed))).max()
    scaled = monodromy(system, period, max(steps, int(np.ceil(period * size / step_phase))))
    n = len(model.frequencies)
    scale = np.eye(2 * n)
    scale[:n, :n] = model.energy_scale
    return floquet(np.linalg.solve(scale, scaled.monodromy @ scale), period), Integrator.MAGNUS


@dataclasses.dataclass(frozen=True)
class InstabilityRange:
    """Adjacent unstable speeds [rad/s], the nearest resonance (modes 1-based, kind
    "primary" 2 f_i / k or "combination" (f_i + f_j) / k) and the largest growth rate [1/s]."""

    low: float
    high: float
    modes: tuple[int, ...]
    harmonic: int
    kind: str  # "primary", "combination", or "divergence" (K + Omega^2 K2 indefinite)
    growth_rate: float


@dataclasses.dataclass(frozen=True)
class StabilityMap:
    """Per speed [rad/s]: the largest multiplier modulus [-], growth rate [1/s] and stiffness
    floor [(rad/s)^2] (``PeriodicModel.stiffness_floor``: negative where the frozen frame is
    quasi-statically divergent at some crank angle); integrator: how the monodromies were
    integrated, and ``magnus_fallback`` (bool per speed): where the adiabatic steps were
    refused and the Magnus steps taken instead."""

    speeds: np.ndarray
    largest_modulus: np.ndarray
    growth_rate: np.ndarray
    ranges: tuple[InstabilityRange, ...]
    stiffness_floor: np.ndarray
    integrator: Integrator
    magnus_fallback: np.ndarray


def stability_map(model: PeriodicModel, speeds: np.ndarray, steps: int = 200,
                  harmonics: int = 6, show_progress: bool = False,
                  step_phase: float = STEP_PHASE,
                  integrator: Integrator = Integrator.ADIABATIC,
                  adiabatic_steps: int = ADIABATIC_STEPS) -> StabilityMap:
    """The largest Floquet multiplier over ``speeds`` [rad/s]. At zero speed the equations do
    not vary: nothing is parametrically excited, the modulus is 1 and the rate 0 by definition
    (the damped modes decay). The speeds go out in chunks through ``parallel.run_tasks``: in
    this process, or on the dask cluster of ``parallel.use_scheduler`` (each speed is
    computed alone, so the result is the same wherever it runs); ``show_progress``: a bar;
    ``integrator``, ``adiabatic_steps``: as ``speed_multipliers``."""
    speeds = np.asarray(speeds, dtype=float)
    # on a cluster a few chunks per worker; here one speed a chunk, for the bar
    count = 4 * workers(n_jobs=1) if on_cluster() else len(speeds)
    chunks = np.array_split(np.arange(len(speeds)), max(1, min(len(speeds), count)))
    parts = run_tasks(_speed_chunk, [(model, speeds[c], steps, step_phase, integrator,
                                      adiabatic_steps) for c in chunks],
                      n_jobs=1, show_progress=show_progress, label="speed chunks")
    modulus = np.concatenate([p[0] for p in parts])
    rate = np.concatenate([p[1] for p in parts])
    fallback = np.concatenate([p[2] for p in parts])
    floor = np.array([model.stiffness_floor(w) for w in speeds])
    return StabilityMap(speeds, modulus, rate,
                        _ranges(model, speeds, modulus, rate, floor, harmonics), floor,
                        integrator, fallback)


def _speed_chunk(model: PeriodicModel, speeds: np.ndarray, steps: int, step_phase: float,
                 integrator: Integrator, adiabatic_steps: int):
    """(largest modulus, growth rate, Magnus steps taken for refused adiabatic ones) at each
    of ``speeds`` [rad/s]."""
    modulus, rate = np.ones(len(speeds)), np.zeros(len(speeds))
    fallback = np.zeros(len(speeds), dtype=bool)
    for i, speed in enumerate(speeds):
        if speed > 0.0:
            result, used = _multipliers(model, speed, steps, step_phase, integrator,
                                        adiabatic_steps)
            modulus[i], rate[i] = result.largest_modulus, result.growth_rate
            fallback[i] = used is not integrator
    return modulus, rate, fallback


def _ranges(model, speeds, modulus, rate, floor, harmonics):
    """Runs of unstable speeds, each labelled with the nearest parametric resonance, or as a
    "divergence" (no modes, harmonic 0) when the stiffness is indefinite somewhere in it."""
    unstable = np.concatenate([[False], modulus > 1.0, [False]])
    starts, ends = np.flatnonzero(np.diff(unstable.astype(int)) == 1), \
        np.flatnonzero(np.diff(unstable.astype(int)) == -1)
    out = []
    for a, b in zip(starts, ends):
        low, high = speeds[a], speeds[b - 1]
        middle = 0.5 * (low + high) / (2.0 * np.pi)  # rev/s
        modes, k, kind = _nearest(model.checked, middle, harmonics)
        if floor[a:b].min() < 0.0:
            modes, k, kind = (), 0, "divergence"
        out.append(InstabilityRange(float(low), float(high), modes, k, kind,
                                    float(rate[a:b].max())))
    return tuple(out)


def _nearest(frequencies, revolutions, harmonics):
    """The parametric resonance (f_i + f_j) / k nearest ``revolutions`` [rev/s]."""
    best = None
    n = len(frequencies)
    for i in range(n):
        for j in range(i, n):
            for k in range(1, harmonics + 1):
                gap = abs((frequencies[i] + frequencies[j]) / k - revolutions)
                if best is None or gap < best[0]:
                    kind = "primary" if i == j else "combination"
                    best = (gap, (i + 1,) if i == j else (i + 1, j + 1), k, kind)
    return best[1:]
