"""The steady response of the running linkage against an independent time-domain answer
(tests/data/exudyn_case3.json, with its provenance; made by scripts/record_exudyn_case3.py;
Exudyn is not needed here).

Exudyn integrated Table II case 3 in time from rest: ANCF cable links, the bearings as springs,
the crank angle prescribed (ramped up, then held), generalized-alpha, the last of many turns
recorded, at 600 and 1200 rev/min with two damping laws and at 60 rev/min (Rayleigh) for the
quasi-static limit. flexlink's periodic solution (``steady_response``'s, as ``flexlink
response`` gives it: 6 static modes a pose and the loads' static answers in the basis, 37
poses) is compared per link on the midspan
bending strain over the turn: the peak |strain| and the RMS of the difference over the turn,
both relative to the recorded peak, within 1 % and 2 % where the damping laws are the same.

The laws. Rayleigh (C = beta K) is the same in both. The record's "constant ratio" is not
flexlink's ``--damping-ratio 0.02``: strain-rate damping cannot give every mode one ratio, so
the record fits each link's own stiffness-proportional beta to that link's first mode (its
mode 3 gets 0.077, mode 5 0.18). flexlink is compared with it twice: under the record's own
law (``record_law_damping``, Law.RECORD_LAW: a like-for-like comparison), and with 0.02 for
every vector (Law.RATIO, what a user would write; it meets the record where the higher modes'
damping does not matter, and departs at 1200 rev/min where it does: ``LAW_MISMATCH``).

Why they need not agree to round-off: flexlink's model is linear about the rigid motion in a
reduced basis (25 vectors, the Fourier series of 37 poses, 16 elements a link with the strain
read on one side of the midspan node), Exudyn's is geometrically exact at 32 elements a link
(its own mesh and step changes: under 0.2 % of the peaks). Where that matters beyond the
tolerances (the rocker at 1200 rev/min), the comparison is a strict xfail with the measured
reason (``KNOWN_FAILURES``). The comparisons with Rayleigh damping failed while flexlink's
damping acted on the motion of its basis (the crank at 600 rev/min 103 % of the peak away);
with the damping on each pose's own deformation (``analysis.damping.deformation_damping``) they
pass, and fail again if it acts on the basis's motion.

    PYTHONPATH=. python benchmarks/time_domain_comparison.py   # prints the comparison tables
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import json
import math
from pathlib import Path

import numpy as np
import pytest

from flexlink.analysis import periodic
from flexlink.analysis.frame_motion import pose_speed_terms
from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene
from flexlink.studies.running.steady_response import (SAMPLES, ForcedModel, forced_model,
                                                      periodic_solution)

ROOT = Path(__file__).resolve().parents[2]
RECORD = json.loads((ROOT / "tests" / "data" / "exudyn_case3.json").read_text())
SCENE = ROOT / RECORD["scene"]
RPM = 2.0 * math.pi / 60.0
N_MODES = 6  # flexlink response's default basis
RATIO = 0.02
RAYLEIGH_BETA = 1.1423e-4
LINKS = ("crank", "coupler", "rocker")
SLOW, FAST = 60.0, 600.0  # rev/min: the quasi-static pair (strain times 100 where quasi-static)
# The agreement asked of flexlink's reduced linear model where the damping laws are the same:
# its own mesh moves the midspan peaks by 0.2 % (16 to 32 elements a link), the record's mesh
# and step by under 0.2 % (its convergence check), the transient left by 1e-4.
PEAK_TOLERANCE = 0.01
CURVE_TOLERANCE = 0.02


class Law(enum.StrEnum):
    """flexlink's damping in a comparison, and which of the record's runs it meets."""

    RAYLEIGH = "rayleigh"  # [damping] rayleigh_beta: C = beta K, the record's "rayleigh"
    RECORD_LAW = "record's law"  # the record's "constant ratio" law itself (record_law_damping)
    RATIO = "ratio 0.02"  # --damping-ratio 0.02, against the record's "constant ratio"

    @property
    def recorded_as(self) -> str:
        return "rayleigh" if self is Law.RAYLEIGH else "constant ratio"


ROCKER_AT_1200 = (
    "the rocker at 1200 rev/min lies beyond flexlink's linear model: its peak is 1.7 % "
    "(Rayleigh), 2.5 % (the record's law), 2.3 % (0.02) below the record's. The record's "
    "geometric nonlinearity (the coupler deflects 3.8 times its depth): with the rigid "
    "motion's loads scaled by 0.25 in both the rocker is -0.08 % and 0.61 % over the curve "
    "(test_the_differences_at_1200_shrink_with_the_load), and not through the links' "
    "stretching (EA x 0.1 moves the record's peak by 0.2 %). In the modal basis alone, "
    "without the loads' static answers, it was 2.4 % below at full load and 0.79 % at 0.25")
LAW_MISMATCH = (
    "the crank at 1200 rev/min: a different damping law, not a model error. Strain-rate "
    "damping cannot give every mode 0.02: the record fits each link's beta to its first mode "
    "and so damps mode 3 at 0.077 and mode 5 at 0.18, where flexlink's ratio is 0.02; the crank "
    "runs near its mode (7th harmonic 140 Hz, mode 144 Hz) and feels it. Given the record's own "
    "law, flexlink's crank is +0.9 % (Law.RECORD_LAW, passing) where with 0.02 it is +2.5 %")
KNOWN_FAILURES = {  # (law, rev/min, link): why
    (Law.RAYLEIGH, 1200.0, "rocker"): ROCKER_AT_1200,
    (Law.RECORD_LAW, 1200.0, "rocker"): ROCKER_AT_1200,
    (Law.RATIO, 1200.0, "rocker"): ROCKER_AT_1200,
    (Law.RATIO, 1200.0, "crank"): LAW_MISMATCH,
}


def scene_for(law: Law):
    overrides = {"damping.rayleigh_beta": RAYLEIGH_BETA} if law is Law.RAYLEIGH else None
    return load_scene(SCENE, overrides)


def in_link_frame(link, shapes: np.ndarray) -> np.ndarray:
    """(3 nodes, n): the columns of ``shapes`` (n_dofs, n) at ``link``'s nodes in its own frame
    (u along the link, v across, the rotation), as ``analysis.identity.energy_parts`` takes
    them."""
    nodes = link.nodes
    c, s = math.cos(link.angle), math.sin(link.angle)
    ux, uy = shapes[3 * nodes], shapes[3 * nodes + 1]
    local = np.empty((3 * len(nodes), shapes.shape[1]))
    local[0::3], local[1::3], local[2::3] = c * ux + s * uy, -s * ux + c * uy, shapes[3 * nodes + 2]
    return local


def record_law_damping(periodic, link_beta: dict, joint_beta: float) -> np.ndarray:
    """C (poses, n, n) of the record's strain-rate damping in ``periodic``'s basis at each pose:
    each link's own bending and axial stiffness (its element matrices in its frame) times its
    beta [s] ``link_beta[name]``, and the rest of the elastic K (the joint springs) times
    ``joint_beta`` [s]."""
    out = joint_beta * np.asarray(periodic.elastic_stiffness, dtype=float)
    for p, (frame, shapes) in enumerate(zip(periodic.pose_models, periodic.pose_shapes)):
        for link in frame.links:
            local = in_link_frame(link, shapes)
            out[p] += (link_beta[link.name] - joint_beta) * (local.T @ link.local_matrices()[0]
                                                             @ local)
    return out


def with_damping(model: ForcedModel, samples: np.ndarray) -> ForcedModel:
    return dataclasses.replace(model, periodic=dataclasses.replace(model.periodic,
                                                                   damping_samples=samples))


@functools.cache
def _ratio_model() -> ForcedModel:
    return forced_model(load_scene(SCENE), N_MODES, damping_ratio=RATIO)


@functools.cache
def _model(law: Law) -> ForcedModel:
    if law is Law.RAYLEIGH:
        return forced_model(scene_for(law), N_MODES)
    if law is Law.RATIO:
        return _ratio_model()
    damping = RECORD["damping"]["constant ratio"]
    return with_damping(_ratio_model(), record_law_damping(
        _ratio_model().periodic, damping["link_beta_s"], damping["joint_damper_beta_s"]))


@functools.cache
def _scaled_model(scale: float) -> ForcedModel:
    """flexlink's Rayleigh model with the rigid motion's d'Alembert loads scaled by ``scale``:
    the loads, and the preload they put on the links (K_g of their axial forces, linear in
    them), as the record's load-scaled run has them. Its answer scales exactly with them but
    for that preload's share."""
    def scaled(*args, **kwargs):
        terms = pose_speed_terms(*args, **kwargs)
        return dataclasses.replace(terms, preload=scale * terms.preload,
                                   inertia_loads=scale * terms.inertia_loads)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(periodic, "pose_speed_terms", scaled)
        return forced_model(scene_for(Law.RAYLEIGH), N_MODES)


