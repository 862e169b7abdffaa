"""Assumed inputs over their written ranges: the scene files' ranges, the sampling rules, and
end points that move the frequencies the way the physics says."""


import numpy as np
import pytest

from flexlink.errors import InputError
from flexlink.scene import load_scene
from flexlink.studies.calibration.sensitivity import Span, draws, end_points, interval, spans

from conftest import CASES_DIR as CASES
CASE2 = CASES / "case2.toml"
ELEMENTS = 4  # direction checks only; the study itself runs at meshes.DEFAULT_ELEMENTS


def test_every_assumed_table2_input_has_a_range_and_a_reason():
    scene = load_scene(CASE2)
    # loss factors state their range in the note: they damp modes, frequencies do not use them
    unranged = [a.field for a in scene.assumptions if not a.range and a.field != "pose.branch"
                and not a.field.endswith("loss_factor")]
    assert unranged == []
    for a in scene.assumptions:
        if a.range:
            assert len(a.reason) > 20, a.field
    fields = {s.field for s in spans(CASE2)}
    assert {"linkage.ground", "section.width", "section.ply_thickness", "joints.Kt", "joints.Kr",
            "drive.stiffness", "joints.A.mass", "joints.B.mass", "section.bending"} <= fields


@pytest.mark.parametrize("noted, message", [
    ('{ value = "1 m", note = "assumed: x", range = ["1 m"], reason = "r" }', "range"),
    ('{ value = "1 m", note = "assumed: x", range = ["0.5 m", "2 m"] }', "reason"),
    ('{ value = "1 m", note = "given", range = ["0.5 m", "2 m"], reason = "r" }', "assumed"),
    ('{ value = "1 m", note = "assumed: x", spread = 2 }', "spread"),
])
def test_malformed_ranges_are_refused(tmp_path, noted, message):
    text = CASE2.read_text().replace('base = "_table2.toml"', f'base = "{CASES / "_table2.toml"}"')
    path = tmp_path / "s.toml"
    path.write_text(text.replace("[linkage]\n", f"[linkage]\nground = {noted}\n", 1))
    with pytest.raises(InputError, match=message):
        load_scene(path)


def test_sampling_rules():
    log = Span("joints.Kt", "1e6 N/m", "1e5 N/m", "1e8 N/m", "r")
    assert log.sample(0.0) == "100000.0 N/m"
    assert float(log.sample(0.5).split()[0]) == pytest.approx(10**6.5)  # log-uniform midpoint
    lin = Span("linkage.ground", "300 mm", "200 mm", "450 mm", "r")
    assert float(lin.sample(0.5).split()[0]) == pytest.approx(325.0)
    rigid = Span("drive.stiffness", "rigid", "100 N*m/rad", "rigid", "r")
    assert rigid.sample(0.0) == "rigid"
    assert float(rigid.sample(0.5).split()[0]) == pytest.approx(200.0)  # compliance midpoint
    assert Span("section.bending", "flatwise", "flatwise", "edgewise", "r").categorical
    with pytest.raises(InputError):
        Span("x", "1 m", "1 m", "2 mm", "r").sample(0.5)


def test_end_points_move_the_way_the_physics_says():
    p = end_points(CASE2, 4, ELEMENTS)
    ends = {s.field: e for s, e in zip(p.spans, p.ends)}
    low, high = 0, 1
    # longer links, all else equal: every frequency falls (f ~ 1/L^2 for the links' bending)
    assert np.all(ends["linkage.ground"][high] < p.nominal) and np.all(ends["linkage.ground"][low] > p.nominal)
    # flatwise, the ply thickness is the in-plane depth: f ~ t with rigid joints, so thicker is higher
    assert np.all(ends["section.ply_thickness"][high] > ends["section.ply_thickness"][low])
    # stiffer bearings, pins and drive can only raise frequencies (Rayleigh: K grows, M fixed)
    for field in ("joints.Kt", "joints.Kr", "drive.stiffness"):
        assert np.all(ends[field][high] >= ends[field][low] * (1 - 1e-12)), field
    # added pin mass can only lower them (M grows, K fixed)
    for field in ("joints.A.mass", "joints.B.mass"):
        assert np.all(ends[field][high] <= ends[field][low] * (1 + 1e-12)), field
    # the orientation: edgewise strips are ~ width / thickness times stiffer in bending
    assert ends["section.bending"][high][0] > 5 * ends["section.bending"][low][0]


def test_monte_carlo_is_reproducible_and_brackets_the_nominal():
    a, b = draws(CASE2, 5, seed=3), draws(CASE2, 5, seed=3)
    assert a == b and a != draws(CASE2, 5, seed=4)
    assert all("section.bending" not in d for d in a)  # categorical: not sampled
    assert all("material" in d and "joints.Kt" in d for d in a)
    iv = interval(CASE2, 30, seed=1, n_modes=2, elements=ELEMENTS)
    nominal = end_points(CASE2, 2, ELEMENTS).nominal
    assert iv.failed == 0
    assert np.all(iv.low < nominal) and np.all(nominal < iv.high)


@pytest.mark.parametrize("command", ["modes", "report"])
def test_scheduler_without_sensitivity_is_refused(tmp_path, command):
    """--scheduler only runs the --sensitivity evaluations: without them it is an error, not
    silently ignored (and no cluster is started for nothing)."""
    from click.testing import CliRunner

    from flexlink.cli import main

    result = CliRunner().invoke(main, [command, str(CASE2), "--scheduler", "local",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 2
    assert "--scheduler runs the --sensitivity evaluations" in result.output
