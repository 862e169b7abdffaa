"""The JSON documents a user reads, key by key, from small hand-made study results: every key
the renderer's docstring promises is there under its name, speeds come out in rev/min
(omega 60 / 2 pi, worked out here rather than taken from flexlink.units), and a value that is
not a number (a band past a divergence) becomes null so the document stays strict JSON.
Each study result is built from a few numbers, so each test costs milliseconds; the commands'
own tests run the studies for real."""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.analysis.mesh import COMMAND_LINE, MeshRule
from flexlink.output.cycle.campbell import campbell_document
from flexlink.output.verification.convergence import convergence_document
from flexlink.output.running.dynamic_campbell import dynamic_json
from flexlink.output.pose.scene_summary import modes_files, summary_document
from flexlink.output.report_data import _rounded, at_speed_data
from flexlink.studies.cycle.bands import Band, CriticalSpeed, NearestMargin
from flexlink.studies.cycle.campbell import CampbellStudy
from flexlink.studies.verification.convergence import (CHOICES, ConvergenceStudy, Level, relative_errors,
                                          richardson)
from flexlink.studies.running.dynamic_campbell import Divergence, DynamicCampbell
from flexlink.studies.report_scene import SPEED_STEPS, AtSpeed
from flexlink.studies.pose.scene_summary import scene_summary
from flexlink.studies.cycle.tracking import TrackedMap, Tracks

RPM_PER_RAD_S = 60 / (2 * math.pi)  # 1 rad/s in rev/min, written out for the oracle
POSES = 6
Q = np.linspace(0.0, 2 * math.pi, POSES, endpoint=False)
F = np.column_stack([10 + np.sin(Q), 30 + np.cos(Q)])  # two tracked lines [Hz] over the turn


def _strict(document: dict) -> dict:
    """The document through strict JSON (no NaN, no infinity) and back."""
    return json.loads(json.dumps(document, allow_nan=False))


def _tracked() -> TrackedMap:
    tracks = Tracks(frequencies=F, shapes=tuple(np.eye(3)[:, :2] for _ in Q),
                    mac=np.ones((POSES, 2)), rank=np.tile(np.arange(2), (POSES, 1)), events=())
    return TrackedMap(scene="synthetic", q=Q, frequencies=F, tracks=tracks, mu90={},
                      labels=("bending 1", "bending 2"), mechanism_counts=np.zeros(POSES, dtype=int))


def test_campbell_document_names_every_range_in_rev_per_min_and_the_nearest_margin():
    # hand-made answers (the studies' own tests derive them): nothing critical below 120 rev/min,
    # the nearest approach harmonic 3 of mode 1 at the top of the window
    window = (0.0, 120 / RPM_PER_RAD_S)
    bands = (Band(1, 9.0, 11.0), Band(2, 29.0, 31.0))
    critical = (CriticalSpeed(mode=2, harmonic=3, low=580 / RPM_PER_RAD_S,
                              high=620 / RPM_PER_RAD_S),)
    nearest = NearestMargin(mode=1, harmonic=3, gap=(9.0 - 6.0) / 9.0, speed=window[1])
    study = CampbellStudy(tracked=_tracked(), mesh=MeshRule(2, COMMAND_LINE), poses=POSES,
                          window=window, margin=0.05, harmonics=3, bands=bands,
                          critical=critical, nearest=nearest)
    doc = _strict(campbell_document(SimpleNamespace(name="synthetic"), study))
    assert set(doc) == {"command", "scene", "speeds_rev_per_min", "margin", "harmonics", "poses",
                        "mesh", "bands", "critical_speeds", "nearest_margin", "tracking_events",
                        "tracking_reseeds", "periodicity", "unsampled_dead_centres_deg",
                        "unsampled_note"}
    assert doc["speeds_rev_per_min"] == pytest.approx([0.0, 120.0], rel=1e-14)  # rounding only
    assert doc["bands"] == [{"mode": 1, "label": "bending 1", "min_Hz": 9.0, "max_Hz": 11.0},
                            {"mode": 2, "label": "bending 2", "min_Hz": 29.0, "max_Hz": 31.0}]
    [c] = doc["critical_speeds"]
    assert (c["mode"], c["harmonic"]) == (2, 3)
    assert [c["from_rev_per_min"], c["to_rev_per_min"]] == pytest.approx([580, 620], rel=1e-14)
    n = doc["nearest_margin"]
    assert set(n) == {"mode", "harmonic", "relative_gap", "at_rev_per_min"}
    assert (n["mode"], n["harmonic"]) == (1, 3)
    assert n["relative_gap"] == pytest.approx(1 / 3, rel=1e-14)
    assert n["at_rev_per_min"] == pytest.approx(120.0, rel=1e-14)