def midspan_strain(model: ForcedModel, speed: float) -> tuple[np.ndarray, np.ndarray]:
    """(crank angles [rad], strain (samples, points) [-]) at crank ``speed`` [rad/s], read as
    ``steady_response`` reads it, from the periodic solution alone: its Floquet verdict at 60
    rev/min takes minutes (Magnus steps over overdamped vectors), and the stability map's own
    tests check it."""
    turn = 2.0 * np.pi * np.arange(SAMPLES) / SAMPLES
    angles = model.periodic.angles[0] + turn
    q = periodic_solution(model, speed).at(turn)
    return angles, -model.half_depth * np.einsum("spn,sn->sp", model.at(model.curvature, angles),
                                                 q)


@functools.cache
def flexlink_curves(law: Law, rpm: float):
    """(crank angles [rad], {link: midspan strain [microstrain]}) of flexlink's response."""
    model = _model(law)
    angles, strain = midspan_strain(model, rpm * RPM)
    labels = [p.link for p in model.points]
    return angles, {name: strain[:, labels.index(name)] * 1e6 for name in LINKS}


def recorded(damping: str, rpm: float, load_scale: float = 1.0) -> dict:
    return next(run for run in RECORD["runs"] if run["damping"] == damping
                and run["speed_rev_min"] == rpm and run["load_scale"] == load_scale)


