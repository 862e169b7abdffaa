"""The report's "At speed" section: present exactly for a scene that declares an operating
speed, with the torque curve, the frequencies from rest to that speed, the axial preload and
the steady response."""

import json
import math
import re

import pytest
from click.testing import CliRunner

from conftest import CASES_DIR
from flexlink.cli import main

# Every check here compares two paths through the code on the same mesh (the page's table and
# the speed figure, at_speed against torque_study and operating_modes), so the coarsest mesh
# serves: the steady response's basis is the most costly part and grows with it.
ELEMENTS = 2


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    folder = tmp_path_factory.mktemp("scenes")
    text = (CASES_DIR / "case3.toml").read_text()
    text = text.replace('base = "_table2.toml"',
                        f'base = "{(CASES_DIR / "_table2.toml").as_posix()}"')
    (folder / "case3_speed.toml").write_text(
        text + '\n[operation]\ncrank_speed = "600 rev/min"\n')
    out = tmp_path_factory.mktemp("report")
    result = CliRunner().invoke(main, ["report", str(folder / "case3_speed.toml"),
                                       str(CASES_DIR / "case1.toml"), "-e", str(ELEMENTS), "-n", "2",
                                       "--cycle-poses", "0", "--json", "--out", str(out)])
    assert result.exit_code == 0, result.output
    return (out / "report.html").read_text()


def _scene(html: str, stem: str) -> str:
    return re.search(rf'<section class="scene" id="scene-{stem}">(.*?)</section>', html,
                     re.S).group(1)


def test_section_appears_exactly_for_the_scene_with_a_speed(page):
    assert "<h3>At speed</h3>" in _scene(page, "case3_speed")
    assert "At speed" not in _scene(page, "case1")
    assert 'id="fig-case1-speed"' not in page and 'id="fig-case1-torque"' not in page
    for name in ("torque", "speed", "response"):
        assert f'id="fig-case3_speed-{name}"' in page
    assert "Axial preload at the operating speed" in _scene(page, "case3_speed")
    assert "<h4>Steady response</h4>" in _scene(page, "case3_speed")


def test_frequencies_at_rest_are_the_static_ones_of_the_page(page):
    data = json.loads(re.search(r'id="flexlink-data">(.*?)</script>', page, re.S).group(1)
                      .replace("<\\/", "</"))
    figure = next(f for f in data["figures"] if f["id"] == "fig-case3_speed-speed")
    at_rest = [trace["y"][0] for trace in figure["data"]]
    speeds = figure["data"][0]["x"]
    assert speeds[0] == 0 and speeds[-1] == pytest.approx(600)
    # the frequency table's computed column at the pose (printed to 2 decimals)
    table = _scene(page, "case3_speed")
    for f in at_rest:
        assert f"{f:,.2f}" in table
    # at 600 rev/min the first mode moves (preload and rotating terms are in)
    assert figure["data"][0]["y"][-1] != pytest.approx(at_rest[0], rel=1e-6)


def test_the_scene_crank_acceleration_reaches_torque_and_modes(tmp_path):
    # [operation] crank_acceleration is part of the operating point: the torque curve and the
    # modes at speed are those of `torque` and `modes --speed` with it, not at constant speed
    from flexlink.output.report_data import at_speed_data
    from flexlink.scene import load_scene
    from flexlink.studies.running.modes_at_speed import operating_modes
    from flexlink.studies.report_scene import at_speed
    from flexlink.studies.running.torque import torque_study

    text = (CASES_DIR / "case3.toml").read_text().replace(
        'base = "_table2.toml"', f'base = "{(CASES_DIR / "_table2.toml").as_posix()}"')
    path = tmp_path / "case3_speeding.toml"
    path.write_text(text + '\n[operation]\ncrank_speed = "600 rev/min"\n'
                           'crank_acceleration = "3000 rad/s^2"\n')
    scene = load_scene(path)
    data = at_speed_data(at_speed(scene, 2, ELEMENTS))
    speed = 600 * 2 * math.pi / 60
    assert data["crank_acceleration_rad_s2"] == pytest.approx(3000.0)
    curve = torque_study(scene, speed, 3000.0, poses=72)
    assert data["torque"]["summary"] == pytest.approx(curve.summary(), rel=1e-12)
    op = operating_modes(scene, speed, 2, ELEMENTS, crank_acceleration=3000.0)
    steady = operating_modes(scene, speed, 2, ELEMENTS)
    at_top = [line[-1] for line in data["modes"]["frequencies_Hz"]]
    assert at_top == pytest.approx(list(op.frequencies), rel=1e-12)
    assert at_top != pytest.approx(list(steady.frequencies), rel=1e-6)


def test_stress_and_life_for_the_scene_with_a_speed_and_strengths(page):
    """Case 3 with a speed declares strengths (the constituents'): its page has the "Stress
    and life" section, its three composite links with strength ratios and no life; case 1
    declares no speed and has none."""
    section = _scene(page, "case3_speed")
    assert "<h3>Stress and life</h3>" in section
    assert 'id="fig-case3_speed-life"' in page
    table = section[section.index("link (worst first)"):]
    assert table.count("none*") == 3
    assert "no life is given without a measured fatigue curve" in section
    assert "Stress and life" not in _scene(page, "case1")


def test_a_response_beyond_small_deflection_is_flagged_on_the_page():
    """A midspan deflecting more than SMALL_DEFLECTION times its link's depth is named in a
    warning above the strain plot, with its ratio in the table; one within it is not."""
    from types import SimpleNamespace

    import numpy as np

    from flexlink.output.html_report import _steady_response_part
    from flexlink.output.report_data import steady_response_data
    from flexlink.studies.running.steady_response import SMALL_DEFLECTION, StrainPoint

    points = (StrainPoint("coupler", 0.135), StrainPoint("rocker", 0.06))
    half_depth = np.array([0.75e-3, 2.0e-3])  # [m]
    peak = np.array([2.0 * half_depth[0] * 3.0, 2.0 * half_depth[1] * 0.1])  # 3 and 0.1 depths
    angles = np.radians([0.0, 120.0, 240.0])
    at = SimpleNamespace(
        forced=SimpleNamespace(points=points, half_depth=half_depth),
        response=SimpleNamespace(angles=angles, strain=np.ones((3, 2)) * 1e-4,
                                 peak_strain=np.array([1e-4, 1e-4]), peak_deflection=peak))
    data = steady_response_data(at)
    assert [p["small_deflection"] for p in data["points"]] == [False, True]
    assert data["points"][0]["deflection_to_depth"] == pytest.approx(3.0, rel=1e-12)
    assert data["small_deflection_limit"] == SMALL_DEFLECTION
    html = _steady_response_part({"id": "case3"}, [], data)
    coupler, rocker = (p["label"] for p in data["points"])
    assert "Beyond small deflection" in html
    assert f"{coupler}: peak deflection 3 times the link's depth" in html
    assert f"{rocker}: peak deflection" not in html