def test_convergence_levels_name_their_solver_choice():
    # f_h = 1 + h^2 at 1, 2, 4 elements: two choices, three levels each
    levels = [Level(choice, n, 3 * n, 0.001, 0.002, np.array([1 + n**-2.0, 2 + n**-2.0]))
              for choice in CHOICES[:2] for n in (1, 2, 4)]
    ext = richardson(levels[:3])
    study = ConvergenceStudy(scene="synthetic", file="synthetic.toml", n_modes=2, repeats=1,
                             tol=1e-6, levels=tuple(levels), extrapolation=ext,
                             errors=relative_errors(levels, ext.reference), cheapest=None,
                             measured=None)
    doc = convergence_document(study)
    for row, level in zip(doc["levels"], levels):
        assert set(row) == {"choice", "method", "mass", "refined", "elements_per_link", "dofs",
                            "assembly_s", "solve_s", "runs", "frequencies_Hz", "relative_error",
                            "max_relative_error"}
        assert (row["method"], row["mass"], row["refined"]) == (
            str(level.choice.method), str(level.choice.mass), level.choice.refine)
        assert row["elements_per_link"] == level.elements and row["dofs"] == 3 * level.elements
    assert {row["method"] for row in doc["levels"]} == {"sparse", "dense"}


def test_bands_at_speed_past_a_divergence_are_null_and_the_rest_are_the_bands():
    speeds = np.array([0.0, 100.0, 200.0]) / RPM_PER_RAD_S
    f = np.stack([F, F * 0.99, np.full_like(F, np.nan)])  # diverged at the third speed
    result = DynamicCampbell(scene="synthetic", q=Q, speeds=speeds, frequencies=f, static=F,
                             basis=5, divergence=Divergence(speed=190 / RPM_PER_RAD_S, q=0.5,
                                                            line=1, grid_speed=speeds[2],
                                                            growth_rate=3.0))
    doc = _strict(dynamic_json(result, []))
    at_speed = doc["bands_at_speed"]
    assert [b["rev_per_min"] for b in at_speed] == pytest.approx([0, 100, 200], abs=1e-12)
    for band, freq in zip(at_speed[:2], f[:2]):
        assert band["min_Hz"] == pytest.approx(freq.min(axis=0).tolist(), rel=1e-15)
        assert band["max_Hz"] == pytest.approx(freq.max(axis=0).tolist(), rel=1e-15)
    assert at_speed[2]["min_Hz"] is None and at_speed[2]["max_Hz"] is None
    assert doc["divergence"]["rev_per_min"] == pytest.approx(190, rel=1e-14)
    assert doc["divergence"]["grid_rev_per_min"] == pytest.approx(200, rel=1e-14)


def _point(frequencies, eigenvalues):
    """A stand-in operating point with just what the page reads of one."""
    return SimpleNamespace(frequencies=np.asarray(frequencies),
                           static_frequencies=np.asarray([10.0, 30.0]),
                           modes=SimpleNamespace(eigenvalues=np.asarray(eigenvalues),
                                                 negative_stiffness=False),
                           axial_forces={"coupler": np.array([-2.0, 5.0])})


