"""The Jacobian of the calibration residuals from eigenvalue sensitivities, not by re-solving.

A calibration's least squares needs d r / d x (x = ln p) at every accepted step. By finite
differences that is one full evaluation (load, build, eigen solve, checks) per free input and
case, about 90 % of a fit's cost. Here each mode's sensitivity comes from its shape s at x
(first-order eigenvalue perturbation, s^T K s / s^T M s stationary in s):

    d ln lambda / d ln p = (s^T dK s) / (s^T K s) - (s^T dM s) / (s^T M s),   d ln f = d ln lambda / 2.

- Inputs that enter K or M linearly through joint springs and joint masses (``LINEAR``: Kt, Kr,
  drive, joint_mass, Ktilt) give s^T dK s = sum k (s_a - s_b)^2 over the springs set by that
  input, and s^T dM s = sum m |s_node|^2 over its masses: no model is built. Which springs
  and masses an input sets is found once per fit by loading the scene with the input scaled by
  ``PROBE`` (a joint with a value of its own in the scene file does not follow the global key);
  a spring made rigid at x is an exact constraint and contributes nothing.
- Inputs that change only the sections (``SECTION``: width, thickness) are differenced on the
  Rayleigh quotient of s: the scene is loaded (and validated) with the input stepped by
  ``STEP`` and its model built, not solved. Where the step makes a spring rigid or not (the
  constraints change), that case is differenced on full evaluations instead.
- Inputs that move the nodes (L1 scales the whole linkage) are differenced on full
  evaluations, as a finite-difference Jacobian does. The Rayleigh quotient is no use there:
  a mode that moves links nearly rigidly on soft bearings is, at the stepped geometry, no
  longer rigid-body-compatible, and the stiff elements' energy of that mismatch (second order
  in the step, but times element / bearing stiffness, 1e6 and more) swamps the first-order
  change (measured: 9.5 against -1.52 for d ln f / d ln L1).

The mode pairing is the residuals' own (``families.paired``, by order). A mode whose frequency
the model did not find (its residual is the constant penalty) has a zero row. Agreement with a
finite-difference Jacobian: tests/studies/test_jacobian.py.
"""

from __future__ import annotations

import dataclasses
import logging

import numpy as np

from flexlink.analysis.families import (PartModes, elastic_modes, part_modes, paired,
                                        part_model, quadratic_forms)
from flexlink.analysis.outofplane import tilt_stiffnesses
from flexlink.errors import FlexlinkError
from flexlink.fe.formulation import FORMULATIONS
from flexlink.fe.joints import spring_energies
from flexlink.fe.model import FrameModel, layout
from flexlink.studies.calibration.derivatives import log_slope

log = logging.getLogger(__name__)

LINEAR = ("Kt", "Kr", "drive", "joint_mass", "Ktilt")
SECTION = ("width", "thickness")
STEP = 1e-5  # step in x = ln p, times max(1, |x|): scipy's 2-point rule at the diff_step the fits used
PROBE = 1.001  # factor that tells which springs and masses an input sets


@dataclasses.dataclass(frozen=True)
class CaseModes:
    """One case evaluated at x: its frequencies [Hz] (n_modes, NaN where not found), each
    part's model and elastic shapes, and which (part, mode) each frequency is."""

    frequencies: np.ndarray
    parts: tuple[PartModes, ...]
    pairs: tuple[tuple[int, int], ...]


def case_modes(scene, n_modes: int, elements: int | None) -> CaseModes:
    """``families.elastic_modes`` of ``scene``, keeping what the sensitivities need."""
    parts = part_modes(scene, n_modes, elements)
    frequencies, pairs = paired(parts, n_modes)
    return CaseModes(frequencies, parts, pairs)


def _part_springs(scene, part: str, elements: int | None) -> tuple[np.ndarray, np.ndarray]:
    """(spring stiffnesses as the scene sets them, before any is made rigid; joint masses) of
    ``part``'s model, in the model's order."""
    topology = scene.topology(elements)
    masses = np.array([m for _, m in layout(topology).point_masses], dtype=float)
    springs = FORMULATIONS[part].springs(topology, tilt_stiffnesses(scene))
    return np.asarray(springs.stiffness, dtype=float), masses


def followers(load, values: np.ndarray, index: int, parts, elements: int | None):
    """Per part: (bool per spring, bool per joint mass) set by free input ``index``, found by
    loading with that input times PROBE, or divided by it where that load fails (a range's
    end); ``load(values)`` -> scene. None if neither loads, or if the input changes anything
    but in proportion (then it is not linear in springs and masses): its column is then
    differenced on full evaluations."""
    base_scene, probe_scene = load(values), None
    for factor in (PROBE, 1.0 / PROBE):
        probe = values.copy()
        probe[index] *= factor
        try:
            probe_scene = load(probe)
            break
        except FlexlinkError:
            continue
    if probe_scene is None:
        return None
    out = []
    for part in parts:
        (k0, m0), (k1, m1) = (_part_springs(s, part, elements) for s in (base_scene, probe_scene))
        if k0.shape != k1.shape or m0.shape != m1.shape:
            return None
        marks = []
        for a, b in ((k0, k1), (m0, m1)):
            with np.errstate(invalid="ignore", divide="ignore"):
                ratio = np.where(a == b, 1.0, b / a)
            moved = ratio != 1.0
            if not np.allclose(ratio[moved], factor, rtol=1e-9, atol=0.0):
                return None
            marks.append(moved)
        out.append(tuple(marks))
    return out


