"""Geometrically nonlinear statics of a planar frame of co-rotational elements
(``fe.corotational``): Newton's method on the exact constraints of the linear model.

The frame is a ``fe.model.FrameModel`` at its stress-free pose. Its rigid springs (pins,
clamps, ground bearings) stay exact at any displacement in these coordinates: coincident nodes
that share translations or rotations keep sharing them however far they move, so the linear
model's ``T`` (``assembly.rigid_elimination``) holds unchanged. Finite springs act on the
global DOFs linearly (a bearing's small play, not a large-motion element).

Unknowns q, u = T q. T only ties DOFs together or grounds them (each row one 1 or none), so the
elements are assembled straight onto q (``CorotationalFrame.eliminated``), a grounded DOF
reading zero. Some entries of q are prescribed (a driven rotation); the rest satisfy
    R(q) = f_int(q) + K_s q - p = 0
by Newton's method with the consistent tangent K_t + K_s.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import scipy.sparse as sp

from flexlink.errors import NumericalError
from flexlink.fe.corotational import (Chords, ElementState, element_state, internal_forces,
                                      tangent_stiffness)


@dataclasses.dataclass(frozen=True)
class CorotationalFrame:
    """Elements of a frame: initial node positions X (e, 2, 2) [m], the unknown of each element
    DOF (e, 6) (n_dofs: a grounded DOF, always zero), chords, n_dofs, and which link each
    element belongs to (e,)."""

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

    def eliminated(self, T) -> CorotationalFrame:
        """The frame on the unknowns q of u = T q (``assembly.rigid_elimination``'s T, sparse
        or dense, or None for no constraint): a grounded DOF maps to n_reduced (zero)."""
        if T is None:
            return self
        T = sp.csr_matrix(T)
        per_row = np.diff(T.indptr)
        if per_row.max(initial=0) > 1 or not np.allclose(T.data, 1.0):
            raise ValueError("T must tie or ground DOFs (each row one 1 or none)")
        column = np.full(T.shape[0] + 1, T.shape[1])
        column[np.flatnonzero(per_row)] = T.indices
        dofs = np.where(self.dofs == self.n_dofs, T.shape[0], self.dofs)
        return dataclasses.replace(self, dofs=column[dofs], n_dofs=T.shape[1])

    def state(self, q) -> ElementState:
        """The elements' state at the unknowns ``q`` (n_dofs,)."""
        return element_state(self.chords, self.X, np.append(q, 0.0)[self.dofs])

    def forces_and_tangent(self, q) -> tuple[np.ndarray, np.ndarray, ElementState]:
        """(f_int (n_dofs,), K_t (n_dofs, n_dofs) dense, the element state) at ``q``."""
        n = self.n_dofs + 1
        state = self.state(q)
        f = np.bincount(self.dofs.ravel(), internal_forces(state).ravel(), n)[:-1]
        k = tangent_stiffness(self.chords, state)
        rows = np.repeat(self.dofs, 6, axis=1).ravel()
        cols = np.tile(self.dofs, (1, 6)).ravel()
        K = np.bincount(rows * n + cols, k.ravel(), n * n).reshape(n, n)[:-1, :-1]
        return f, K, state

    def energy(self, q) -> float:
        """Strain energy [J] of the elements at ``q``."""
        return float(self.state(q).energy.sum())


@dataclasses.dataclass(frozen=True)
class StaticSolution:
    """A converged state: q, the residual forces (the reactions on the prescribed entries)
    [N, N m], the element state, Newton iterations."""

    q: np.ndarray
    reactions: np.ndarray
    state: ElementState
    iterations: int


