"""Which mesh a command uses, and why: one rule for ``modes``, ``export`` and ``cycle``.

In order: the command line (``-e``), else the mesh the scene pins
(``mesh.elements_per_link``), else the coarsest of 8, 16, 32, ... elements per link whose
Richardson error estimate |f_h - f_h/2| / (2^p - 1) / f meets a relative frequency tolerance
at the scene's pose (for a general scene, the pose at its start crank angle).

p = ORDER = 2, the lowest order among the elements: Timoshenko links converge at O(h^2) in the
eigenvalue (their shear strain is constant along each element), and so does the axial linear
element with consistent mass. Euler-Bernoulli bending converges at O(h^4), and in a frame of
Euler-Bernoulli links the axial h^2 term is tiny at practical meshes (a bending mode stretches
each link almost uniformly, which linear elements represent exactly), so there the estimate
is conservative: about (2^4 - 1) / (2^2 - 1) = 5 times the actual error (measured 4.9 to 5.0
on Table II case 1 and on a cantilever; 1.0 to 1.06 on a stubby Timoshenko cantilever).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.eigensolver import EigenSolver, Method
from flexlink.analysis.modal import pose_modes
from flexlink.analysis.precision import roundoff_ratio
from flexlink.analysis.solve import LOST_LIMIT
from flexlink.errors import NumericalError

ORDER = 2  # leading order of the frequency error in h (module docstring)
DEFAULT_TOL = 1e-6  # relative frequency tolerance of the default mesh rule
# the energy-refined frequencies do not depend on the eigen solver, so the fast one serves
SPARSE_SOLVER = EigenSolver(Method.SPARSE)
COMMAND_LINE, SCENE, TOLERANCE = "command line (-e)", "scene (mesh.elements_per_link)", "tolerance"
FIXED = "fixed"  # a command's own default mesh, with the reason and the error estimate it has


@dataclasses.dataclass(frozen=True)
class MeshRule:
    """``elements`` per link and the ``rule`` that chose them (COMMAND_LINE, SCENE or
    TOLERANCE); for TOLERANCE also the tolerance, the estimated relative error and
    (elements, estimate) per refinement step."""

    elements: int
    rule: str = TOLERANCE
    tol: float | None = None
    estimate: float | None = None
    history: tuple[tuple[int, float], ...] = ()
    reason: str | None = None  # why a FIXED mesh is enough

    def as_dict(self) -> dict:
        """For a command's JSON output."""
        out = {"rule": self.rule, "elements_per_link": self.elements}
        if self.rule == TOLERANCE:
            out.update(tolerance=self.tol, estimated_relative_error=self.estimate,
                       richardson_order=ORDER)
        if self.rule == FIXED:
            out.update(reason=self.reason, estimated_relative_error=self.estimate,
                       richardson_order=ORDER)
        return out

    def describe(self) -> str:
        """One line for a command's text output."""
        if self.rule == FIXED:
            error = ("not estimated" if self.estimate is None
                     else f"estimated discretisation error {self.estimate:.1e}")
            return (f"mesh: {self.elements} elements/link, fixed ({error}, order-{ORDER} "
                    f"Richardson estimate): {self.reason}")
        if self.rule != TOLERANCE:
            return (f"mesh: {self.elements} elements/link from the {self.rule}; discretisation "
                    "error not estimated (omit it to use --tol)")
        return (f"mesh: {self.elements} elements/link, the coarsest meeting the relative "
                f"frequency tolerance {self.tol:g} (estimated discretisation error "
                f"{self.estimate:.1e}, order-{ORDER} Richardson estimate)")




def choose_mesh(scene, n_modes: int, elements: int | None = None,
                tol: float | None = None) -> MeshRule:
    """The mesh for ``scene``: ``elements`` if given, else the scene's pinned mesh, else
    ``mesh_for_tolerance`` at relative tolerance ``tol`` (None: DEFAULT_TOL); the MeshRule says
    which."""
    if elements is not None:
        return MeshRule(elements, COMMAND_LINE)
    if scene.elements_per_link is not None:  # pinned by [mesh] elements_per_link
        return MeshRule(scene.elements_per_link, SCENE)
    return mesh_for_tolerance(scene, n_modes, DEFAULT_TOL if tol is None else tol)


def mesh_for_tolerance(scene, n_modes: int, tol: float = DEFAULT_TOL,
                       solver: EigenSolver = SPARSE_SOLVER,
                       start: int = 4, max_elements: int = 4096) -> MeshRule:
    """Refine by doubling from ``start`` until the estimated relative error <= ``tol``.

    The energy-refined frequencies do not depend on the eigen solver to 1e-12, so the fast
    sparse one serves for the estimate whatever solver the final answer uses. A tolerance
    below what double precision reaches for this model is refused (NumericalError) with the
    best estimate reached."""
    def frequencies(elements):
        return _frequencies(scene, n_modes, elements, solver)

    previous = frequencies(start)
    elements, history = start, []
    while elements < max_elements:
        current = frequencies(2 * elements)
        if current is None:
            break
        elements *= 2
        estimate = float((np.abs(current - previous) / (2**ORDER - 1) / current).max())
        history.append((elements, estimate))
        if estimate <= tol:
            return MeshRule(elements, TOLERANCE, tol, estimate, tuple(history))
        previous = current
    best = min(history, key=lambda h: h[1]) if history else (start, float("nan"))
    if elements < max_elements:
        raise NumericalError(
            f"the relative frequency tolerance {tol:g} is below what double precision reaches "
            f"for this model: the best Richardson error estimate was {best[1]:.1g} at {best[0]} "
            f"elements/link, and {2 * elements} elements/link lose the lowest modes to "
            f"round-off in K. Ask for a tolerance of {best[1]:.1g} or more")
    raise NumericalError(f"no mesh up to {max_elements} elements per link meets the relative "
                         f"frequency tolerance {tol:g} (best estimate {best[1]:.2g} at {best[0]} "
                         "elements/link)")


def _frequencies(scene, n_modes: int, elements: int, solver: EigenSolver = SPARSE_SOLVER):
    """The lowest ``n_modes`` elastic frequencies [Hz] at the scene's pose on ``elements`` per
    link, None past what double precision holds."""
    points = scene.rigid_pose().joints
    topology = scene.topology(elements)
    if roundoff_ratio(topology, points) > LOST_LIMIT:
        return None
    try:
        modes = pose_modes(topology, points, n_modes, solver)[1]
    except NumericalError:  # past the precision limit: the solver's own check refused it
        return None
    return modes.elastic_frequencies[:n_modes]


def fixed_mesh(scene, n_modes: int, elements: int, reason: str) -> MeshRule:
    """A command's own default of ``elements`` per link, with the ``reason`` it is enough and
    the Richardson estimate of its relative frequency error (from ``elements`` / 2 to
    ``elements``, None where either cannot be solved)."""
    coarse = _frequencies(scene, n_modes, max(1, elements // 2)) if elements > 1 else None
    fine = _frequencies(scene, n_modes, elements)
    estimate = None
    if coarse is not None and fine is not None:
        estimate = float((np.abs(fine - coarse) / (2**ORDER - 1) / fine).max())
    return MeshRule(elements, FIXED, estimate=estimate, reason=reason)
