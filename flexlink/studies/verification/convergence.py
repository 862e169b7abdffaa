"""Mesh convergence: frequencies, error and run time over mesh levels and solver/mass choices.

Discretisation error is measured against a Richardson extrapolation of the finest three levels
h, h/2, h/4 of one choice. The leading error term is of order p = ORDER = 2: the axial P1
element (with consistent mass) has eigenvalue error O(h^2), and every mode of a pinned frame
stretches its links a little; Hermite bending alone converges at O(h^4) (tests/
test_convergence.py shows both). So each pair is extrapolated at order 2,
    r = f_h/2 + (f_h/2 - f_h) / (2^2 - 1),
and the two results once more at order 4 (the next term), which removes the h^4 bending error
too. The observed order log2(|f_h - f_h/2| / |f_h/2 - f_h/4|) is computed and compared with p.
Model error (against measurement) is kept apart: refining the mesh does not reduce it.
"""

from __future__ import annotations

import dataclasses
import math
import statistics

import numpy as np

from flexlink.analysis.mesh import DEFAULT_TOL, ORDER, MeshRule, mesh_for_tolerance  # noqa: F401 (re-exported)
from flexlink.analysis.eigensolver import EigenSolver, Method
from flexlink.analysis.modal import Mass, analyze
from flexlink.errors import NumericalError
from flexlink.scene import Scene
from flexlink.studies.array_shapes import check_shape
from flexlink.analysis.solve import DENSE_LIMIT
from flexlink.units import percent_error

# ORDER: see module docstring; the second extrapolation step uses ORDER + 2
REPEAT_BUDGET_S = 5.0  # a level stops repeating once its runs took this long (slow dense levels)
ORDER_SLACK = 0.5  # observed order within ORDER +- this counts as asymptotic


@dataclasses.dataclass(frozen=True)
class Choice:
    """A way to solve: eigen ``method``, ``mass`` matrix, and energy refinement (see solve.py)."""

    method: Method
    mass: Mass
    refine: bool = True

    @property
    def label(self) -> str:
        return f"{self.method}/{self.mass}" + ("" if self.refine else " (unrefined)")


CHOICES = (Choice(Method.SPARSE, Mass.CONSISTENT), Choice(Method.DENSE, Mass.CONSISTENT),
           Choice(Method.SPARSE, Mass.LUMPED), Choice(Method.DENSE, Mass.LUMPED),
           Choice(Method.SPARSE, Mass.CONSISTENT, refine=False))
REFERENCE_CHOICE = CHOICES[0]  # the choice the Richardson reference is extrapolated from


@dataclasses.dataclass(frozen=True)
class Level:
    """One mesh level of one choice: median times [s] and the lowest elastic frequencies [Hz]."""

    choice: Choice
    elements: int
    dofs: int
    assembly_s: float
    solve_s: float
    frequencies: np.ndarray
    runs: int = 1

    @property
    def total_s(self) -> float:
        return self.assembly_s + self.solve_s


@dataclasses.dataclass(frozen=True)
class Extrapolation:
    """Richardson reference [Hz] from the finest levels ``elements`` (h, h/2, h/4) of one choice,
    with the order used and the observed order per mode."""

    reference: np.ndarray
    order: int
    observed: np.ndarray
    elements: tuple[int, ...]
    uncertainty: np.ndarray  # relative change of the reference by the second (order-4) step

    @property
    def asymptotic(self) -> bool:
        return bool(np.all(np.abs(self.observed - self.order) <= ORDER_SLACK))


def mesh_levels(max_elements: int = 512) -> tuple[int, ...]:
    """1, 2, 4, ... up to ``max_elements`` elements per link."""
    return tuple(2**k for k in range(int(math.log2(max_elements)) + 1))


def run_level(scene: Scene, choice: Choice, elements: int, n_modes: int, repeats: int) -> Level:
    """One level of one choice, solved up to ``repeats`` times (see ``run_levels``)."""
    return run_levels(scene, [(choice, elements)], n_modes, repeats)[0]


def run_levels(scene: Scene, work, n_modes: int, repeats: int, progress=None,
               refused: list | None = None) -> list[Level]:
    """Every (choice, elements) of ``work``, solved ``repeats`` times, round-robin: each round
    runs every level once, so a change in machine load during the study hits every choice
    alike. A level whose runs took REPEAT_BUDGET_S in all is not repeated further. Median
    assembly and solve wall times [s].

    A level the solver refuses (NumericalError, e.g. a mesh past double precision for that
    choice) is left out of the result; with ``refused`` given, (choice, elements, message) is
    appended there, otherwise the error propagates."""
    work = list(work)
    runs: list[list] = [[] for _ in work]
    failed: dict[int, str] = {}
    rounds = range(repeats)
    for _ in (progress(rounds) if progress else rounds):
        for i, ((choice, elements), done) in enumerate(zip(work, runs)):
            if i in failed or (done and sum(sum(r.seconds.values()) for r in done)
                               >= REPEAT_BUDGET_S):
                continue
            try:
                done.append(analyze(scene, n_modes, elements, EigenSolver(choice.method), choice.mass,
                                    choice.refine))
            except NumericalError as exc:
                if refused is None:
                    raise
                failed[i] = str(exc)
                refused.append((choice, elements, str(exc)))
    return [Level(choice=c, elements=e, dofs=done[-1].modes.n_dofs,
                  assembly_s=statistics.median(r.seconds["assembly"] for r in done),
                  solve_s=statistics.median(r.seconds["solve"] for r in done),
                  frequencies=done[-1].elastic_frequencies(n_modes), runs=len(done))
            for i, ((c, e), done) in enumerate(zip(work, runs)) if i not in failed]


