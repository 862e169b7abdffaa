"""Parametric stability of the running linkage over crank speed (Floquet).

Model: at crank speed Omega the elastic motion about the rigid motion obeys, with
theta = Omega t the crank angle,
    M(theta) x'' + (C + Omega G1(theta)) x' + (K(theta) + K_ext(theta) + Omega^2 K2(theta)) x = 0,
the operating-point matrices of ``studies.operating_point`` taken at each crank angle (frozen
configuration at each instant; at constant crank speed the inertia preload, the centrifugal and
the link angular-acceleration terms all scale with Omega^2, the Coriolis matrix with Omega).
The matrices are assembled once, at ``poses`` equally spaced crank angles, at Omega = 0 and 1
rad/s, and interpolated in theta by their Fourier series (exact for a trigonometric
polynomial of degree below poses/2). They are projected on the lowest ``n_modes`` static modes
of the reference pose (the scene's), mass normalised, in which the damping is modal:
C = diag(2 zeta omega_i). The period is one revolution, T = 2 pi / Omega.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.floquet import FloquetResult, first_order, monodromy
from flexlink.analysis.modal import pose_modes
from flexlink.analysis.solve import MECHANISM
from flexlink.errors import InputError, NumericalError
from flexlink.fe.assembly import reduced_columns, rigid_elimination
from flexlink.fe.geometric import GeometricForm, geometric_entries
from flexlink.fe.model_at_pose import pose_model
from flexlink.fe.preload import axial_forces, inertia_loads, static_displacement
from flexlink.fe.rotating import node_owners, rotating_entries
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.scene import Scene
from flexlink.studies.operating_point import external_loads, link_motion, reduced_pair, reducer

DEFAULT_DAMPING_RATIO = 0.01  # modal; light structural damping of bolted metal frames


@dataclasses.dataclass(frozen=True)
class PeriodicModel:
    """The periodic equations in the reference modal basis, sampled at ``angles`` [rad].

    mass, coriolis (per rad/s), stiffness (at Omega = 0), speed_stiffness (per (rad/s)^2):
    (poses, n, n); frequencies: the basis' static frequencies [Hz]; damping_ratio [-]."""

    angles: np.ndarray
    mass: np.ndarray
    coriolis: np.ndarray
    stiffness: np.ndarray
    speed_stiffness: np.ndarray
    frequencies: np.ndarray
    damping_ratio: float

    def matrices_at(self, theta: np.ndarray) -> tuple[np.ndarray, ...]:
        """(M, G1, K, K2) at crank angles theta (m,) [rad] by Fourier interpolation."""
        return tuple(_fourier(a, theta) for a in
                     (self.mass, self.coriolis, self.stiffness, self.speed_stiffness))

    def system(self, speed: float):
        """times (m,) [s] -> A(t) (m, 2n, 2n) at crank speed ``speed`` [rad/s]."""
        omega_i = 2.0 * np.pi * self.frequencies
        damping = np.diag(2.0 * self.damping_ratio * omega_i)

        def a(t):
            M, G1, K, K2 = self.matrices_at(self.angles[0] + speed * np.asarray(t))
            return first_order(M, damping + speed * G1, K + speed**2 * K2)
        return a


