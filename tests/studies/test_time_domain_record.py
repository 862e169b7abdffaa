"""The steady response of the running linkage against an independent time-domain answer
(tests/data/exudyn_case3.json, with its provenance; made by scripts/record_exudyn_case3.py;
Exudyn is not needed here).

Exudyn integrated Table II case 3 in time from rest: ANCF cable links, the bearings as springs,
the crank angle prescribed (ramped up, then held), generalized-alpha, the last of many turns
recorded. flexlink's ``steady_response`` solves the same linkage's periodic state directly, as
``flexlink response`` does (6 static modes in the basis, 37 poses). The two are compared per
link, at each recorded speed and damping law, on the midspan bending strain over the turn:
the peak |strain| and the RMS of the difference over the turn, both relative to the recorded
peak.

Why they need not agree to round-off: flexlink's model is linear about the rigid motion in a
reduced basis (16 vectors, the Fourier series of 37 poses, 16 elements a link with the strain
read on one side of the midspan node), Exudyn's is geometrically exact at 32 elements a link
(its own mesh and step changes: under 0.2 % of the peaks); and "constant ratio" damps every
basis vector at 0.02 in flexlink, but in the time domain only each link's first mode, the
others more (stiffness-proportional per link; see ``tolerances``).

The comparisons that fail today are marked strict xfail (``KNOWN_FAILURES``): with Rayleigh
damping, and at 1200 rev/min even with one ratio, flexlink's curves move with the damping of its
stiff basis vectors, which a quasi-static strain should not feel. When the damping acts on the
deformation only they should pass, turn into XPASS failures, and lose their mark.

    PYTHONPATH=. python benchmarks/time_domain_comparison.py   # prints the comparison tables
"""

from __future__ import annotations

import functools
import json
import math
from pathlib import Path

import numpy as np
import pytest

from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene
from flexlink.studies.running.steady_response import forced_model, steady_response

ROOT = Path(__file__).resolve().parents[2]
RECORD = json.loads((ROOT / "tests" / "data" / "exudyn_case3.json").read_text())
SCENE = ROOT / RECORD["scene"]
RPM = 2.0 * math.pi / 60.0
N_MODES = 6  # flexlink response's default basis
RATIO = 0.02
RAYLEIGH_BETA = 1.1423e-4
LINKS = ("crank", "coupler", "rocker")
# The agreement asked of flexlink's reduced linear model where the damping laws are the same:
# its own mesh moves the midspan peaks by 0.2 % (16 to 32 elements a link), the record's mesh
# and step by under 0.2 % (its convergence check), the transient left by 1e-4.
PEAK_TOLERANCE = 0.01
CURVE_TOLERANCE = 0.02
BASIS_DAMPING = ("flexlink's modal damping acts on the motion of its basis: the damping of the "
                 "stiff basis vectors moves the quasi-static strain")
KNOWN_FAILURES = {  # (damping, rev/min, link): why, until the damping acts on deformation only
    ("rayleigh", 600.0, "crank"): BASIS_DAMPING,
    ("rayleigh", 600.0, "coupler"): BASIS_DAMPING,
    ("rayleigh", 1200.0, "crank"): BASIS_DAMPING,
    ("rayleigh", 1200.0, "coupler"): BASIS_DAMPING,
    ("rayleigh", 1200.0, "rocker"): BASIS_DAMPING,
    ("constant ratio", 1200.0, "crank"): BASIS_DAMPING + "; at 1200 rev/min even at one ratio",
    ("constant ratio", 1200.0, "rocker"): BASIS_DAMPING + "; at 1200 rev/min even at one ratio",
}


def scene_for(law: str):
    overrides = {"damping.rayleigh_beta": RAYLEIGH_BETA} if law == "rayleigh" else None
    return load_scene(SCENE, overrides)


@functools.cache
def _model(law: str):
    return forced_model(scene_for(law), N_MODES,
                        damping_ratio=RATIO if law == "constant ratio" else None)


@functools.cache
def flexlink_curves(law: str, rpm: float):
    """(crank angles [rad], {link: midspan strain [microstrain]}) of flexlink's response."""
    model = _model(law)
    response = steady_response(model, rpm * RPM)
    labels = [p.link for p in model.points]
    return response.angles, {name: response.strain[:, labels.index(name)] * 1e6
                             for name in LINKS}


def recorded(law: str, rpm: float) -> dict:
    return next(run for run in RECORD["runs"]
                if run["damping"] == law and run["speed_rev_min"] == rpm)