def test_at_speed_data_gives_the_speed_grid_in_rev_per_min_from_rest_to_the_declared_speed():
    declared = 500.0  # [rev/min]
    speeds = np.linspace(0.0, declared / RPM_PER_RAD_S, SPEED_STEPS)
    points = tuple(_point([10.0, 30.0], [2j * math.pi * 10.0, 2j * math.pi * 30.0])
                   for _ in speeds)
    at = AtSpeed(speed=speeds[-1], crank_acceleration=0.0, torque=None,
                 torque_unavailable="no torque in this test", speeds=speeds, points=points,
                 response_unavailable="no response in this test")
    data = _strict(at_speed_data(at))
    assert data["rev_per_min"] == pytest.approx(declared, rel=1e-14)
    assert data["modes"]["rev_per_min"] == pytest.approx(np.linspace(0, declared, SPEED_STEPS),
                                                         rel=1e-14, abs=1e-12)
    assert data["modes"]["frequencies_Hz"] == [[10.0] * SPEED_STEPS, [30.0] * SPEED_STEPS]
    assert data["modes"]["axial_N"] == [{"link": "coupler", "tension": 5.0, "compression": -2.0}]
    assert data["torque"] == {"unavailable": "no torque in this test"}


@pytest.mark.parametrize("values, shown", [
    ([12345.678, -0.5], [12346.0, -0.0]),   # 5 digits of the largest: no decimal
    ([123456.789, 1.04], [123457.0, 1.0]),  # more than 5 integer digits: kept, no decimal
    ([1.234567, 0.000123], [1.2346, 0.0001]),
])
def test_page_values_keep_five_significant_digits_of_the_largest(values, shown):
    assert _rounded(np.array(values)) == shown


def test_the_printed_modes_document_lists_failures_even_when_no_scene_succeeded(tmp_path):
    failures = [{"file": "a.toml", "error": "a.toml: linkage.R2: expected a length"},
                {"file": "b.toml", "error": "b.toml: cannot read"}]
    documents, tables, printed = modes_files([], tmp_path, failures)
    assert printed["failures"] == failures
    assert printed["cases"] == [] and printed["files"] == []
    assert documents == {} and tables == {}


def _case1_written(folder, name: str, extra: str) -> str:
    text = (CASES_DIR / "case1.toml").read_text().replace(
        'base = "_table2.toml"', f'base = "{(CASES_DIR / "_table2.toml").as_posix()}"')
    path = folder / f"{name}.toml"
    path.write_text(text + extra)
    return str(path)


def test_the_other_shear_source_is_the_scene_solved_with_that_source(tmp_path):
    # Timoshenko links read the laminate's G, so the other source moves the frequencies; the
    # document's alternative must be that scene, solved on its own, on the same mesh
    timoshenko = '\n[model]\nbeam = "timoshenko"\n'
    used = _case1_written(tmp_path, "printed", timoshenko)
    other = _case1_written(tmp_path, "isotropic", timoshenko.replace(
        "[model]", '[material.composite]\nfiber = "carbon_fiber"\nmatrix = "polyester"\n'
        'fiber_volume_fraction = 0.5\nshear_modulus = "isotropic"\n\n[model]'))
    doc = summary_document(scene_summary(used, 2, 2, alternatives=True))
    alt = doc["other_shear_source"]
    assert (alt["field"], alt["value"], alt["used"]) == (
        "material.composite.shear_modulus", "isotropic", "printed")
    direct = [row["computed_Hz"] for row in summary_document(scene_summary(other, 2, 2))["modes"]]
    # the same model solved twice: equal to the eigen solver's rounding
    assert alt["computed_Hz"] == pytest.approx(direct, rel=1e-10)
    assert alt["computed_Hz"] != pytest.approx([r["computed_Hz"] for r in doc["modes"]],
                                               rel=1e-6)