def _spring_forms(model: FrameModel, follows: np.ndarray, shapes: np.ndarray) -> np.ndarray:
    """sum over the finite springs marked in ``follows`` of k (s_a - s_b)^2, per shape."""
    use = follows & np.isfinite(model.springs.stiffness)
    return spring_energies(model.springs, shapes)[use].sum(axis=0)


def _mass_forms(part: str, model: FrameModel, follows: np.ndarray, shapes: np.ndarray):
    """sum over the joint masses marked in ``follows`` of m |s at the node|^2, per shape, on
    the DOFs a joint mass moves in ``part`` (in plane: x and y; out of plane: w)."""
    out = np.zeros(shapes.shape[1])
    dofs = FORMULATIONS[part].mass_dofs
    for (node, mass), use in zip(model.point_masses, follows):
        if use:
            out += mass * (shapes[[3 * node + d for d in dofs]] ** 2).sum(axis=0)
    return out


def _constraints(model: FrameModel) -> tuple:
    return model.n_dofs, tuple(np.isinf(model.springs.stiffness))


def log_frequency_sensitivities(load, values: np.ndarray, names: tuple[str, ...],
                                cases: list[CaseModes | None], n_modes: int,
                                elements: int | None, followers_cache: dict,
                                upper: np.ndarray | None = None) -> np.ndarray:
    """d ln f / d ln p, shape (cases, n_modes, inputs), at ``values`` [SI] of the free inputs
    ``names``; ``load(case, values)`` -> scene; ``cases``: each case's ``case_modes`` at
    ``values`` (None where it failed: zero rows). ``followers_cache``: {(case, input):
    ``followers``}, filled on first use. ``upper``: ln of the inputs' upper bounds, which a
    differencing step does not cross (default none)."""
    D = np.zeros((len(cases), n_modes, len(names)))
    x = np.log(values)
    upper = np.full(len(x), np.inf) if upper is None else upper
    for i, case in enumerate(cases):
        if case is None or not case.pairs:
            continue
        forms = [quadratic_forms(p.part, p.model, p.shapes) for p in case.parts]
        for j, name in enumerate(names):
            key = (i, j)
            if name in LINEAR and key not in followers_cache:
                followers_cache[key] = followers(lambda v, i=i: load(i, v), values, j,
                                                 [p.part for p in case.parts], elements)
            marks = followers_cache.get(key) if name in LINEAR else None
            if marks is not None and not all(
                    len(springs) == len(p.model.springs.stiffness)
                    and len(masses) == len(p.model.point_masses)
                    for p, (springs, masses) in zip(case.parts, marks)):
                marks = None  # this evaluation's model is laid out otherwise: difference it
            if marks is not None:
                column = []
                for part, (q, m), (springs, masses) in zip(case.parts, forms, marks):
                    dq = _spring_forms(part.model, springs, part.shapes)
                    dm = _mass_forms(part.part, part.model, masses, part.shapes)
                    column.append(0.5 * (dq / q - dm / m))
            else:
                column = _differenced(load, i, case, forms, x, upper, j, elements,
                                      rayleigh=name in SECTION)
            if column is None:  # the step failed: leave the column at zero, as the fit's own
                continue        # penalty does not tell a direction either
            D[i, :len(case.pairs), j] = [column[p][k] for p, k in case.pairs]
    return D


def _step(x: float, upper: float) -> float:
    """The forward step in x = ln p, turned back where it would leave the upper bound."""
    h = STEP * max(1.0, abs(x))
    return -h if x + h > upper else h


def _differenced(load, i: int, case: CaseModes, forms, x: np.ndarray, upper: np.ndarray,
                 j: int, elements: int | None, rayleigh: bool):
    """Per part, d ln f / d x_j of its modes by a forward step, on the Rayleigh quotients of
    their shapes if ``rayleigh`` and the step leaves the constraints as they are, else on full
    evaluations; None if the stepped scene fails."""
    h = _step(x[j], upper[j])
    stepped = x.copy()
    stepped[j] += h
    try:
        scene = load(i, np.exp(stepped))
        if not rayleigh:
            return _evaluated(scene, case, h, elements)
        models = [part_model(scene, p.part, elements) for p in case.parts]
        if any(_constraints(a) != _constraints(p.model) for a, p in zip(models, case.parts)):
            return _evaluated(scene, case, h, elements)
    except FlexlinkError as exc:
        log.info("sensitivity step of input %d failed: %s", j, exc)
        return None
    out = []
    for part, model, (q, m) in zip(case.parts, models, forms):
        q1, m1 = quadratic_forms(part.part, model, part.shapes)
        out.append(0.5 * log_slope(q1 / m1, q / m, h))  # f^2 is the Rayleigh quotient
    return out


def _evaluated(scene, case: CaseModes, h: float, elements: int | None):
    """Per part, d ln f / d x by re-solving ``scene`` (the stepped one) and pairing by order."""
    n_modes = len(case.frequencies)
    stepped = elastic_modes(scene, n_modes, elements)[0]
    out = [np.zeros(len(p.frequencies)) for p in case.parts]
    for (p, k), f0, f1 in zip(case.pairs, case.frequencies, stepped):
        out[p][k] = log_slope(f1, f0, h) if np.isfinite(f1) else 0.0
    return out