def differences(reference: np.ndarray, ours: np.ndarray) -> tuple[float, float, float]:
    """(peak |ours| / peak |reference| - 1, RMS of ours - reference, max |ours - reference|),
    the last two relative to peak |reference|."""
    peak = np.abs(reference).max()
    return (float(np.abs(ours).max() / peak - 1.0),
            float(np.sqrt(np.mean((ours - reference) ** 2)) / peak),
            float(np.abs(ours - reference).max() / peak))


def tolerances(law: str, rpm: float, link: str) -> tuple[float, float]:
    """(peak, curve) tolerances [-]. A constant ratio for every mode is not a law strain-rate
    damping can hold: the record fits each link's first mode and damps the others more. So the
    record's own spread between its two laws (how far its answer moves when the damping of
    every mode but the first changes) is added there; Rayleigh is the same law in both."""
    if law != "constant ratio":
        return PEAK_TOLERANCE, CURVE_TOLERANCE
    a = np.asarray(recorded("constant ratio", rpm)["strain_microstrain"][link])
    b = np.asarray(recorded("rayleigh", rpm)["strain_microstrain"][link])
    peak, curve, _ = differences(a, b)
    return PEAK_TOLERANCE + abs(peak), CURVE_TOLERANCE + curve


def comparison_rows() -> list[dict]:
    """One row per recorded speed, damping law and link: the peaks [microstrain], the
    differences [%] and their tolerances [%]."""
    rows = []
    for run in RECORD["runs"]:
        law, rpm = run["damping"], run["speed_rev_min"]
        _, ours = flexlink_curves(law, rpm)
        for name in LINKS:
            theirs = np.asarray(run["strain_microstrain"][name])
            peak, curve, largest = differences(theirs, ours[name])
            peak_tol, curve_tol = tolerances(law, rpm, name)
            rows.append({"link": name, "speed_rev_min": rpm, "damping": law,
                         "peak_flexlink": float(np.abs(ours[name]).max()),
                         "peak_exudyn": float(np.abs(theirs).max()),
                         "peak_diff_pct": 100 * peak, "curve_diff_pct": 100 * curve,
                         "max_diff_pct": 100 * largest, "peak_tolerance_pct": 100 * peak_tol,
                         "curve_tolerance_pct": 100 * curve_tol,
                         "known_failure": (law, rpm, name) in KNOWN_FAILURES})
    return rows


def table(rows: list[dict]) -> str:
    head = (f"{'link':8} {'rev/min':>7}  {'damping':15} {'peak flexlink':>13} "
            f"{'peak exudyn':>11} {'peak diff %':>11} {'curve diff %':>12} {'max diff %':>10} "
            f"{'tol peak/curve %':>16}")
    lines = [head, "-" * len(head)]
    lines += [f"{r['link']:8} {r['speed_rev_min']:7g}  {r['damping']:15} "
              f"{r['peak_flexlink']:13.3f} {r['peak_exudyn']:11.3f} "
              f"{r['peak_diff_pct']:+11.2f} {r['curve_diff_pct']:12.2f} "
              f"{r['max_diff_pct']:10.2f} "
              f"{r['peak_tolerance_pct']:7.2f}/{r['curve_tolerance_pct']:<5.2f}"
              + ("  known failure" if r["known_failure"] else "") for r in rows]
    return "\n".join(lines + [
        "peaks in microstrain; curve diff: RMS of flexlink - Exudyn over the turn, max diff: "
        "its largest value, both / Exudyn's peak"])


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
    angles, _ = flexlink_curves("constant ratio", RECORD["runs"][0]["speed_rev_min"])
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


def _cases():
    for run in RECORD["runs"]:
        law, rpm = run["damping"], run["speed_rev_min"]
        for name in LINKS:
            marks = [pytest.mark.slow]
            if (law, rpm, name) in KNOWN_FAILURES:
                marks.append(pytest.mark.xfail(strict=True,
                                               reason=KNOWN_FAILURES[law, rpm, name]))
            yield pytest.param(law, rpm, name, marks=marks,
                               id=f"{law.replace(' ', '-')}-{rpm:g}-{name}")


@pytest.mark.parametrize("law, rpm, link", list(_cases()))
def test_steady_strain_matches_the_time_domain_record(law, rpm, link):
    theirs = np.asarray(recorded(law, rpm)["strain_microstrain"][link])
    _, ours = flexlink_curves(law, rpm)
    peak, curve, _ = differences(theirs, ours[link])
    peak_tol, curve_tol = tolerances(law, rpm, link)
    assert abs(peak) < peak_tol and curve < curve_tol, (peak, curve, peak_tol, curve_tol)
