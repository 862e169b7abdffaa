"""One scene at its pose, summarised for ``modes``, ``report`` and ``export``: the lowest
elastic modes of its model family against the scene's reference columns, with the checks of
the solve, the mesh that was used, the warnings, and on request the other values of its
two-way modelling choices and the sensitivity study. Pairing with a reference column is by
mode order of the elastic modes only; rigid-body/mechanism modes are kept apart, never paired.

The solve itself is always the planar (in-plane) one (``analysis.modal.analyze``): its pose,
DOF count, solver, residuals and mechanism modes are those reported. For another family the
frequencies and kinds are that family's (``families.elastic_modes``), and the planar model's
mode identity and damping, which would describe other modes, are left out.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.damping import damping_source, modal_damping_ratios, overdamped_note
from flexlink.analysis.eigensolver import DEFAULT_SOLVER, EigenSolver
from flexlink.analysis.families import elastic_modes, in_plane_only_note, scene_family
from flexlink.analysis.identity import (DIRECTIONS, ModeIdentity, mode_identity,
                                        participating_mass, total_mass)
from flexlink.analysis.mesh import MeshRule, choose_mesh
from flexlink.analysis.modal import CaseResult, analyze
from flexlink.analysis.solve import ELASTIC
from flexlink.fe.motions import ModelFamily
from flexlink.scene import load_scene
from flexlink.studies.pose.alternatives import (Alternative, other_orientation, other_shear_source,
                                           timoshenko_alternative)
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.calibration.sensitivity import SceneSensitivity, sensitivity_study
from flexlink.units import percent_error


@dataclasses.dataclass(frozen=True)
class Alternatives:
    """The scene under the other value of each two-way modelling choice it makes: the strip
    orientation (None when the scene sets none), Timoshenko links (None unless a link is
    outside Euler-Bernoulli theory) and the composite's shear modulus source (None unless it
    has Timoshenko links of a composite)."""

    orientation: Alternative | None
    timoshenko: Alternative | None
    shear_source: Alternative | None


@dataclasses.dataclass(frozen=True)
class SensitivityRun:
    """What ``--sensitivity`` asks for: Monte Carlo ``samples`` and ``seed``, worker ``jobs``
    (-1: one per core), and whether to show a progress bar."""

    samples: int
    seed: int
    jobs: int
    progress: bool


@dataclasses.dataclass(frozen=True)
class SceneSummary:
    """One scene at its pose. ``case``: the planar analysis (scene, pose, model, modes, solve
    checks, timings); ``family``: the model family whose modes these are; ``frequencies``: its
    n lowest elastic frequencies [Hz] (NaN where fewer were found); ``kinds``: per mode
    "in-plane" or "out-of-plane" (None for the planar family); ``identity``: the modes'
    ``identity.ModeIdentity`` (None for another family); ``damping_ratio``: per mode [-],
    declared in the scene's [damping] or else from the links' loss factors (empty for another
    family), and ``damping_source`` how it was found; ``mechanism``: rigid-body/mechanism
    frequencies [Hz]; ``mass``: total [kg]; ``participating``: mass per direction of
    ``identity.DIRECTIONS`` [kg]; ``reference``: each reference column's values [Hz] paired
    with these modes and ``errors`` their % errors (computed vs reference); ``note``: why the
    modes are the in-plane ones of another family."""

    case: CaseResult
    family: ModelFamily
    frequencies: np.ndarray
    kinds: tuple[str, ...] | None
    identity: ModeIdentity | None
    damping_ratio: np.ndarray
    damping_source: str
    mechanism: np.ndarray
    mass: float
    participating: np.ndarray
    reference: dict[str, tuple[float, ...]]
    errors: dict[str, np.ndarray]
    mesh: MeshRule
    warnings: tuple[str, ...] = ()
    note: str | None = None
    alternatives: Alternatives | None = None
    sensitivity: SceneSensitivity | None = None

    def __post_init__(self):
        n = len(self.frequencies)
        check_shape("SceneSummary", "frequencies", self.frequencies, (None,))
        if self.kinds is not None:
            check_shape("SceneSummary", "kinds", self.kinds, (n,))
        if self.identity is not None and len(self.identity) not in (0, n):
            raise ValueError(f"SceneSummary.identity has {len(self.identity)} modes, expected "
                             f"one per mode ({n}), or none")
        check_shape("SceneSummary", "damping_ratio", self.damping_ratio,  # per mode, or none
                    (0 if len(self.damping_ratio) == 0 else n,))
        check_shape("SceneSummary", "mechanism", self.mechanism, (None,))
        check_shape("SceneSummary", "participating", self.participating, (len(DIRECTIONS),))
        if set(self.errors) != set(self.reference):
            raise ValueError("SceneSummary.errors has the columns "
                             f"{sorted(self.errors)}, expected those of reference "
                             f"{sorted(self.reference)}")
        for name, values in self.reference.items():
            if len(values) > n:
                raise ValueError(f"SceneSummary.reference[{name!r}] has {len(values)} values, "
                                 f"expected at most one per mode ({n})")
            check_shape("SceneSummary", f"errors[{name!r}]", self.errors[name], (len(values),))

    @property
    def max_residual(self) -> float:
        """The largest relative eigen residual of the planar solve's elastic modes [-]."""
        modes = self.case.modes
        return float(np.nanmax(modes.residuals[modes.elastic]))

    @property
    def mean_abs_error_pct(self) -> dict[str, float]:
        """Mean |error| [%] per reference column that pairs with at least one mode."""
        return {name: float(np.mean(np.abs(e))) for name, e in self.errors.items() if len(e)}