def _fourier(samples: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Trigonometric interpolation over one turn of samples (N, ...) taken at N equal steps
    from angle 0 (N odd, so every harmonic has its pair and the interpolant is real)."""
    N = samples.shape[0]
    c = np.fft.fft(samples, axis=0) / N
    k = np.fft.fftfreq(N, 1.0 / N)
    return np.tensordot(np.exp(1j * np.outer(theta, k)), c, axes=(1, 0)).real


def periodic_model(scene: Scene, n_modes: int = 6, poses: int = 37,
                   damping_ratio: float = DEFAULT_DAMPING_RATIO,
                   elements_per_link: int | None = None) -> PeriodicModel:
    """The periodic equations of ``scene`` over one crank turn in its reference pose's lowest
    ``n_modes`` static modes, sampled at ``poses`` (odd) crank angles from the scene's pose."""
    if poses < 3 or poses % 2 == 0:
        raise InputError(f"poses must be an odd count of at least 3, got {poses}")
    if not 0.0 <= damping_ratio < 1.0:
        raise InputError(f"damping ratio {damping_ratio} is outside [0, 1)",
                         field="--damping-ratio", expected="a ratio in [0, 1)")
    topology = scene.topology(elements_per_link)
    state0 = scene.rigid_state(None)
    model0, static, _ = pose_modes(topology, state0.points, n_modes)
    if MECHANISM in static.kinds:
        raise NumericalError(f"{scene.path}: the frame has a mechanism mode at its pose: the "
                             "stability map needs the crank held by its drive")
    T = rigid_elimination(model0)
    column, n = reduced_columns(T, model0.n_dofs)
    basis = np.zeros((n, n_modes))
    basis[column[column >= 0]] = static.shapes[np.ix_(column >= 0, static.elastic[:n_modes])]
    reduce = reducer(column, n, dense=True)
    angles = state0.q + 2.0 * np.pi * np.arange(poses) / poses
    out = np.empty((4, poses, n_modes, n_modes))
    for p, angle in enumerate(angles):
        out[:, p] = _pose_matrices(scene, topology, angle, T, n, reduce, basis,
                                     _link_angles(model0))
    scale = np.sqrt(np.diagonal(out[0, 0]))  # mass-normalise at the reference pose
    out /= np.outer(scale, scale)
    return PeriodicModel(angles=angles, mass=out[0], coriolis=out[1], stiffness=out[2],
                         speed_stiffness=out[3], frequencies=static.elastic_frequencies[:n_modes],
                         damping_ratio=damping_ratio)


def _pose_matrices(scene, topology, angle, T, n, reduce, basis, reference):
    """(M, G1, K + K_ext, K2) at crank ``angle`` [rad] in ``basis`` of co-rotating DOFs."""
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
    R = _turning(model, reference, T)
    return tuple(basis.T @ R.T @ np.asarray(A) @ R @ basis for A in (M, G1, K + K_ext, K2))


def _link_angles(model) -> np.ndarray:
    """Each link's direction angle [rad] from its first node to its last."""
    ends = np.array([model.nodes[link.nodes[-1]] - model.nodes[link.nodes[0]]
                     for link in model.links])
    return np.arctan2(ends[:, 1], ends[:, 0])


def _turning(model, reference, T) -> np.ndarray:
    """R (reduced) taking co-rotating node DOFs to global ones: each node's (ux, uy) turned by
    how far its link has turned since the reference pose (``reference``: its link angles).
    The co-rotating DOFs keep a mode's meaning over the turn (a crank's bending stays bending
    after half a revolution); global ones do not. A rigid pin's shared translation turns
    with the first of its links (one DOF, one rotation: any choice is a valid coordinate)."""
    node_turn = (_link_angles(model) - reference)[node_owners(model)]
    if T is not None:
        T = T.tocsc()
        for j in np.flatnonzero(np.diff(T.indptr) > 1):
            nodes = T.indices[T.indptr[j]:T.indptr[j + 1]] // 3
            node_turn[nodes] = node_turn[nodes[0]]
    c, s = np.cos(node_turn), np.sin(node_turn)
    R = np.zeros((model.n_dofs, model.n_dofs))
    ux, uy = 3 * np.arange(len(model.nodes)), 3 * np.arange(len(model.nodes)) + 1
    R[ux, ux], R[ux, uy], R[uy, ux], R[uy, uy] = c, -s, s, c
    R[ux + 2, ux + 2] = 1.0
    # R T = T Rr: Rr = (T^T T)^-1 T^T R T, T^T T counting the DOFs tied in each column
    Rr = R if T is None else (np.asarray(T.T @ (T.T @ R.T).T)
                              / np.diff(T.indptr)[:, None])
    if not np.allclose(Rr.T @ Rr, np.eye(Rr.shape[0]), atol=1e-12):
        raise NumericalError("a grounded or tied DOF is one direction of a turning node: the "
                             "co-rotating coordinates cannot be formed")
    return Rr


def _geometric(model, Kr, T, reduce, loads):
    """Reduced K_g of the axial forces that ``loads`` put in the frame held by its drive."""
    forces = axial_forces(model, static_displacement(Kr, T, loads))
    return reduce(*geometric_entries(model, forces, GeometricForm.CONSISTENT))


def speed_multipliers(model: PeriodicModel, speed: float, steps: int = 200) -> FloquetResult:
    """Floquet multipliers over one revolution at crank ``speed`` [rad/s] (> 0), by at least
    ``steps`` Magnus steps, and more where needed to keep h max|eig A| <= 1 (h omega_max <= 1,
    well inside the Magnus series' convergence): at low speed one revolution spans many
    periods of the highest mode."""
    period = 2.0 * np.pi / speed
    system = model.system(speed)
    size = np.abs(np.linalg.eigvals(system((model.angles - model.angles[0]) / speed))).max()
    return monodromy(system, period, max(steps, int(np.ceil(period * size))))


@dataclasses.dataclass(frozen=True)
class InstabilityRange:
    """Adjacent unstable speeds [rad/s], the nearest resonance (modes 1-based, kind
    "primary" 2 f_i / k or "combination" (f_i + f_j) / k) and the largest growth rate [1/s]."""

    low: float
    high: float
    modes: tuple[int, ...]
    harmonic: int
    kind: str
    growth_rate: float


@dataclasses.dataclass(frozen=True)
class StabilityMap:
    """Per speed [rad/s]: the largest multiplier modulus [-] and growth rate [1/s]."""

    speeds: np.ndarray
    largest_modulus: np.ndarray
    growth_rate: np.ndarray
    ranges: tuple[InstabilityRange, ...]


def stability_map(model: PeriodicModel, speeds: np.ndarray, steps: int = 200,
                  harmonics: int = 6, progress=None) -> StabilityMap:
    """The largest Floquet multiplier over ``speeds`` [rad/s]. At zero speed the equations do
    not vary: nothing is parametrically excited, the modulus is 1 and the rate 0 by definition
    (the damped modes decay). ``progress``: wraps the loop over speeds (a progress bar)."""
    speeds = np.asarray(speeds, dtype=float)
    modulus, rate = np.ones(len(speeds)), np.zeros(len(speeds))
    for i in (progress or iter)(range(len(speeds))):
        if speeds[i] > 0.0:
            result = speed_multipliers(model, speeds[i], steps)
            modulus[i], rate[i] = result.largest_modulus, result.growth_rate
    return StabilityMap(speeds, modulus, rate, _ranges(model, speeds, modulus, rate, harmonics))


def _ranges(model, speeds, modulus, rate, harmonics):
    unstable = np.concatenate([[False], modulus > 1.0, [False]])
    starts, ends = np.flatnonzero(np.diff(unstable.astype(int)) == 1), \
        np.flatnonzero(np.diff(unstable.astype(int)) == -1)
    out = []
    for a, b in zip(starts, ends):
        low, high = speeds[a], speeds[b - 1]
        middle = 0.5 * (low + high) / (2.0 * np.pi)  # rev/s
        modes, k, kind = _nearest(model.frequencies, middle, harmonics)
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
