"""The periodic equations of the running linkage over one crank turn, and their Floquet
multipliers at a crank speed.

Model: at crank speed Omega the elastic motion about the rigid motion obeys, with
theta = Omega t the crank angle,
    M(theta) x'' + (C(theta) + Omega G1(theta)) x'
        + (K(theta) + K_ext(theta) + Omega^2 K2(theta)) x = Omega^2 f2(theta) + f_ext(theta),
the speed terms of ``fe.speed_terms`` taken at each crank angle (frozen configuration at each
instant; at constant crank speed the inertia preload, the centrifugal and the link
angular-acceleration terms and the d'Alembert loads all scale with Omega^2, the Coriolis matrix
with Omega). The matrices and loads are assembled once, at ``poses`` equally spaced crank angles,
per unit speed (``analysis.frame_motion.pose_speed_terms``), and interpolated in theta by their
Fourier series (``analysis.fourier``: exact for a trigonometric polynomial of degree below
poses/2), in co-rotating node coordinates (``fe.co_rotating``). They are projected on the basis
of ``analysis.pose_basis`` (the static modes of the poses over the turn, compressed by SVD and
checked against every pose's own lowest frequencies), given as the scene pose's Ritz vectors.
The damping C(theta) is each pose's own (``analysis.damping.deformation_damping``): modal over
the pose's modes in the basis, so it acts on the rate of the elastic deformation at that pose.
A damping fixed in the basis, diag(2 zeta_i omega_i) of the scene pose's Ritz vectors at every
pose, would instead act on the basis's own motion: the links' co-rotating frames turn against
each other over the turn, so the pins' translations carried with them read, in the scene
pose's terms, as stretches of the stiff pin springs, and the stiff vectors' damping (large
under Rayleigh's beta K) resists the quasi-static response itself. The period is one
revolution, T = 2 pi / Omega.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import logging
from collections.abc import Callable

import numpy as np
import scipy.linalg as sla

from flexlink.analysis import adiabatic
from flexlink.analysis.damping import basis_damping, checked_ratio, deformation_damping
from flexlink.analysis.eigensolver import AUTO_DENSE_MAX
from flexlink.analysis.floquet import FloquetResult, floquet, monodromy
from flexlink.analysis.fourier import fourier_coefficients, fourier_series
from flexlink.analysis.frame_motion import pose_speed_terms
from flexlink.analysis.load_vectors import static_load_directions
from flexlink.analysis.modal import pose_modes
from flexlink.analysis.pose_basis import DEFAULT_TOLERANCE, PoseBasis, pose_basis
from flexlink.analysis.solve import MECHANISM
from flexlink.errors import InputError, NumericalError
from flexlink.fe.assembly import (eliminated_pair, eliminating_assembler, reduced_columns,
                                  rigid_elimination)
from flexlink.fe.co_rotating import co_rotating_turn, link_angles
from flexlink.fe.model_at_pose import pose_model
from flexlink.fe.speed_terms import speed_linear, speed_quadratic
from flexlink.scene import Scene
from flexlink.units import rev_per_min

log = logging.getLogger(__name__)
ADIABATIC_GRID = 2048  # crank angles of the adiabatic basis per turn: 1024 steps at most
ADIABATIC_STEPS = 64  # equal adiabatic steps a turn at least, then halved where Q needs:
# ln |mu| per turn within the map's 1e-3 (docs/critical-speeds.md, "Convergence")
FLOOR_POINTS = 4  # crank angles per sampled pose where the stiffness floor is sought
REST_GROWTH = 1e-8  # growth rate at rest over max |lambda| beyond round-off (``rest_rates``)
STEP_PHASE = 2.0  # h omega_max bound [rad]: ln|mu| within 1.3e-4 per turn of h omega_max 0.5
MAGNUS_BUDGET = 1 << 21  # Magnus steps a turn at most (about a minute): more is refused
FOURTH_ORDER_MOST = 16384  # fourth-order steps a fallback takes as they are; more: midpoint first
MIDPOINT_STEPS = 256  # the midpoint steps' first count a turn, then doubled
MIDPOINT_TOLERANCE = 1e-4  # ln |mu| per turn between a count and its double, twice running:
# the map's 1e-3 with a margin (second order: the finer count's error is about a third of it)
# every frozen mode losing this many e-folds a turn (|mu| below 2e-9): at such a speed a
# parametric resonance would need a harmonic of order 2 omega / Omega, far above the
# coefficients' own (poses / 2), so the adiabatic limit holds and no steps are needed
QUASI_STATIC_DECAY = 20.0


class Integrator(enum.StrEnum):
    """How a speed's monodromy is integrated: ADIABATIC (the default), the
    interaction-picture steps of ``analysis.adiabatic``, whose count does not follow the
    stiffest frequency; MAGNUS, the fourth-order Magnus steps of ``analysis.floquet`` (h
    omega_max <= step_phase), as accurate and many times slower below a few thousand rev/min
    (docs/critical-speeds.md, "Speed"); QUASI_STATIC, no steps: a speed so slow that every
    frozen mode decays by more than QUASI_STATIC_DECAY e-folds a turn (``quasi_static_
    multipliers``), taken where the adiabatic steps are refused; MIDPOINT, the
    exponential-midpoint (second-order Magnus) steps of ``midpoint_multipliers``, whose count
    follows how fast the coefficients turn, not the stiffest frequency: where the adiabatic
    steps are refused and the fourth-order ones would number more than FOURTH_ORDER_MOST."""

    ADIABATIC = "adiabatic"
    MAGNUS = "magnus"
    QUASI_STATIC = "quasi-static"
    MIDPOINT = "midpoint"


@dataclasses.dataclass(frozen=True)
class PeriodicModel:
    """The periodic equations projected on a basis, sampled at ``angles`` [rad].

    mass, coriolis (per rad/s), stiffness (at Omega = 0), speed_stiffness (per (rad/s)^2):
    (poses, n, n); frequencies (n,): the basis vectors' Ritz frequencies at the scene's pose
    [Hz]; damping_ratio (n,) [-]: zeta_i per basis vector at the scene's pose (a single number
    is taken for every vector); damping_samples (poses, n, n): C at each pose (None: the modal
    C = diag(2 zeta_i omega_i) of equations given directly in modal coordinates, the same at
    every pose); elastic_stiffness (poses, n, n): K alone, without the external loads'
    preload (None: not given); basis: how the basis was
    built and its check (``analysis.pose_basis``), None for equations given directly; then the
    first ``checked`` frequencies are those the check covers (all of them without a basis);
    damping_source: where the ratios came from, for the outputs. The forcing, None for free
    equations: inertia_forcing (poses, n) [per (rad/s)^2] the projected d'Alembert loads and
    external_forcing (poses, n) the scene's [[loads]]; ``pose_models`` (the frame model at
    each pose) and ``pose_shapes`` (poses, n_dofs, n): the basis vectors in each pose's global
    DOFs, for what a study reads off the response. load_vectors: how many of the basis
    vectors are static answers to the loads added to the modes (``analysis.load_vectors``);
    verdict: the equations in the modal basis alone, whose multipliers say whether the
    steady state exists (None: these, ``stability``)."""

    angles: np.ndarray
    mass: np.ndarray
    coriolis: np.ndarray
    stiffness: np.ndarray
    speed_stiffness: np.ndarray
    frequencies: np.ndarray
    damping_ratio: np.ndarray
    basis: PoseBasis | None = None
    damping_source: str = "given with the equations"
    inertia_forcing: np.ndarray | None = None
    external_forcing: np.ndarray | None = None
    pose_models: tuple = ()
    pose_shapes: np.ndarray | None = None
    damping_samples: np.ndarray | None = None
    elastic_stiffness: np.ndarray | None = None
    load_vectors: int = 0
    verdict: PeriodicModel | None = None

    def __post_init__(self):
        poses, n = len(self.angles), len(self.frequencies)
        for name in ("mass", "coriolis", "stiffness", "speed_stiffness", "damping_samples",
                     "elastic_stiffness"):
            if name in ("damping_samples", "elastic_stiffness") and getattr(self, name) is None:
                continue
            if np.shape(getattr(self, name)) != (poses, n, n):
                raise ValueError(f"PeriodicModel.{name} has shape "
                                 f"{np.shape(getattr(self, name))}, expected ({poses}, {n}, {n})")
        ratios = np.broadcast_to(np.asarray(self.damping_ratio, dtype=float),
                                 np.shape(self.frequencies)).copy()
        if not (np.all(np.isfinite(ratios)) and np.all(ratios >= 0.0)):
            raise ValueError(f"damping ratios must be finite and >= 0, got {ratios}")
        object.__setattr__(self, "damping_ratio", ratios)
        if (self.inertia_forcing is None) != (self.external_forcing is None):
            raise ValueError("PeriodicModel needs both forcings or neither")
        for name in ("inertia_forcing", "external_forcing"):
            value = getattr(self, name)
            if value is not None and np.shape(value) != (poses, n):
                raise ValueError(f"PeriodicModel.{name} has shape {np.shape(value)}, expected "
                                 f"({poses}, {n})")
        if self.pose_shapes is not None and (
                np.ndim(self.pose_shapes) != 3 or np.shape(self.pose_shapes)[::2] != (poses, n)
                or len(self.pose_models) != poses):
            raise ValueError(f"PeriodicModel.pose_shapes has shape {np.shape(self.pose_shapes)}"
                             f" and {len(self.pose_models)} pose models, expected "
                             f"({poses}, n_dofs, {n}) and {poses}")

    @property
    def stability(self) -> PeriodicModel:
        """The equations whose Floquet multipliers give the stability verdict: the stability
        map's, in the modal basis, so that the response and the map agree on which speeds
        have a steady state (the loads' static answers added to the basis are stiff vectors
        that move no multiplier of the lowest modes' and only make the steps dearer)."""
        return self if self.verdict is None else self.verdict

    @property
    def checked(self) -> np.ndarray:
        """The scene pose's lowest frequencies [Hz] the basis was checked on (the modes the
        unstable ranges are labelled with)."""
        return self.frequencies if self.basis is None else self.basis.exact[0]

    @property
    def damping(self) -> np.ndarray:
        """C (poses, n, n) at each sampled pose: ``damping_samples``, else the modal damping
        diag(2 zeta_i omega_i) at every pose."""
        if self.damping_samples is not None:
            return self.damping_samples
        diagonal = np.diag(2.0 * self.damping_ratio * 2.0 * np.pi * self.frequencies)
        return np.broadcast_to(diagonal, self.mass.shape)

    def at(self, samples: np.ndarray, theta) -> np.ndarray:
        """``samples`` (poses, ...) taken at this model's angles, interpolated at crank angles
        ``theta`` (m,) [rad] as the model interpolates its matrices."""
        return fourier_series(samples, np.asarray(theta, dtype=float) - self.angles[0])

    def matrices_at(self, theta: np.ndarray) -> tuple[np.ndarray, ...]:
        """(M, G1, K, K2) at crank angles theta (m,) [rad] by Fourier interpolation."""
        return tuple(self.at(a, theta) for a in
                     (self.mass, self.coriolis, self.stiffness, self.speed_stiffness))

    def stiffness_floor(self, speed: float) -> float:
        """The lowest eigenvalue [(rad/s)^2] over the turn (FLOOR_POINTS points per sampled
        pose) of the symmetric part of K + speed^2 K2, mass weighted: negative where the
        frozen frame buckles under its own inertia at that speed (a quasi-static divergence,
        not a parametric resonance), or at rest where the interpolation between poses fails."""
        at_rest, per_speed = self._floor_pencil
        return float(np.linalg.eigvalsh(speed_quadratic(speed, at_rest, per_speed))[:, 0].min())

    def rest_rates(self) -> tuple[np.ndarray, np.ndarray, float]:
        """(theta (m,) [rad], rates (m,) [1/s], scale [1/s]): at FLOOR_POINTS crank angles
        per sampled pose, the fastest growth max Re lambda of the equations frozen at rest,
        x' = [[0, I], [-M^-1 K, -M^-1 C]] x, with M^-1 K and M^-1 C interpolated as the
        integrators take them (``per_mass``), and max |lambda| over the turn. At rest
        nothing turns: with the stiffness positive (``stiffness_floor``) and the damping
        dissipative every frozen pose decays or keeps its energy, so a growth well above
        round-off comes from an interpolation between poses that does not resolve how the
        matrices change (rigid pins at 13 poses: M^-1 K has an eigenvalue of -1.2e8 (rad/s)^2
        between poses, a multiplier of 5e130 at 600 rev/min). Its mean over the turn is the
        exponent of the slow-speed limit of the largest multiplier (``quasi_static_
        multipliers``): positive, the interpolated equations are unstable at slow speeds."""
        theta = self.angles[0] + np.linspace(0.0, 2.0 * np.pi, FLOOR_POINTS * len(self.angles),
                                             endpoint=False)
        samples = self.per_mass
        n = samples.shape[-1]
        at_rest = np.zeros((len(theta), 2 * n, 2 * n))
        at_rest[:, :n, n:] = np.eye(n)
        at_rest[:, n:, :n] = -self.at(samples[:, 2], theta)
        at_rest[:, n:, n:] = -self.at(samples[:, 0], theta)
        values = np.linalg.eigvals(at_rest)
        return theta, values.real.max(axis=1), float(np.abs(values).max())

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
    def per_mass(self) -> np.ndarray:
        """(poses, 4, n, n): M^-1 C, M^-1 G1, M^-1 K, M^-1 K2 at each sampled pose, the blocks
        of the first-order equations that are interpolated (linear in C + Omega G1 and
        K + Omega^2 K2, so one series serves every speed; exact at the samples like the
        matrices' own series)."""
        blocks = np.stack(np.broadcast_arrays(self.damping, self.coriolis, self.stiffness,
                                              self.speed_stiffness), axis=1)
        return np.linalg.solve(self.mass[:, None], blocks)

    @functools.cached_property
    def _coefficients(self) -> tuple[np.ndarray, np.ndarray]:
        """The Fourier coefficients of ``per_mass`` ((P + 1, 4, n, n)) and of M^-1 f2,
        M^-1 f_ext ((P + 1, 2, n)), once per model."""
        if self.inertia_forcing is None:
            raise ValueError("these periodic equations carry no forcing")
        forcing = np.stack([self.inertia_forcing, self.external_forcing], axis=1)
        loads = np.linalg.solve(self.mass[:, None], forcing[..., None])[..., 0]
        return fourier_coefficients(self.per_mass), fourier_coefficients(loads)

    def harmonic_equations(self, speed: float):
        """Fourier coefficients (``analysis.fourier``) of S = M^-1 (K + Omega^2 K2) [1/s^2],
        D = M^-1 (C + Omega G1) [1/s] (both (P + 1, n, n)) and g = M^-1 (Omega^2 f2 + f_ext)
        ((P + 1, n)) at crank ``speed`` Omega [rad/s], theta from the first pose: the
        equations of ``system``, whose parts' coefficients combine linearly at every speed
        (the input of ``analysis.harmonic_balance``)."""
        blocks, loads = self._coefficients
        return (speed_quadratic(speed, blocks[:, 2], blocks[:, 3]),
                speed_linear(speed, blocks[:, 0], blocks[:, 1]),
                speed_quadratic(speed, loads[:, 1], loads[:, 0]))

    @functools.cached_property
    def energy_scale(self) -> np.ndarray:
        """R (n, n) [rad/s]: the symmetric square root of the turn's mean mass-weighted
        stiffness at rest, L sym(K) L^T (L L^T = M^-1, ``_floor_pencil``: positive definite
        at every point, as the model refuses it otherwise; the symmetric part of M^-1 K need
        not be, where M varies over the turn and K is stiff: the wiper, rigid pins). In the
        coordinates (R q, q') the stiffness and velocity parts of the state weigh alike, so
        A's norm is near its spectral radius there (in (q, q') it is up to 65 times larger
        on Table II case 1, and each doubling is one more squaring in every step's
        exponential)."""
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
        samples = self.per_mass
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
        except NumericalError as refusal:  # the same at every speed: said once, without one
            log.info("adiabatic steps refused at every speed (%s): Magnus steps instead",
                     refusal)
            return refusal

    def system(self, speed: float, *, energy_coordinates: bool = False):
        """times (m,) [s] -> A(t) (m, 2n, 2n) at crank speed ``speed`` [rad/s], t = 0 at the
        scene's pose, for the state (q, q'), or with ``energy_coordinates`` for (R q, q'), R
        the ``energy_scale`` (the same multipliers; a similarity, exact)."""
        samples = self.per_mass
        n = samples.shape[-1]
        damping = speed_linear(speed, samples[:, 0], samples[:, 1])
        stiffness = speed_quadratic(speed, samples[:, 2], samples[:, 3])
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


def periodic_model(scene: Scene, n_modes: int = 6, poses: int = 37,
                   damping_ratio: float | None = None,
                   elements_per_link: int | None = None, basis_size: int | None = None,
                   tolerance: float = DEFAULT_TOLERANCE,
                   load_vectors: bool = False) -> PeriodicModel:
    """The periodic equations of ``scene`` over one crank turn with their forcing, sampled at
    ``poses`` (odd) crank angles from the scene's pose, in the basis of
    ``analysis.pose_basis``: the lowest ``n_modes`` static modes of every other pose in
    co-rotating coordinates, compressed by SVD to ``basis_size`` vectors (None: the fewest
    whose lowest ``n_modes`` frequencies match the full model's at every pose to
    ``tolerance``), given as the scene pose's Ritz vectors. ``damping_ratio`` [-]: every
    vector's, else (None) the scene's declared damping (``analysis.damping.basis_damping``).
    ``load_vectors``: the basis with the static answers of every pose's stiffness at rest
    (K + K_ext) to its loads (the d'Alembert loads per unit speed^2 and the [[loads]]) added
    (``analysis.load_vectors``), again as the scene pose's Ritz vectors, and the modal
    basis's equations kept as its ``verdict`` (``PeriodicModel.stability``)."""
    if poses < 3 or poses % 2 == 0:
        raise InputError(f"poses must be an odd count of at least 3, got {poses}",
                         field="poses", expected="an odd count >= 3")
    if damping_ratio is not None:  # refused before any work
        checked_ratio(damping_ratio)
    scene.require_full_turn()
    topology = scene.topology(elements_per_link)
    state0 = scene.rigid_state(None)
    model0, static, _ = pose_modes(topology, state0.points, n_modes)
    if MECHANISM in static.kinds:
        raise NumericalError(f"{scene.path}: the frame has a mechanism mode at its pose: the "
                             "periodic equations need the crank held by its drive")
    T = rigid_elimination(model0)
    column, n = reduced_columns(T, model0.n_dofs)
    assemble = eliminating_assembler(column, n, dense=True)
    reference = link_angles(model0)
    angles = state0.q + 2.0 * np.pi * np.arange(poses) / poses
    full = np.empty((5, poses, n, n))  # M, G1, K, K_ext, K2 in co-rotating DOFs
    loads = np.empty((2, poses, n))  # f2, f_ext in co-rotating DOFs
    models, turns = [], []
    for p, angle in enumerate(angles):
        state = scene.rigid_state(angle)
        model = pose_model(topology, state.points)
        K, M = (np.asarray(A.toarray() if hasattr(A, "toarray") else A)
                for A in eliminated_pair(model, T, assemble, direct=n <= AUTO_DENSE_MAX))
        terms = pose_speed_terms(scene, topology, state, model, K, T, assemble)
        R = co_rotating_turn(model, reference, T)
        for k, A in enumerate((M, terms.linear(), K, terms.constant(), terms.squared())):
            full[k, p] = R.T @ np.asarray(A) @ R
        for k, f in enumerate((terms.inertia_loads, terms.external_loads)):
            loads[k, p] = R.T @ (f if T is None else T.T @ f)
        models.append(model)
        turns.append(R)
    basis = pose_basis(full[2], full[0], n_modes, basis_size, tolerance)
    modal = _projected(scene, damping_ratio, basis, full, loads, angles, models, turns, T)
    if not load_vectors:
        return modal
    W = static_load_directions(full[2] + full[3], full[0, 0], loads, basis.vectors)
    if not W.shape[1]:
        return modal
    vectors, frequencies = _reference_ritz(np.concatenate([basis.vectors, W], axis=1),
                                           full[2, 0], full[0, 0])
    enriched = dataclasses.replace(basis, vectors=vectors, frequencies=frequencies)
    try:
        model = _projected(scene, damping_ratio, enriched, full, loads, angles, models, turns, T)
    except NumericalError as refusal:  # the modal basis passed the same checks: keep it
        log.warning("%s: the loads' static answers are left out of the basis (%s)",
                    scene.path, refusal)
        return modal
    return dataclasses.replace(model, load_vectors=W.shape[1], verdict=modal)


def _reference_ritz(B: np.ndarray, K0: np.ndarray, M0: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The span of B (n, r) as the reference pose's Ritz vectors (M_0-orthonormal, K_0
    diagonal, ascending) and their frequencies [Hz]."""
    values, Q = sla.eigh(B.T @ K0 @ B, B.T @ M0 @ B)
    return B @ Q, np.sqrt(values) / (2.0 * np.pi)


def _projected(scene: Scene, damping_ratio: float | None, basis: PoseBasis, full: np.ndarray,
               loads: np.ndarray, angles: np.ndarray, models: list, turns: list,
               T) -> PeriodicModel:
    """The periodic equations on ``basis`` from the co-rotating matrices ``full`` (M, G1, K,
    K_ext, K2: (5, poses, n, n)) and ``loads`` (f2, f_ext: (2, poses, n)) at ``angles``,
    checked: NumericalError where the interpolation between the poses fails."""
    poses = len(angles)
    model0 = models[0]
    V = basis.vectors  # co-rotating eliminated DOFs per coordinate
    M, G1, K, K_ext, K2 = (V.T @ A @ V for A in full)
    shapes = np.stack([R @ V if T is None else np.asarray(T @ (R @ V)) for R in turns])
    # at the scene's pose the co-rotating DOFs are the global ones
    damping = basis_damping(scene, damping_ratio, 2.0 * np.pi * basis.frequencies, model0,
                            shapes[0])
    model = PeriodicModel(angles=angles, mass=M, coriolis=G1, stiffness=K + K_ext,
                          speed_stiffness=K2, frequencies=basis.frequencies,
                          damping_ratio=damping.ratios, basis=basis,
                          damping_source=damping.source, inertia_forcing=loads[0] @ V,
                          external_forcing=loads[1] @ V, pose_models=tuple(models),
                          pose_shapes=shapes, elastic_stiffness=K,
                          damping_samples=deformation_damping(scene, damping_ratio, M, K, models,
                                                              shapes))
    floor = model.stiffness_floor(0.0)
    if floor <= 0.0:
        singular = _singular_poses(scene)
        advice = (f"the linkage passes a singular pose at crank {singular} deg (a flat pose or "
                  "dead centre, where its assembly and the frame's stiff directions turn "
                  "abruptly): the periodic equations cannot follow it, and more poses do not "
                  "help") if singular else ("the basis' stiff directions change faster than the "
                                            "poses resolve; use more poses")
        raise NumericalError(
            f"{scene.path}: between the {poses} sampled poses the interpolated stiffness is "
            f"indefinite (lowest eigenvalue {floor:.3g} (rad/s)^2 at rest): {advice}")
    theta, rates, scale = model.rest_rates()
    k = int(np.argmax(rates))
    where = (f"rate {rates[k]:.3g} 1/s near crank {np.degrees(theta[k]) % 360.0:.4g} deg, "
             f"{rates.mean():.3g} 1/s on average over the turn")
    if rates.mean() > REST_GROWTH * scale:
        raise NumericalError(
            f"{scene.path}: between the {poses} sampled poses the interpolated equations grow "
            f"at rest ({where}), where every pose is stable: the poses do not resolve how the "
            "frame's matrices change over the turn, and its multipliers would show a false "
            f"instability; use more poses ({2 * poses - 1} or more: --poses of response "
            "and stability-map)")
    if rates[k] > REST_GROWTH * scale:
        log.warning("%s: between the %d sampled poses the interpolated equations grow at rest "
                    "in places (%s), though they decay over the turn: more poses (--poses "
                    "%d) would resolve the frame's matrices better", scene.path, poses, where,
                    2 * poses - 1)
    return model


def _singular_poses(scene: Scene) -> str:
    """The crank angles [deg] of a four-bar's flat poses and dead centres as text, or ""."""
    if scene.four_bar is None:
        return ""
    angles = sorted({round(float(np.degrees(a)), 3) for a in
                     scene.four_bar.flat_poses() + scene.four_bar.dead_centres()})
    return ", ".join(f"{a:g}" for a in angles)


def speed_multipliers(model: PeriodicModel, speed: float, steps: int = 200,
                      step_phase: float = STEP_PHASE,
                      integrator: Integrator = Integrator.ADIABATIC,
                      adiabatic_steps: int = ADIABATIC_STEPS,
                      on_steps: Callable[[int], None] | None = None) -> FloquetResult:
    """Floquet multipliers over one revolution at crank ``speed`` [rad/s] (> 0). With
    ``Integrator.ADIABATIC``, by ``adiabatic_steps`` equal adiabatic steps at least (more
    where the damping needs them), each halved where the couplings need it
    (``adiabatic.step_bounds``); where the adiabatic basis refuses or its grid cannot give
    them (logged), the quasi-static bound where it holds, else the fourth-order Magnus steps,
    or the midpoint steps where those would number more than FOURTH_ORDER_MOST. With
    ``Integrator.MAGNUS``, by at least ``steps`` Magnus steps, and more where needed to keep
    h max|eig A| <= ``step_phase``: at low speed one revolution spans many periods of the
    highest basis frequency, and the Magnus step's error grows with h omega_max
    (docs/critical-speeds.md, convergence). With ``Integrator.MIDPOINT``: ``midpoint_
    multipliers``. ``on_steps``: called with each batch of Magnus steps done (progress)."""
    return multipliers_by(model, speed, steps, step_phase, integrator, adiabatic_steps,
                          on_steps)[0]


def multipliers_by(model: PeriodicModel, speed: float, steps: int = 200,
                   step_phase: float = STEP_PHASE,
                   integrator: Integrator = Integrator.ADIABATIC,
                   adiabatic_steps: int = ADIABATIC_STEPS,
                   on_steps: Callable[[int], None] | None = None
                   ) -> tuple[FloquetResult, Integrator]:
    """``speed_multipliers`` and the integrator that gave them."""
    if integrator is Integrator.MIDPOINT:
        return midpoint_multipliers(model, speed, on_steps), Integrator.MIDPOINT
    fallback = integrator is Integrator.ADIABATIC
    if fallback:
        try:
            basis = model.adiabatic  # its refusal does not depend on the speed: logged once
            return (adiabatic.adiabatic_monodromy(basis, speed, adiabatic_steps),
                    Integrator.ADIABATIC)
        except NumericalError as error:
            quasi = quasi_static_multipliers(model, speed)
            if quasi is not None:
                return quasi, Integrator.QUASI_STATIC
            if not isinstance(model._adiabatic_or_refusal, NumericalError):
                log.info("adiabatic steps refused at %.6g rev/min (%s): Magnus steps there",
                         rev_per_min(speed), error)
    period = 2.0 * np.pi / speed
    system = model.system(speed, energy_coordinates=True)
    size = np.abs(np.linalg.eigvals(system((model.angles - model.angles[0]) / speed))).max()
    count = max(steps, int(np.ceil(period * size / step_phase)))
    if fallback and count > FOURTH_ORDER_MOST:
        # the midpoint steps while they number at most half the fourth-order count in all
        # (a midpoint step costs about 0.75 of a fourth-order one): where they do not settle
        # by then, the fourth-order steps cost at most 1.4 times what they cost alone
        midpoint = midpoint_multipliers(model, speed, on_steps,
                                        most=min(count, MAGNUS_BUDGET) // 2)
        if midpoint is not None:
            return midpoint, Integrator.MIDPOINT
    if count > MAGNUS_BUDGET:
        raise NumericalError(_too_many_steps(model, speed, count, size))
    scaled = monodromy(system, period, count, on_steps=on_steps)
    return _unscaled(model, scaled), Integrator.MAGNUS


def midpoint_multipliers(model: PeriodicModel, speed: float,
                         on_steps: Callable[[int], None] | None = None,
                         most: int | None = None) -> FloquetResult | None:
    """Floquet multipliers at crank ``speed`` [rad/s] by exponential-midpoint steps
    (``floquet.propagators``, order 2) on the state (R q, q'), MIDPOINT_STEPS a turn, the
    count doubled until the largest ln |mu| per turn has moved by at most MIDPOINT_TOLERANCE
    over two doublings running (``_settled``), the finest count's multipliers returned. Each
    step is the exact flow of the equations frozen at its midpoint, however stiff, so the
    count follows how fast the coefficients turn with the crank, not the stiffest basis
    vector: where the fourth-order steps need h omega_max <= STEP_PHASE (case 3, 14 modes,
    Rayleigh damping: 2e5 of them at 1200 rev/min) these settle at 1024 steps a turn, 1792
    in all (``benchmarks/floquet_speed.py``). Where the stiff vectors are neither overdamped nor
    many periods a step the convergence is uneven (the aluminium four-bar at 100 rev/min:
    6e-5 from 2048 to 4096 steps, then 6.8e-4 to 8192), hence two doublings. ``most``: the
    steps in all past which None is returned (None: MAGNUS_BUDGET a count, then
    NumericalError)."""
    period = 2.0 * np.pi / speed
    system = model.system(speed, energy_coordinates=True)
    count, spent, moduli = MIDPOINT_STEPS, 0, []
    while True:
        if most is not None and spent + count > most:
            return None
        result = _unscaled(model, monodromy(system, period, count, order=2, on_steps=on_steps))
        spent += count
        moduli.append(result.largest_modulus)
        if _settled(moduli[-3:]):
            return result
        if most is None and 2 * count > MAGNUS_BUDGET:
            raise NumericalError(
                f"the midpoint steps' largest |mu| at {rev_per_min(speed):.6g} rev/min still "
                f"moves ({', '.join(f'{m:.6g}' for m in moduli[-3:])}) at {count} steps a "
                "turn, the most this run allows")
        count *= 2


def _settled(moduli: list[float]) -> bool:
    """Whether three successive counts' largest |mu| agree, each with the next, within
    MIDPOINT_TOLERANCE in ln |mu|, or all lie below exp(-QUASI_STATIC_DECAY) (stable beyond
    doubt)."""
    if len(moduli) < 3:
        return False
    floor = np.exp(-QUASI_STATIC_DECAY)
    if max(moduli) < floor:
        return True
    logs = np.log(np.maximum(moduli, floor**2))
    return bool(np.all(np.abs(np.diff(logs)) <= MIDPOINT_TOLERANCE))


def _unscaled(model: PeriodicModel, scaled: FloquetResult) -> FloquetResult:
    """The multipliers of the state (q, q') from the monodromy of (R q, q')."""
    n = len(model.frequencies)
    scale = np.eye(2 * n)
    scale[:n, :n] = model.energy_scale
    return floquet(np.linalg.solve(scale, scaled.monodromy @ scale), scaled.period)


def quasi_static_multipliers(model: PeriodicModel, speed: float) -> FloquetResult | None:
    """The adiabatic limit of the multipliers at a crank ``speed`` [rad/s] so slow that one
    turn spans many decay times of every frozen mode: with lambda_j(theta) the eigenvalues of
    the first-order matrix A frozen at each sampled pose, the slowest decay rate over the turn
    r(theta) = max_j Re lambda_j(theta) < 0 bounds each multiplier by exp(T mean(r)) (the
    adiabatic theorem: the slow variation changes the exponent by O(Omega / gap), while it is
    at least QUASI_STATIC_DECAY here). None where that does not hold (a pose whose frozen mode
    does not decay, or too little decay a turn): the steps are needed there."""
    period = 2.0 * np.pi / speed
    frozen = model.system(speed)((model.angles - model.angles[0]) / speed)
    slowest = np.linalg.eigvals(frozen).real.max(axis=1)  # per pose [1/s]
    if slowest.max() >= 0.0 or -period * slowest.mean() < QUASI_STATIC_DECAY:
        return None
    exponent = period * slowest.mean()  # ln of the largest |mu|'s upper bound
    bound = np.exp(exponent)  # 0 where it underflows: the exponent stays in the result
    return dataclasses.replace(floquet(np.diag(np.full(frozen.shape[-1], bound)), period),
                               log_largest=float(exponent))


def _too_many_steps(model: PeriodicModel, speed: float, count: int, size: float) -> str:
    """Why a speed needs more than MAGNUS_BUDGET Magnus steps, naming an overdamped basis
    vector where one sets the step."""
    over = np.flatnonzero(model.damping_ratio >= 1.0)
    listed = ", ".join(str(i + 1) for i in over[:6]) + (", ..." if len(over) > 6 else "")
    cause = (f"basis vector(s) {listed} are overdamped "
             f"(damping ratio up to {model.damping_ratio.max():.3g}: {model.damping_source}), "
             "and the fastest decay rate sets the step"
             if len(over) else "one turn spans that many periods of the stiffest basis vector")
    return (f"{count} Magnus steps a turn are needed at {rev_per_min(speed):.6g} rev/min "
            f"(largest rate {size:.3g} 1/s), above the {MAGNUS_BUDGET} this run allows: {cause}")
