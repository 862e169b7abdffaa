"""The large sparse check (``flexlink stability --slow``) on sizes the suite can afford: its model
(graded pinned spans) against the closed form, and its bookkeeping of the child processes'
answers (memory per DOF, the fitted exponent, the verdict) against a hand calculation."""

import math
import subprocess
from types import SimpleNamespace

import numpy as np
import pytest
from conftest import CASES_DIR

import flexlink.studies.verification.self_checks as stability
from flexlink.scene import load_scene

CASE1 = CASES_DIR / "case1.toml"


def test_graded_spans_lie_in_a_row_and_the_child_finds_the_longest_span_closed_form(capsys):
    section = next(iter(load_scene(CASE1).sections.values()))
    topology, points = stability.graded_spans(section, 8)
    # six long spans, then two graded from 0.1 m: 0.1 (1 - 0.05 k / 2), k = 0, 1
    lengths = [*stability.LONG_SPANS, 0.1, 0.0975]
    assert np.array([points[f"J{i}"] for i in range(9)]) == pytest.approx(
        np.c_[np.concatenate([[0.0], np.cumsum(lengths)]), np.zeros(9)], abs=1e-15)
    assert [(j.ground, j.Kt, j.Kr) for j in topology.joints] == [(True, math.inf, 0.0)] * 9
    assert [(link.start, link.end) for link in topology.links] == [
        (f"J{i}", f"J{i + 1}") for i in range(8)]

    stability._large_child(str(CASE1), 2)
    n, f1, exact, before, after = capsys.readouterr().out.split()
    # simply supported span of 0.15 m: f = (pi / L)^2 sqrt(EI / rhoA) / (2 pi)
    closed = (math.pi / 0.15) ** 2 * math.sqrt(section.EI / section.mass_per_length) / (2 * math.pi)
    assert float(exact) == pytest.approx(closed, rel=1e-14)
    # 1e-6: 32 Hermite elements per span are far finer than the first mode needs (h^4 error)
    assert float(f1) == pytest.approx(closed, rel=1e-6)
    assert int(n) > 0 and 0 < int(before) <= int(after)


def test_the_report_of_the_children_is_the_hand_calculation(monkeypatch):
    # children's answers: DOFs, f1, closed form [Hz], RSS before and peak after [kB]; the work's
    # memory doubles with the DOFs (exponent 1) at 8 kB per DOF
    answers = {1: "1000 50.0 50.0 100000 108000", 2: "2000 50.0 50.0 100000 116000"}

    def child(command, **_):
        spans = int(command[-1].rsplit(",", 1)[1].rstrip(")"))
        return SimpleNamespace(returncode=0, stdout=answers[spans], stderr="")
    monkeypatch.setattr(subprocess, "run", child)
    sizes = (90, 190)  # one and two spans of 3 x 33 - 4 = 95 free DOFs
    check = stability.large_sparse(SimpleNamespace(path="x.toml"), sizes=sizes)
    rows = check.details["rows"]
    assert [(r["dofs"], r["f1_Hz"], r["closed_form_Hz"]) for r in rows] == [
        (1000, 50.0, 50.0), (2000, 50.0, 50.0)]
    assert [r["work_MB"] for r in rows] == pytest.approx([8000 / 1024, 16000 / 1024])
    assert check.details["memory_exponent"] == pytest.approx(1.0, abs=1e-12)
    assert "kB per DOF 8.00, 8.00" in check.got and check.passed

    answers[2] = "2000 50.0 50.001 100000 116000"  # 2e-5 from the closed form: fails
    assert not stability.large_sparse(SimpleNamespace(path="x.toml"), sizes=sizes).passed
