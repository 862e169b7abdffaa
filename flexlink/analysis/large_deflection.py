"""Geometrically nonlinear statics of a planar frame of co-rotational elements
(``fe.corotational``): Newton's method on the exact constraints of the linear model.

The frame is a ``fe.model.FrameModel`` at its stress-free pose. Its rigid springs (pins,
clamps, ground bearings) stay exact at any displacement in these coordinates: coincident nodes
that share translations or rotations keep sharing them however far they move, so the linear
model's ``T`` (``assembly.rigid_elimination``) holds unchanged. Finite springs act on the
global DOFs linearly (a bearing's small play, not a large-motion element).

Unknowns q, u = T q; some entries of q are prescribed (a driven rotation); the rest satisfy
    R(q) = T^T (f_int(T q) + K_s T q - p) = 0
by Newton's method with the consistent tangent T^T (K_t + K_s) T.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.errors import NumericalError
from flexlink.fe.corotational import (Chords, ElementState, element_state, internal_forces,
                                      tangent_stiffness)


@dataclasses.dataclass(frozen=True)
class CorotationalFrame:
    """Elements of a frame: initial node positions X (e, 2, 2) [m], global DOFs (e, 6), chords,
    n_dofs, and which link each element belongs to (e,)."""

    X: np.ndarray
    dofs: np.ndarray
    chords: Chords
    n_dofs: int
    link: np.ndarray

    def __post_init__(self):
        e = len(self.X)
        if self.X.shape != (e, 2, 2) or self.dofs.shape != (e, 6) or self.link.shape != (e,):
            raise ValueError(f"CorotationalFrame: X {self.X.shape}, dofs {self.dofs.shape}, "
                             f"link {self.link.shape}; expected (e, 2, 2), (e, 6), (e,)")

    @classmethod
    def of(cls, model) -> CorotationalFrame:
        """The elements of every link of ``model`` (``fe.model.FrameModel``) at its pose."""
        X, dofs, EA, EI, link = [], [], [], [], []
        for index, mesh in enumerate(model.links):
            nodes = mesh.nodes
            X.append(np.stack([model.nodes[nodes[:-1]], model.nodes[nodes[1:]]], axis=1))
            first = 3 * nodes[:-1, None] + np.arange(6)
            dofs.append(first)
            EA += [mesh.section.EA] * mesh.elements
            EI += [mesh.section.EI] * mesh.elements
            link += [index] * mesh.elements
        X = np.concatenate(X)
        return cls(X, np.concatenate(dofs), Chords.of(X, np.array(EA), np.array(EI)),
                   model.n_dofs, np.array(link))

    def state(self, u_full) -> ElementState:
        """The elements' state at global displacements ``u_full`` (n_dofs,)."""
        return element_state(self.chords, self.X, np.asarray(u_full)[self.dofs])

    def forces_and_tangent(self, u_full) -> tuple[np.ndarray, np.ndarray, ElementState]:
        """(f_int (n_dofs,), K_t (n_dofs, n_dofs) dense, the element state) at ``u_full``."""
        state = self.state(u_full)
        f = np.bincount(self.dofs.ravel(), internal_forces(state).ravel(), self.n_dofs)
        k = tangent_stiffness(self.chords, state)
        rows = np.repeat(self.dofs, 6, axis=1).ravel()
        cols = np.tile(self.dofs, (1, 6)).ravel()
        K = np.bincount(rows * self.n_dofs + cols, k.ravel(),
                        self.n_dofs * self.n_dofs).reshape(self.n_dofs, self.n_dofs)
        return f, K, state

    def energy(self, u_full) -> float:
        """Strain energy [J] of the elements at ``u_full``."""
        return float(self.state(u_full).energy.sum())


@dataclasses.dataclass(frozen=True)
class StaticSolution:
    """A converged state: q (reduced), u (full), reduced internal forces (the reactions on the
    prescribed entries) [N, N m], element state, Newton iterations."""

    q: np.ndarray
    u: np.ndarray
    reactions: np.ndarray
    state: ElementState
    iterations: int


def solve_static(frame: CorotationalFrame, T, prescribed: np.ndarray, guess: np.ndarray,
                 K_springs=None, load=None, rtol: float = 1e-10, max_iterations: int = 30,
                 where: str = "") -> StaticSolution:
    """Newton's method for the free entries of q from ``guess`` (n_reduced,), whose entries at
    the indices ``prescribed`` are held. ``T``: dense (n_dofs, n_reduced) or None (identity);
    ``K_springs``: (n_dofs, n_dofs) linear springs; ``load``: (n_dofs,) dead loads [N, N m].
    Converged when the last step changed no entry of q by more than ``rtol`` relative and the
    free residual is below ``rtol`` times the largest of the internal force, the reaction and
    the load (the scale of the forces in play), or below the round-off of K q, 64 eps |K| d
    (|K| the largest tangent entry, d the frame's extent: the axial stiffness of a slender
    frame makes that floor far above eps times the bending forces). NumericalError naming ``where`` if
    not converged in ``max_iterations``."""
    Tm = np.eye(frame.n_dofs) if T is None else np.asarray(T)
    q = np.array(guess, dtype=float)
    free = np.setdiff1d(np.arange(len(q)), prescribed)
    p = np.zeros(frame.n_dofs) if load is None else np.asarray(load, float)
    q_scale = max(float(np.abs(q).max()), 1e-300)
    extent = float(np.ptp(frame.X.reshape(-1, 2), axis=0).max())
    for iteration in range(1, max_iterations + 1):
        u = Tm @ q
        f, K, state = frame.forces_and_tangent(u)
        if K_springs is not None:
            f = f + K_springs @ u
            K = K + K_springs
        R = Tm.T @ (f - p)
        Kr = Tm.T @ K @ Tm
        noise = 64 * np.finfo(float).eps * float(np.abs(Kr).max()) * extent
        scale = max(rtol * float(np.abs(Tm.T @ f).max()), rtol * float(np.abs(p).max()), noise)
        try:
            step = np.linalg.solve(Kr[np.ix_(free, free)], -R[free])
        except np.linalg.LinAlgError as exc:
            raise NumericalError(f"{where}: singular tangent stiffness at Newton iteration "
                                 f"{iteration}") from exc
        q[free] += step
        q_scale = max(q_scale, float(np.abs(q).max()))
        if (np.abs(R[free]).max() <= scale and np.abs(step).max() <= rtol * q_scale):
            break
        if not np.all(np.isfinite(q)):
            break
    else:
        iteration = max_iterations + 1
    if iteration > max_iterations or not np.all(np.isfinite(q)):
        raise NumericalError(f"{where}: Newton's method did not converge in {max_iterations} "
                             f"iterations (free residual {np.abs(R[free]).max():.3e} against "
                             f"tolerance {scale:.3e} N or N m)")
    u = Tm @ q
    f, _, state = frame.forces_and_tangent(u)
    if K_springs is not None:
        f = f + K_springs @ u
    return StaticSolution(q, u, Tm.T @ (f - p), state, iteration)
