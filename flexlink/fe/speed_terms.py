"""The speed terms of a frame at one pose of its rigid motion, assembled once per unit crank speed
and unit crank acceleration.

At crank speed Omega and crank angular acceleration qddot the rigid motion of a pose is
(``kinematics.dynamics``) omega = K Omega per link, alpha = K qddot + L Omega^2 and, per node,
a = p'' Omega^2 + p' qddot. Every term of the small vibrations about that motion is therefore a
sum of powers of the two (``rotating`` for the link frames' terms, ``preload`` and
``geometric`` for the stiffness of the axial forces, which are linear in the loads):

    G(Omega)            = Omega G1                          G1 = 2 omega_1 S        (Coriolis)
    K_s(Omega, qddot)   = K_ext + Omega^2 K2 + qddot K1
    K2 = -omega_1^2 Mt + alpha_1 S + K_g(N(f_1))     (centrifugal, circulatory, inertia preload)
    K1 = alpha_a S + K_g(N(f_a))                     (the same from rest at 1 rad/s^2)
    K_ext = K_g(N(f_ext))                            (the constant external loads)

with _1 the motion at Omega = 1 rad/s, qddot = 0 and _a at Omega = 0, qddot = 1 rad/s^2, and
f the d'Alembert loads of that motion (the loads the steady response is forced by). ``speed_terms``
assembles them, in the DOFs left by the rigid elimination; ``speed_quadratic`` and
``speed_linear`` are the one place the powers of the speed are applied, to these matrices or
to anything made of them (projected, sampled over a turn, Fourier coefficients).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.fe.geometric import GeometricForm, geometric_entries
from flexlink.fe.model import FrameModel
from flexlink.fe.preload import axial_forces, inertia_loads, static_displacement
from flexlink.fe.rotating import rotating_entries


@dataclasses.dataclass(frozen=True)
class Terms:
    """Which speed terms enter (all by default); ``geometric`` the K_g form."""

    preload: bool = True
    centrifugal: bool = True
    coriolis: bool = True
    acceleration: bool = True  # the circulatory alpha S term
    geometric: GeometricForm = GeometricForm.CONSISTENT


ALL_TERMS = Terms()


@dataclasses.dataclass(frozen=True)
class UnitMotion:
    """A pose's rigid motion per unit crank speed and acceleration: per link (model.links
    order) ``omega`` [rad/s per rad/s] and ``alpha`` [rad/s^2 per (rad/s)^2] at 1 rad/s, and
    per node ``acceleration`` (N, 2) [m/s^2 per (rad/s)^2]; ``start_alpha`` and
    ``start_acceleration`` the same from rest at 1 rad/s^2 of crank acceleration (None: not
    asked for)."""

    omega: np.ndarray
    alpha: np.ndarray
    acceleration: np.ndarray
    start_alpha: np.ndarray | None = None
    start_acceleration: np.ndarray | None = None

    def __post_init__(self):
        links, nodes = np.shape(self.omega), np.shape(self.acceleration)
        if len(links) != 1 or np.shape(self.alpha) != links:
            raise ValueError(f"UnitMotion.alpha has shape {np.shape(self.alpha)}, expected "
                             f"{links} (one value per link, as omega)")
        if len(nodes) != 2 or nodes[1] != 2:
            raise ValueError(f"UnitMotion.acceleration has shape {nodes}, expected (nodes, 2)")
        if (self.start_alpha is None) != (self.start_acceleration is None):
            raise ValueError("UnitMotion needs both start_alpha and start_acceleration, or "
                             "neither")
        if self.start_alpha is not None and (np.shape(self.start_alpha) != links
                                             or np.shape(self.start_acceleration) != nodes):
            raise ValueError(f"UnitMotion's start terms need shapes {links} and {nodes}")


@dataclasses.dataclass(frozen=True)
class SpeedTerms:
    """A pose's speed terms (module docstring) in the DOFs left by the rigid elimination (n x n,
    dense or sparse as the assembler given to ``speed_terms`` makes them): per (rad/s)^2
    ``centrifugal`` (-omega_1^2 Mt), ``circulatory`` (alpha_1 S) and ``preload`` (K_g of the
    d'Alembert loads); per rad/s ``coriolis`` (G1); per rad/s^2 ``start_circulatory`` and
    ``start_preload`` (None when the motion had no start terms); ``external_preload``
    (K_g of the constant external loads). The full-size nodal loads (n_dofs,) [N, N m] and
    their axial forces (per link (elements,) [N]) per unit: ``inertia_loads``,
    ``start_loads``, ``external_loads``; ``*_forces`` likewise, and ``*_displacement`` the
    frame's static answer (n_dofs,) [m, rad] to each, held by its drive."""

    centrifugal: object
    circulatory: object
    coriolis: object
    preload: object
    external_preload: object
    inertia_loads: np.ndarray
    external_loads: np.ndarray
    inertia_forces: tuple[np.ndarray, ...]
    external_forces: tuple[np.ndarray, ...]
    inertia_displacement: np.ndarray | None = None
    external_displacement: np.ndarray | None = None
    start_circulatory: object = None
    start_preload: object = None
    start_loads: np.ndarray | None = None
    start_forces: tuple[np.ndarray, ...] | None = None
    start_displacement: np.ndarray | None = None

    def __post_init__(self):
        n = np.shape(self.centrifugal)
        for name in ("circulatory", "coriolis", "preload", "external_preload"):
            if np.shape(getattr(self, name)) != n:
                raise ValueError(f"SpeedTerms.{name} has shape {np.shape(getattr(self, name))}, "
                                 f"expected {n}")
        if np.shape(self.external_loads) != np.shape(self.inertia_loads):
            raise ValueError("SpeedTerms.external_loads needs the shape of inertia_loads")

    def squared(self, terms: Terms = ALL_TERMS):
        """K2: the stiffness per (rad/s)^2 of crank speed of the terms asked for."""
        return _sum([(terms.centrifugal, self.centrifugal),
                     (terms.acceleration, self.circulatory),
                     (terms.preload, self.preload)], self.centrifugal)

    def accelerated(self, terms: Terms = ALL_TERMS):
        """K1: the stiffness per rad/s^2 of crank acceleration of the terms asked for."""
        if self.start_circulatory is None:
            raise ValueError("these speed terms were assembled without the crank acceleration's")
        return _sum([(terms.acceleration, self.start_circulatory),
                     (terms.preload, self.start_preload)], self.centrifugal)

    def constant(self, terms: Terms = ALL_TERMS):
        """K_ext: the stiffness of the constant external loads' preload, if asked for."""
        return _sum([(terms.preload, self.external_preload)], self.centrifugal)

    def linear(self, terms: Terms = ALL_TERMS):
        """G1: the Coriolis matrix per rad/s, if asked for."""
        return _sum([(terms.coriolis, self.coriolis)], self.coriolis)

    def at(self, speed: float, acceleration: float = 0.0,
           terms: Terms = ALL_TERMS) -> tuple[object, object]:
        """(G, K_s) at crank ``speed`` [rad/s] and crank ``acceleration`` [rad/s^2]: the
        gyroscopic matrix and the stiffness the motion adds to the elastic K."""
        accelerated = self.accelerated(terms) if acceleration else None
        return (speed_linear(speed, 0.0, self.linear(terms)),
                speed_quadratic(speed, self.constant(terms), self.squared(terms),
                                acceleration, accelerated))

    def loads_at(self, speed: float, acceleration: float = 0.0) -> np.ndarray:
        """The nodal loads (n_dofs,) [N, N m] of the rigid motion and the external loads."""
        return speed_quadratic(speed, self.external_loads, self.inertia_loads, acceleration,
                               self.start_loads if acceleration else None)

    def forces_at(self, speed: float, acceleration: float = 0.0) -> tuple[np.ndarray, ...]:
        """Per link the axial forces (elements,) [N] of ``loads_at``."""
        start = self.start_forces if acceleration else None
        return tuple(speed_quadratic(speed, e, i, acceleration, None if start is None else start[k])
                     for k, (e, i) in enumerate(zip(self.external_forces, self.inertia_forces)))


def _sum(parts, like):
    """The sum of the matrices whose flag is set, or a zero matrix shaped as ``like``."""
    chosen = [matrix for on, matrix in parts if on]
    if not chosen:
        return like * 0.0
    total = chosen[0]
    for matrix in chosen[1:]:
        total = total + matrix
    return total


def speed_quadratic(speed: float, at_rest, squared, acceleration: float = 0.0,
                    accelerated=None):
    """at_rest + speed^2 squared (+ acceleration accelerated): a stiffness or a load at crank
    ``speed`` [rad/s] and crank ``acceleration`` [rad/s^2] from its parts per unit; any array
    shapes that broadcast (a pose's matrices, their samples over a turn or Fourier
    coefficients)."""
    out = at_rest + speed**2 * squared
    if accelerated is not None:
        out = out + acceleration * accelerated
    elif acceleration:
        raise ValueError("a crank acceleration needs the stiffness per unit acceleration")
    return out


def speed_linear(speed: float, at_rest, linear):
    """at_rest + speed linear: a damping at crank ``speed`` [rad/s] (the Coriolis matrix per
    rad/s added to the damping at rest)."""
    return at_rest + speed * linear


def speed_terms(model: FrameModel, stiffness, T, assemble, motion: UnitMotion,
                external: np.ndarray,
                form: GeometricForm = GeometricForm.CONSISTENT) -> SpeedTerms:
    """The speed terms of ``model`` (a FrameModel at one pose) moving with ``motion`` per unit
    crank speed and acceleration and carrying the constant nodal loads ``external`` (n_dofs,)
    [N, N m]. ``stiffness``: its K with the rigid constraints eliminated (T^T K T, dense or
    sparse), the frame held by its drive; ``T`` from ``assembly.rigid_elimination`` (None:
    nothing rigid); ``assemble``: global entries (rows, cols, values) -> the eliminated
    matrix (``assembly.eliminating_assembler``); ``form``: the K_g form. NumericalError
    (``preload.static_displacement``) when the frame cannot carry the loads."""
    rows, cols, rot = rotating_entries(model, motion.omega, motion.alpha)
    loads = [inertia_loads(model, motion.acceleration, motion.alpha), np.asarray(external, float)]
    starting = motion.start_alpha is not None
    if starting:
        loads.append(inertia_loads(model, motion.start_acceleration, motion.start_alpha))
    u = static_displacement(stiffness, T, np.column_stack(loads))
    forces = [axial_forces(model, u[:, k]) for k in range(len(loads))]

    def preload(k):
        return assemble(*geometric_entries(model, forces[k], form))

    start = {}
    if starting:
        s_rows, s_cols, s_rot = rotating_entries(model, np.zeros_like(motion.start_alpha),
                                                 motion.start_alpha)
        start = dict(start_circulatory=assemble(s_rows, s_cols, s_rot[2]),
                     start_preload=preload(2), start_loads=loads[2], start_forces=forces[2],
                     start_displacement=u[:, 2])
    return SpeedTerms(centrifugal=assemble(rows, cols, rot[0]),
                      circulatory=assemble(rows, cols, rot[2]),
                      coriolis=assemble(rows, cols, rot[1]), preload=preload(0),
                      external_preload=preload(1), inertia_loads=loads[0],
                      external_loads=loads[1], inertia_forces=forces[0],
                      external_forces=forces[1], inertia_displacement=u[:, 0],
                      external_displacement=u[:, 1], **start)