def differences(reference: np.ndarray, ours: np.ndarray) -> tuple[float, float, float]:
    """(peak |ours| / peak |reference| - 1, RMS of ours - reference, max |ours - reference|),
    the last two relative to peak |reference|."""
    peak = np.abs(reference).max()
    return (float(np.abs(ours).max() / peak - 1.0),
            float(np.sqrt(np.mean((ours - reference) ** 2)) / peak),
            float(np.abs(ours - reference).max() / peak))


def comparisons():
    """(law, rev/min) of every comparison: each recorded run against flexlink under the laws
    that meet it."""
    for run in RECORD["runs"]:
        for law in Law:
            if law.recorded_as == run["damping"] and run["load_scale"] == 1.0:
                yield law, run["speed_rev_min"]


def comparison_rows() -> list[dict]:
    """One row per comparison and link: the peaks [microstrain], the differences [%] and
    the tolerances [%]."""
    rows = []
    for law, rpm in comparisons():
        _, ours = flexlink_curves(law, rpm)
        for name in LINKS:
            theirs = np.asarray(recorded(law.recorded_as, rpm)["strain_microstrain"][name])
            peak, curve, largest = differences(theirs, ours[name])
            rows.append({"link": name, "speed_rev_min": rpm, "damping": str(law),
                         "recorded_damping": law.recorded_as,
                         "peak_flexlink": float(np.abs(ours[name]).max()),
                         "peak_exudyn": float(np.abs(theirs).max()),
                         "peak_diff_pct": 100 * peak, "curve_diff_pct": 100 * curve,
                         "max_diff_pct": 100 * largest,
                         "peak_tolerance_pct": 100 * PEAK_TOLERANCE,
                         "curve_tolerance_pct": 100 * CURVE_TOLERANCE,
                         "known_failure": (law, rpm, name) in KNOWN_FAILURES})
    return rows


def quasi_static_departures() -> dict:
    """Per link: how far the 600 rev/min curve is from 100 times the 60 rev/min one, flexlink's
    and the record's (Rayleigh), and the difference of the two departures, each (peak, max over
    the turn) relative to the 600 rev/min peak [-]."""
    scale = (FAST / SLOW) ** 2
    _, slow = flexlink_curves(Law.RAYLEIGH, SLOW)
    _, fast = flexlink_curves(Law.RAYLEIGH, FAST)
    out = {}
    for name in LINKS:
        theirs = {rpm: np.asarray(recorded("rayleigh", rpm)["strain_microstrain"][name])
                  for rpm in (SLOW, FAST)}
        ours = fast[name] - scale * slow[name]
        record = theirs[FAST] - scale * theirs[SLOW]
        peak = np.abs(theirs[FAST]).max()
        out[name] = {
            "flexlink": (np.abs(fast[name]).max() / np.abs(scale * slow[name]).max() - 1,
                         np.abs(ours).max() / peak),
            "exudyn": (np.abs(theirs[FAST]).max() / np.abs(scale * theirs[SLOW]).max() - 1,
                       np.abs(record).max() / peak),
            "difference": np.abs(ours - record).max() / peak}
    return out


