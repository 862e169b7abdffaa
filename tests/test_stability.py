"""The fast stability checks (flexlink/stability.py), one test each: every check must pass, and
a check must be able to fail (a broken input is reported as FAIL, not hidden)."""

from pathlib import Path

import dataclasses
import json

import pytest
from click.testing import CliRunner

from flexlink import load_scene
from flexlink.studies import stability as st
from flexlink.cli import main

ROOT = Path(__file__).resolve().parent.parent
CASE1 = ROOT / "cases" / "case1.toml"


@pytest.fixture(scope="module")
def scene():
    return load_scene(CASE1)


@pytest.mark.parametrize("check", st.FAST, ids=lambda f: f.__name__)
def test_fast_check_passes(scene, check):
    result = check(scene)
    for c in result if isinstance(result, list) else [result]:
        assert c.passed, f"{c.id} {c.name}: expected {c.expected}; got {c.got}"


def test_a_failing_check_is_reported(scene, monkeypatch):
    # two elements per cantilever: its frequency misses the closed form by more than 1e-6, and
    # check 7a must say FAIL
    monkeypatch.setattr(st, "ELEMENTS", 2)
    assert not st.repeated(scene).passed


def test_penalty_switch_is_logged_and_exact(scene, caplog):
    from flexlink.fe.rigid import rigidified, rigid_threshold
    from flexlink.fe.model import build_model
    topo = scene.topology(8)
    model = build_model(dataclasses.replace(topo, joints=tuple(
        dataclasses.replace(j, Kt=1e30) for j in topo.joints)), scene.rigid_pose().joints)
    with caplog.at_level("WARNING", logger="flexlink.fe.rigid"):
        stiff = rigidified(model)
    assert "treated as rigid" in caplog.text
    translational = model.springs.dof_a % 3 != 2
    assert all(map(lambda k: k == float("inf"), stiff.springs.stiffness[translational]))
    assert (rigid_threshold(model)[translational] < 1e30).all()


def test_stability_command(tmp_path, monkeypatch):
    # the checks themselves are tested above; here the command's output and exit code
    monkeypatch.setattr(st, "FAST", (st.repeated, st.units))
    result = CliRunner().invoke(main, ["stability", str(CASE1), "--json", "--out", str(tmp_path)])
    doc = json.loads(result.stdout)
    assert result.exit_code == 0 and doc["passed"] == doc["total"] == 5
    assert [c["id"] for c in doc["checks"]] == ["7a", "8a", "8b", "8c", "8d"]
    assert json.loads((tmp_path / "case1" / "stability.json").read_text()) == doc
    monkeypatch.setattr(st, "ELEMENTS", 2)  # makes 7a fail: exit code 1, FAIL printed
    result = CliRunner().invoke(main, ["stability", str(CASE1), "--out", str(tmp_path)])
    assert result.exit_code == 1 and "[FAIL] 7a" in result.output