def solve_static(frame: CorotationalFrame, prescribed: np.ndarray, guess: np.ndarray,
                 K_springs=None, load=None, rtol: float = 1e-10, max_iterations: int = 30,
                 where: str = "") -> StaticSolution:
    """Newton's method for the free entries of q from ``guess`` (n_dofs,), whose entries at
    the indices ``prescribed`` are held. ``K_springs``: (n_dofs, n_dofs) linear springs;
    ``load``: (n_dofs,) dead loads [N, N m]. Converged when the last step changed no entry of
    q by more than ``rtol`` relative and the free residual is below ``rtol`` times the
    largest of the internal force and the load (the scale of the forces in play), or below
    the round-off of K q, 64 eps |K| d (|K| the largest tangent entry, d the frame's extent:
    the axial stiffness of a slender frame makes that floor far above eps times the bending
    forces). NumericalError naming ``where`` if not converged in ``max_iterations``."""
    q = np.array(guess, dtype=float)
    free = np.setdiff1d(np.arange(len(q)), prescribed)
    p = np.zeros(frame.n_dofs) if load is None else np.asarray(load, float)
    q_scale = max(float(np.abs(q).max()), 1e-300)
    extent = float(np.ptp(frame.X.reshape(-1, 2), axis=0).max())
    R, bound = np.zeros(1), 0.0
    for iteration in range(1, max_iterations + 1):
        f, K, _ = frame.forces_and_tangent(q)
        if K_springs is not None:
            f = f + K_springs @ q
            K = K + K_springs
        R = (f - p)[free]
        noise = 64 * np.finfo(float).eps * float(np.abs(K).max()) * extent
        bound = max(rtol * float(np.abs(f).max()), rtol * float(np.abs(p).max()), noise)
        try:
            step = np.linalg.solve(K[np.ix_(free, free)], -R)
        except np.linalg.LinAlgError as exc:
            raise NumericalError(f"{where}: singular tangent stiffness at Newton iteration "
                                 f"{iteration}") from exc
        q[free] += step
        if not np.all(np.isfinite(q)):
            break
        q_scale = max(q_scale, float(np.abs(q).max()))
        if np.abs(R).max() <= bound and np.abs(step).max() <= rtol * q_scale:
            f, _, state = frame.forces_and_tangent(q)
            if K_springs is not None:
                f = f + K_springs @ q
            return StaticSolution(q, f - p, state, iteration)
    raise NumericalError(f"{where}: Newton's method did not converge in {max_iterations} "
                         f"iterations (free residual {np.abs(R).max():.3e} against tolerance "
                         f"{bound:.3e} N or N m)")


@dataclasses.dataclass(frozen=True)
class DrivenPath:
    """States along a prescribed rotation of one unknown: q (n, n_dofs), the driving moment
    (the reaction on the driven entry) (n,) [N m], the strain energy (n,) [J], element states
    and Newton iterations per step."""

    q: np.ndarray
    moment: np.ndarray
    energy: np.ndarray
    states: tuple[ElementState, ...]
    iterations: np.ndarray


def driven_path(frame: CorotationalFrame, driven: int, turns, label=None,
                max_iterations: int = 30, progress=None, K_springs=None) -> DrivenPath:
    """Continuation in the driven rotation: q[driven] = ``turns`` (n,) [rad] in order, from
    the stress-free state, each step's Newton iteration started from the secant extrapolation
    of the two before it; ``K_springs`` as ``solve_static``'s. ``label(turn)`` names a step in the NumericalError of a step that
    does not converge (e.g. the crank angle); ``progress``: an iterable wrapper."""
    label = label or (lambda turn: f"driven rotation {np.degrees(turn):.2f} deg")
    turns = np.asarray(turns, dtype=float)
    q_prev = q = np.zeros(frame.n_dofs)
    driven_entry = np.array([driven])
    qs, moments, energies, states, iterations = [], [], [], [], []
    for turn in (progress(turns) if progress else turns):
        guess = 2 * q - q_prev if qs else q.copy()
        guess[driven] = turn
        solution = solve_static(frame, driven_entry, guess, K_springs,
                                max_iterations=max_iterations, where=label(turn))
        q_prev, q = q, solution.q
        qs.append(q)
        moments.append(solution.reactions[driven])
        spring_energy = 0.0 if K_springs is None else 0.5 * q @ K_springs @ q
        energies.append(solution.state.energy.sum() + spring_energy)
        states.append(solution.state)
        iterations.append(solution.iterations)
    return DrivenPath(np.array(qs), np.array(moments), np.array(energies), tuple(states),
                      np.array(iterations))