def runs_dense(elements: int, scene: Scene) -> bool:
    """Dense choices stop at DENSE_LIMIT DOFs (far past where sparse is faster)."""
    return 3 * (elements + 1) * len(scene.sections) <= DENSE_LIMIT


def observed_order(coarse: np.ndarray, middle: np.ndarray, fine: np.ndarray) -> np.ndarray:
    """log2 of successive difference ratios, per mode (NaN where a difference is zero)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.log2(np.abs(middle - coarse) / np.abs(fine - middle))


def richardson(levels: list[Level], order: int = ORDER) -> Extrapolation:
    """Extrapolate the finest three of ``levels`` (one choice, ascending elements, each twice the
    last): each pair at ``order``, then the two results at ``order + 2``."""
    if len(levels) < 3:
        raise ValueError("Richardson extrapolation with an order check needs three levels")
    c, m, f = levels[-3:]
    if not (m.elements == 2 * c.elements and f.elements == 2 * m.elements):
        raise ValueError("Richardson levels must halve h: elements n, 2n, 4n")

    def step(coarse, fine, p):
        return fine + (fine - coarse) / (2**p - 1)

    first = step(m.frequencies, f.frequencies, order)
    reference = step(step(c.frequencies, m.frequencies, order), first, order + 2)
    return Extrapolation(reference=reference, order=order,
                         observed=observed_order(c.frequencies, m.frequencies, f.frequencies),
                         elements=(c.elements, m.elements, f.elements),
                         uncertainty=np.abs(reference - first) / reference)


def relative_errors(levels: list[Level], reference: np.ndarray) -> np.ndarray:
    """(len(levels), n) |f - f_ref| / f_ref."""
    return np.array([np.abs(l.frequencies - reference) / reference for l in levels])


def cheapest(levels: list[Level], reference: np.ndarray, tol: float) -> Level | None:
    """The level (of any choice) with the smallest median time whose every frequency is within
    ``tol`` (relative) of ``reference``; None if none is."""
    ok = [l for l, e in zip(levels, relative_errors(levels, reference)) if e.max() <= tol]
    return min(ok, key=lambda l: l.total_s) if ok else None


def measured_column(scene: Scene) -> tuple[str, list[float]] | None:
    """The scene's measured reference column ("Ex") [Hz] if it has one, else its first
    column, as (name, values); None without a reference table."""
    if scene.reference is None or not scene.reference.columns:
        return None
    columns = scene.reference.columns
    name = "Ex" if "Ex" in columns else next(iter(columns))
    return name, columns[name]


def _pct(computed, measured) -> list[float]:
    """% error of ``computed`` against ``measured`` [Hz], over the modes both have."""
    k = min(len(computed), len(measured))
    return [percent_error(computed[i], measured[i]) for i in range(k)]


@dataclasses.dataclass(frozen=True)
class ConvergenceStudy:
    """Every level of every choice of ``scene`` (``file``) with ``n_modes`` elastic modes and up
    to ``repeats`` runs each, the Richardson ``extrapolation`` of REFERENCE_CHOICE, each level's
    relative ``errors`` against its reference (levels, modes), the ``cheapest`` level within
    the relative tolerance ``tol`` (None: none is), the scene's ``measured`` column (name,
    values [Hz]; None without one) and the levels the solver ``refused`` (choice, elements,
    reason)."""

    scene: str
    file: str
    n_modes: int
    repeats: int
    tol: float
    levels: tuple[Level, ...]
    extrapolation: Extrapolation
    errors: np.ndarray
    cheapest: Level | None
    measured: tuple[str, list[float]] | None
    refused: tuple[tuple[Choice, int, str], ...] = ()

    def __post_init__(self):
        modes = len(self.extrapolation.reference)
        check_shape("ConvergenceStudy", "errors", self.errors, (len(self.levels), modes))
        for level in self.levels:
            check_shape("ConvergenceStudy", "levels[].frequencies", level.frequencies, (modes,))

    @property
    def reference(self) -> np.ndarray:
        """The Richardson reference frequencies [Hz]."""
        return self.extrapolation.reference

    def measured_pct(self, computed) -> list[float]:
        """% error of ``computed`` [Hz] against the measured column (over the modes both have);
        empty without one."""
        return [] if self.measured is None else _pct(computed, self.measured[1])


def convergence_study(scene: Scene, n_modes: int, max_elements: int, repeats: int, tol: float,
                      progress=None) -> ConvergenceStudy:
    """Solve ``scene`` at 1, 2, 4, ... ``max_elements`` elements per link with every choice of
    CHOICES (dense ones up to DENSE_LIMIT DOFs), ``repeats`` times round-robin; extrapolate the
    first choice (Richardson), measure every level's error against it and against the
    measured column, and name the cheapest level within the relative tolerance ``tol``."""
    work = [(c, e) for c in CHOICES for e in mesh_levels(max_elements)
            if c.method is not Method.DENSE or runs_dense(e, scene)]
    refused: list = []
    levels = run_levels(scene, work, n_modes, repeats, progress, refused)
    extrapolation = richardson([l for l in levels if l.choice == REFERENCE_CHOICE])
    return ConvergenceStudy(
        scene=scene.name, file=scene.path, n_modes=n_modes, repeats=repeats, tol=tol,
        levels=tuple(levels), extrapolation=extrapolation,
        errors=relative_errors(levels, extrapolation.reference),
        cheapest=cheapest(levels, extrapolation.reference, tol),
        measured=measured_column(scene), refused=tuple(refused))
