"""One model path, one mesh rule, and hostile inputs on the user's path (issue 11 items 1, 9).

Every driver builds its FrameModel through ``fe.model_at_pose.pose_model`` and solves through
``analysis.modal.pose_modes`` / ``solve.lowest_elastic``; these tests hold them to it."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.analysis import mesh as mesh_rule
from flexlink.analysis import modal
from flexlink.analysis.modal import analyze
from flexlink.analysis.solve import MECHANISM
from flexlink.analysis.sweep import modal_sweep
from flexlink.cli import main
from flexlink.errors import InputError, NumericalError
from flexlink.scene import load_scene

from conftest import ROOT
CASE1 = ROOT / "cases" / "case1.toml"
WIPER = ROOT / "scenes" / "wiper.toml"


def test_stiff_springs_give_the_same_frequencies_on_every_path():
    # Kt = 1e16 N/m is far past rigid.RIGID_RATIO x the stiffest element: every path must make
    # it an exact constraint. As a penalty the sweep was off by 3e-8 (full) and 4e-6
    # (Craig-Bampton) at 16 elements/link.
    scene = load_scene(CASE1, overrides={"joints.Kt": "1e16 N/m"})
    case = analyze(scene, 4, 16)
    f = case.elastic_frequencies(4)
    topology, points = scene.topology(16), case.pose.joints  # the same crank angle
    full = modal_sweep(topology, [points], 4).frequencies[0]
    cb = modal_sweep(topology, [points], 4, reduction="craig-bampton").frequencies[0]
    # full: the sweep's unrefined dense eigenvalues against analyze's energy-refined ones
    # differ by K's round-off, eps lambda_max / lambda_1: measured 8e-13 with edgewise strips,
    # 4e-11 with the flatwise default (a wider stiffness spread)
    np.testing.assert_allclose(full, f, rtol=2e-10)
    # Craig-Bampton: truncated fixed-interface basis with its static correction, measured 3e-10
    np.testing.assert_allclose(cb, f, rtol=1e-8)


def test_stiff_springs_are_exact_in_the_out_of_plane_family_too():
    from flexlink.analysis.outofplane import analyze_out_of_plane

    rigid = analyze_out_of_plane(load_scene(CASE1, overrides={"joints.Kt": "rigid"}), 4, 16)
    stiff = analyze_out_of_plane(load_scene(CASE1, overrides={"joints.Kt": "1e16 N/m"}), 4, 16)
    # the same exact constraint on both: equal up to the solver's round-off (as a penalty,
    # 1e16 N/m put mode 1 below the round-off floor and the solve was refused)
    np.testing.assert_allclose(stiff.elastic_frequencies[:4], rigid.elastic_frequencies[:4],
                               rtol=1e-12)


def kt_zero(tmp_path):
    path = tmp_path / "kt0.toml"
    # edgewise strips: with the flatwise default and 2 elements/link the dense solve's highest
    # mode (26) has a backward error of 1.8e-9, over solve.py's 1e-10 limit (a NumericalError,
    # reported, not this test's subject: the refusal of too many modes)
    path.write_text(f'base = "{CASE1}"\n[joints]\nKt = "0 N/m"\n[section]\nbending = "edgewise"\n')
    return path


def test_free_bearings_return_every_elastic_mode_asked_for(tmp_path):
    # Kt = 0: the three links fly apart, 8 rigid-body modes (crank 2, coupler 3, rocker 3)
    # below the elastic ones; more than solve.SPARE_MODES, so the request must widen
    result = analyze(load_scene(kt_zero(tmp_path)), 6, 16)
    assert result.modes.kinds.count(MECHANISM) == 8
    assert len(result.elastic_frequencies(6)) == 6
    assert all(k == MECHANISM for k in result.modes.kinds[:8])


@pytest.mark.parametrize("command", [["modes"], ["modes", "-e", "16", "-n", "6"],
                                     ["export", "--no-pictures", "-e", "8"]])
def test_free_bearings_on_the_command_line(tmp_path, command):
    result = CliRunner().invoke(main, [command[0], str(kt_zero(tmp_path)), *command[1:],
                                       "--json", "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    n = 6 if "-n" in command else 4
    freqs = (doc["cases"][0]["frequencies_Hz"] if command[0] == "export"
             else [m["computed_Hz"] for m in doc["cases"][0]["modes"]])
    assert len(freqs) == n and all(f > 0 for f in freqs)


def test_too_many_modes_is_a_clear_error(tmp_path):
    with pytest.raises(InputError, match="only 18"):  # 2 elements/link: 26 DOFs, 8 zero modes
        analyze(load_scene(kt_zero(tmp_path)), 200, 2)
    result = CliRunner().invoke(main, ["modes", str(CASE1), "-e", "2", "-n", "200",
                                       "--out", str(tmp_path)])
    assert result.exit_code != 0 and "Traceback" not in result.output
    assert "200 elastic modes asked for" in result.output


def test_a_mesh_past_double_precision_is_refused_before_assembly(monkeypatch):
    def never(*args, **kwargs):
        raise AssertionError("assembled a model that was to be refused")

    monkeypatch.setattr(modal, "pose_model", never)
    monkeypatch.setattr(modal, "assemble", never)
    with pytest.raises(NumericalError, match="too fine for double precision"):
        analyze(load_scene(CASE1), 4, 100000)


def test_a_tolerance_out_of_reach_says_what_is_reachable():
    with pytest.raises(NumericalError, match="below what double precision reaches") as err:
        mesh_rule.mesh_for_tolerance(load_scene(CASE1), 4, 1e-15)
    assert "fewer elements" not in str(err.value)


def test_mesh_rule_order(monkeypatch):
    scene = load_scene(CASE1)
    assert mesh_rule.choose_mesh(scene, 4, elements=12).rule == mesh_rule.COMMAND_LINE
    pinned = load_scene(CASE1, overrides={"mesh.elements_per_link": 10})
    assert pinned.elements_per_link == 10 and scene.elements_per_link is None
    assert mesh_rule.choose_mesh(pinned, 4) == mesh_rule.MeshRule(10, mesh_rule.SCENE)
    rule = mesh_rule.choose_mesh(scene, 4, tol=1e-4)
    assert rule.rule == mesh_rule.TOLERANCE and rule.estimate <= 1e-4


def test_mesh_rule_on_a_general_scene():

    scene = load_scene(WIPER)
    rule = mesh_rule.mesh_for_tolerance(scene, 3, 1e-4)
    assert rule.estimate <= 1e-4
    assert all(est > 1e-4 for _, est in rule.history[:-1])


def test_export_and_cycle_record_the_mesh_they_used(tmp_path):
    runner = CliRunner()
    exported = runner.invoke(main, ["export", str(CASE1), "--no-pictures", "-n", "2", "--tol",
                                    "1e-4", "--json", "--out", str(tmp_path / "e")])
    assert exported.exit_code == 0, exported.output
    case = json.loads(exported.output)["cases"][0]
    modes = runner.invoke(main, ["modes", str(CASE1), "-n", "2", "--tol", "1e-4", "--json",
                                 "--out", str(tmp_path / "m")])
    chosen = json.loads(modes.output)["cases"][0]["mesh"]
    assert case["mesh"]["rule"] == chosen["rule"] == "tolerance"
    assert case["mesh"]["elements_per_link"] == chosen["elements_per_link"]
    # ARPACK's random start vector moves the refined frequencies by ~1e-15, the estimate by 1e-12
    assert case["mesh"]["estimated_relative_error"] == pytest.approx(
        chosen["estimated_relative_error"], rel=1e-9)
    cycle = runner.invoke(main, ["cycle", str(WIPER), "--poses", "6", "-n", "2", "-e", "6",
                                 "--out", str(tmp_path / "c")])
    assert cycle.exit_code == 0, cycle.output
    assert "mesh: 6 elements/link from the command line (-e)" in cycle.output


def test_too_many_modes_is_said_even_where_the_top_modes_fail_their_checks(tmp_path):
    """Flatwise strips with free bearings at 2 elements/link: asking for every mode makes the
    highest ones fail the backward-error check through the spectral shift; a request beyond
    the model's 18 elastic modes (26 DOFs less 8 mechanism modes) must say so, not report
    round-off."""
    scene = tmp_path / "soft.toml"
    scene.write_text(f'base = "{(ROOT / "cases" / "_table2.toml").as_posix()}"\n'
                     "[linkage]\nR2 = 0.267\nR3 = 0.800\nR4 = 0.667\n"
                     '[joints]\nKt = "0 N/m"\n')
    result = CliRunner().invoke(main, ["modes", str(scene), "-e", "2", "-n", "19", "--out",
                                       str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "19 elastic modes asked for, but the model has only 18 (26 DOFs, 8 of them" \
        in result.stderr, result.stderr


def test_a_pose_system_times_its_assembly_and_its_solve():
    # the convergence study reads these two timings by name
    scene = load_scene(CASE1)
    system = modal.pose_system(scene.topology(4), scene.rigid_pose().joints, 2)
    assert set(system.seconds) == {"assembly", "solve"}
    assert all(seconds >= 0 for seconds in system.seconds.values())