def scene_summary(path, n_modes: int, elements: int | None = None, tol: float | None = None,
                  solver: EigenSolver = DEFAULT_SOLVER, *, in_plane_only: str | None = None,
                  alternatives: bool = False, sensitivity: SensitivityRun | None = None
                  ) -> SceneSummary:
    """The summary of the scene file at ``path``: on ``elements`` per link if given, else the
    scene's pinned mesh, else the mesh rule at ``tol``; the rest as ``summary_of``."""
    scene = load_scene(path)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    return summary_of(analyze(scene, n_modes, mesh.elements, solver), n_modes, mesh, solver,
                      in_plane_only=in_plane_only, alternatives=alternatives,
                      sensitivity=sensitivity)


def summary_of(case: CaseResult, n_modes: int, mesh: MeshRule,
               solver: EigenSolver = DEFAULT_SOLVER, *,
               in_plane_only: str | None = None, alternatives: bool = False,
               sensitivity: SensitivityRun | None = None) -> SceneSummary:
    """The summary of the planar analysis ``case`` on ``mesh``. ``in_plane_only``: what is
    built on the in-plane model only (e.g. "the export"): the planar modes, with a note saying
    so when the scene's family is another; else the family's own modes. ``alternatives``: also
    the other value of each modelling choice; ``sensitivity``: also the sensitivity study."""
    scene, modes = case.scene, case.modes
    family = ModelFamily.PLANAR if in_plane_only else scene_family(scene)
    frequencies, kinds = case.elastic_frequencies(n_modes), None
    identity, damping = None, np.zeros(0)
    if family is ModelFamily.PLANAR:
        shapes = modes.shapes[:, modes.elastic[:n_modes]]
        identity = mode_identity(case.model, shapes)
        damping = np.asarray(modal_damping_ratios(
            case.model, shapes, 2 * np.pi * frequencies, scene.loss_factors,
            scene.options.damping), dtype=float)
    else:
        frequencies, kinds = elastic_modes(scene, n_modes, mesh.elements, solver)
    frequencies = np.asarray(frequencies, dtype=float)
    columns = scene.reference.columns if scene.reference else {}
    reference = {name: tuple(values[:len(frequencies)]) for name, values in columns.items()}
    errors = {name: np.array([percent_error(float(f), v) for f, v in zip(frequencies, values)])
              for name, values in reference.items()}
    mechanism = np.array([f for f, k in zip(modes.frequencies, modes.kinds) if k != ELASTIC],
                         dtype=float)
    return SceneSummary(
        case=case, family=family, frequencies=frequencies, kinds=kinds, identity=identity,
        damping_ratio=damping, damping_source=damping_source(scene.options.damping),
        mechanism=mechanism, mass=total_mass(case.model),
        participating=np.asarray(participating_mass(case.model), dtype=float),
        reference=reference, errors=errors, mesh=mesh,
        warnings=tuple(case.warnings) + tuple(w for w in [overdamped_note(damping)] if w),
        note=in_plane_only_note(scene, in_plane_only) if in_plane_only else None,
        alternatives=_alternatives(case, n_modes, mesh.elements) if alternatives else None,
        sensitivity=None if sensitivity is None else sensitivity_study(
            scene, n_modes, sensitivity.samples, sensitivity.seed, sensitivity.jobs,
            sensitivity.progress))


def _alternatives(case: CaseResult, n_modes: int, elements: int) -> Alternatives:
    scene = case.scene
    slender = any("Euler-Bernoulli" in w for w in case.warnings)
    return Alternatives(
        orientation=other_orientation(scene, n_modes, elements),
        timoshenko=timoshenko_alternative(scene, n_modes, elements) if slender else None,
        shear_source=other_shear_source(scene, n_modes, elements))


def overall_mean_abs_error(summaries: list[SceneSummary]) -> dict[str, float]:
    """Mean |error| [%] per reference column over every paired mode of every summary."""
    pooled: dict[str, list[np.ndarray]] = {}
    for s in summaries:
        for name, e in s.errors.items():
            if len(e):
                pooled.setdefault(name, []).append(np.abs(e))
    return {name: float(np.mean(np.concatenate(parts))) for name, parts in pooled.items()}