def table(rows: list[dict]) -> str:
    head = (f"{'link':8} {'rev/min':>7}  {'flexlink damping':16} {'record':14} "
            f"{'peak flexlink':>13} {'peak exudyn':>11} {'peak diff %':>11} "
            f"{'curve diff %':>12} {'max diff %':>10}")
    lines = [head, "-" * len(head)]
    lines += [f"{r['link']:8} {r['speed_rev_min']:7g}  {r['damping']:16} "
              f"{r['recorded_damping']:14} {r['peak_flexlink']:13.3f} {r['peak_exudyn']:11.3f} "
              f"{r['peak_diff_pct']:+11.2f} {r['curve_diff_pct']:12.2f} "
              f"{r['max_diff_pct']:10.2f}"
              + ("  known failure" if r["known_failure"] else "") for r in rows]
    return "\n".join(lines + [
        f"peaks in microstrain; tolerances {100 * PEAK_TOLERANCE:g} % (peak) and "
        f"{100 * CURVE_TOLERANCE:g} % (curve); curve diff: RMS of flexlink - Exudyn over the "
        "turn, max diff: its largest value, both / Exudyn's peak; \"ratio 0.02\" meets a "
        "record whose law differs (see the test's LAW_MISMATCH)"])


def departure_table(departures: dict) -> str:
    lines = [f"{'link':8} {'flexlink peak / max %':>22} {'exudyn peak / max %':>20} "
             f"{'max of the difference %':>24}"]
    lines += [f"{name:8} {100 * d['flexlink'][0]:+11.2f} / {100 * d['flexlink'][1]:<8.2f} "
              f"{100 * d['exudyn'][0]:+10.2f} / {100 * d['exudyn'][1]:<7.2f} "
              f"{100 * d['difference']:24.2f}" for name, d in departures.items()]
    return "\n".join(lines + [
        f"the {FAST:g} rev/min curve against {(FAST / SLOW) ** 2:g} times the {SLOW:g} rev/min "
        "one (Rayleigh): peak ratio - 1, and the largest difference over the turn / the "
        f"{FAST:g} rev/min peak"])


def test_record_checked_its_element_against_closed_forms():
    """The record's own sanity checks: its cable element against the Euler-Bernoulli closed
    forms (order-4 frequency convergence leaves 6e-8 at 32 elements; the static tip load is
    held exactly by cubic elements, up to the geometric nonlinearity of a 1e-4 L deflection)."""
    checks = RECORD["closed_form_checks"]
    for key in ("pinned_pinned_first_Hz", "cantilever_tip_deflection_m",
                "cantilever_midspan_curvature_per_m"):
        check = checks[key]
        assert abs(check["exudyn"] / check["closed_form"] - 1) < 1e-6, (key, check)


@pytest.mark.parametrize("pins, overrides", [("elastic_pins", None),
                                             ("rigid_pins", {"joints.Kt": "rigid"})])
def test_linkage_frequencies_match_flexlink_modes(pins, overrides):
    """At rest at its pose the recorded linkage is flexlink's: the same cubic bending
    interpolation at the same mesh; only the axial one differs (cubic in the ANCF cable, linear
    in flexlink's frame), which moves the modes by up to 5e-8 at 32 elements."""
    theirs = np.array(RECORD["linkage_frequencies_at_pose"][pins]["frequencies_Hz"])
    ours = analyze(load_scene(SCENE, overrides), len(theirs),
                   RECORD["model"]["elements_per_link"]).modes.frequencies[:len(theirs)]
    np.testing.assert_allclose(ours, theirs, rtol=5e-7)


def test_record_samples_flexlinks_crank_angles():
    angles, _ = flexlink_curves(Law.RATIO, RECORD["runs"][0]["speed_rev_min"])
    samples = RECORD["samples"]
    theirs = samples["first_crank_angle_rad"] + samples["step_rad"] * np.arange(samples["count"])
    np.testing.assert_allclose(angles, theirs, rtol=0, atol=1e-12)


def test_record_reached_its_steady_state():
    """The last two recorded turns agree to 1e-3 of the peak (the transient left), and the
    record's own mesh and step changes stay under 1e-2 (its convergence check)."""
    for run in RECORD["runs"]:
        assert max(run["turn_to_turn_change"].values()) < 1e-3, run["turn_to_turn_change"]
    for series in ("elements_per_link", "steps_per_sample"):
        spread = RECORD["convergence"][series]["difference_from_finest"]
        finest_but_one = sorted(spread, key=int)[-1]
        assert max(spread[finest_but_one].values()) < 1e-2, (series, spread)


@pytest.mark.slow
def test_the_record_law_with_one_beta_is_flexlinks_rayleigh():
    """The record's law written in flexlink's basis, every beta the same, is flexlink's own
    Rayleigh damping beta K at every pose (each pose's modes in the basis): the link parts
    and the joint springs make up the whole elastic K. 1e-9 of the largest entry: the
    round-off of the eigen decomposition of a K whose entries span 1e3 to 1e11."""
    rayleigh = _model(Law.RAYLEIGH).periodic
    assert np.abs(rayleigh.mass - _ratio_model().periodic.mass).max() == 0.0  # one basis
    betas = dict.fromkeys(LINKS, RAYLEIGH_BETA)
    ours = record_law_damping(_ratio_model().periodic, betas, RAYLEIGH_BETA)
    assert np.abs(ours - rayleigh.damping).max() <= 1e-9 * np.abs(rayleigh.damping).max()


@pytest.mark.slow
def test_the_record_law_in_flexlink_damps_the_records_modes_as_exudyn_does():
    """At rest at the scene's pose, the damped modes of flexlink's basis (M, the record's
    law's C, the elastic K) have the frequencies and damping ratios Exudyn's linearised
    model of the record has (its complex eigenvalues): the same law in both, mode by mode,
    the higher modes' ratios far from 0.02 (mode 3 0.077, mode 5 0.18). The first five within
    1e-4 in frequency and 1e-3 in ratio (measured 7e-5 and 3.3e-4: flexlink's 16 elements a
    link against the record's 32, the basis's Ritz values); the sixth (870 Hz), which this
    non-proportional damping couples to vectors outside the basis, within 2e-3 and 2e-2
    (measured 9.7e-4 and 9.9e-3; under Rayleigh, proportional, all six within 8e-5)."""
    law = RECORD["damping"]["constant ratio"]
    model = _model(Law.RECORD_LAW).periodic
    M, K, C = model.mass[0], model.elastic_stiffness[0], model.damping[0]
    n = len(M)
    first_order = np.block([[np.zeros((n, n)), np.eye(n)],
                            [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam = np.linalg.eigvals(first_order)
    lam = lam[lam.imag > 0]
    lam = lam[np.argsort(np.abs(lam))][:len(law["modes_Hz"])]
    frequencies, ratios = np.abs(lam) / (2 * np.pi), -lam.real / np.abs(lam)
    np.testing.assert_allclose(frequencies[:5], law["modes_Hz"][:5], rtol=1e-4)
    np.testing.assert_allclose(ratios[:5], law["damping_ratios"][:5], rtol=1e-3)
    np.testing.assert_allclose(frequencies[5], law["modes_Hz"][5], rtol=2e-3)
    np.testing.assert_allclose(ratios[5], law["damping_ratios"][5], rtol=2e-2)
    assert max(law["damping_ratios"]) > 4 * RATIO  # the law is not one ratio for all


def _cases():
    for law, rpm in comparisons():
        for name in LINKS:
            marks = [pytest.mark.slow]
            if (law, rpm, name) in KNOWN_FAILURES:
                marks.append(pytest.mark.xfail(strict=True,
                                               reason=KNOWN_FAILURES[law, rpm, name]))
            yield pytest.param(law, rpm, name, marks=marks,
                               id=f"{law.replace(' ', '-')}-{rpm:g}-{name}")


@pytest.mark.parametrize("law, rpm, link", list(_cases()))
def test_steady_strain_matches_the_time_domain_record(law, rpm, link):
    theirs = np.asarray(recorded(law.recorded_as, rpm)["strain_microstrain"][link])
    _, ours = flexlink_curves(law, rpm)
    peak, curve, _ = differences(theirs, ours[link])
    assert abs(peak) < PEAK_TOLERANCE and curve < CURVE_TOLERANCE, (peak, curve)


@pytest.mark.slow
def test_the_cranks_departure_from_quasi_static_scaling_is_the_time_domains():
    """The crank's strain at 600 rev/min is 100 times its strain at 60 rev/min only to 1.3 % at
    the peak and 2.6 % of the peak over the turn (flexlink, Rayleigh). The record departs the
    same way, independently (1.25 % and 2.57 %), so that is the crank's own dynamics (its load
    harmonics reach about 60 Hz at 600 rev/min, its mode 144 Hz), not flexlink's damping or
    basis. The two departures differ by 0.15 % of the peak at most over the turn; allowed 0.3 %:
    flexlink's curves are 0.15 % (600 rev/min) and under 0.01 % (60 rev/min, times 100) of
    the peak from the record's at most. The peak's and the curve's departures agree within
    0.2 % (measured 0.07 % and 0.03 %)."""
    crank = quasi_static_departures()["crank"]
    ours, theirs = crank["flexlink"], crank["exudyn"]
    assert abs(ours[0] - theirs[0]) <= 0.002 and abs(ours[1] - theirs[1]) <= 0.002, crank
    assert crank["difference"] <= 0.003, crank


ROCKER_TOLERANCE = 0.003


@pytest.mark.slow
@pytest.mark.parametrize("law, rpm", [(law, rpm) for law, rpm in comparisons() if rpm < 1200.0],
                         ids=lambda v: str(v).replace(" ", "-"))
def test_the_loads_static_answers_bring_the_rocker_to_the_record(law, rpm):
    """The rocker, whose midspan strain is the smallest of the three and leans most on the
    static share of the modes the basis leaves out: its peak within 0.3 % of the record's at
    60 and 600 rev/min (measured +0.16 to +0.20 %; the record's own mesh and step move it by
    under 0.2 %), which the modal basis alone misses (-0.58 to -0.61 %, the added vectors
    off)."""
    theirs = np.asarray(recorded(law.recorded_as, rpm)["strain_microstrain"]["rocker"])
    peak, _, _ = differences(theirs, flexlink_curves(law, rpm)[1]["rocker"])
    assert abs(peak) < ROCKER_TOLERANCE, peak


def load_scaled_rows() -> list[dict]:
    """Per link at the record's load-scaled speed (Rayleigh): the differences [%] (peak,
    curve) at full load and with the rigid motion's loads scaled in both."""
    scaled = next(run for run in RECORD["runs"] if run["load_scale"] != 1.0)
    rpm, scale = scaled["speed_rev_min"], scaled["load_scale"]
    model = _scaled_model(scale)
    _, strain = midspan_strain(model, rpm * RPM)
    labels = [p.link for p in model.points]
    _, full = flexlink_curves(Law.RAYLEIGH, rpm)
    rows = []
    for name in LINKS:
        theirs = np.asarray(scaled["strain_microstrain"][name])
        at_full = differences(np.asarray(recorded("rayleigh", rpm)["strain_microstrain"][name]),
                              full[name])
        at_scale = differences(theirs, strain[:, labels.index(name)] * 1e6)
        rows.append({"link": name, "speed_rev_min": rpm, "load_scale": scale,
                     "full_peak_diff_pct": 100 * at_full[0],
                     "full_curve_diff_pct": 100 * at_full[1],
                     "scaled_peak_diff_pct": 100 * at_scale[0],
                     "scaled_curve_diff_pct": 100 * at_scale[1]})
    return rows


def load_scaled_table(rows: list[dict]) -> str:
    lines = [f"{'link':8} {'rev/min':>7} {'full load peak / curve %':>25} "
             f"{'loads x S peak / curve %':>25}"]
    lines += [f"{r['link']:8} {r['speed_rev_min']:7g} {r['full_peak_diff_pct']:+13.2f} / "
              f"{r['full_curve_diff_pct']:<9.2f} {r['scaled_peak_diff_pct']:+13.2f} / "
              f"{r['scaled_curve_diff_pct']:<9.2f}" for r in rows]
    return "\n".join(lines + [
        f"flexlink against the record, Rayleigh, with the rigid motion's loads as they are and "
        f"scaled by S = {rows[0]['load_scale']:g} in both (a counter-load in the record; "
        "flexlink's loads and their preload)"])


@pytest.mark.slow
def test_the_differences_at_1200_shrink_with_the_load():
    """Most of the differences at 1200 rev/min grow with the amplitude: the time domain's
    geometric nonlinearity, which flexlink's linear model leaves out. With the rigid motion's
    loads scaled by 0.25 in both (flexlink's answer, its inertia preload scaled too, is then
    the linear answer to the smaller loads; the record's by a lumped counter-load at its
    nodes) the curve differences fall from 1.61, 0.95, 1.79 % (crank, coupler, rocker) to
    0.64, 0.35, 0.61 %, and the rocker's peak difference from -1.74 to -0.08 %. A linear
    model's error would scale with the loads and keep its share; asked: each curve difference
    at most 0.7 of its full-load value (measured 0.40, 0.37, 0.34)."""
    for row in load_scaled_rows():
        assert row["scaled_curve_diff_pct"] <= 0.7 * row["full_curve_diff_pct"], row
