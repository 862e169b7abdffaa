"""`flexlink modes --json`: the pose it reports is the scene's linkage closed at the analysed
transmission angle, and its assumptions are the scene's, value and note as written.

Case 1: ground 300 mm and R2, R3, R4 = 0.267, 0.800, 0.667 of it, analysed at mu = 90 deg."""

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.cli import main
from flexlink.scene import load_scene

CASE1 = CASES_DIR / "case1.toml"


def test_pose_closes_the_linkage_and_assumptions_are_the_scenes(tmp_path):
    result = CliRunner().invoke(main, ["modes", str(CASE1), "-e", "2", "-n", "2", "--json",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    [case] = json.loads(result.output)["cases"]
    pose = case["pose"]
    o2, a, b, o4 = (np.array(pose["joints_m"][k]) for k in ("O2", "A", "B", "O4"))
    ground = 0.3
    # each link keeps its length (to round-off of the pose solve)
    lengths = [np.linalg.norm(o4 - o2), np.linalg.norm(a - o2), np.linalg.norm(b - a),
               np.linalg.norm(o4 - b)]
    assert lengths == pytest.approx([ground, 0.267 * ground, 0.8 * ground, 0.667 * ground],
                                    rel=1e-9)
    # mu: the angle at B between the coupler (B -> A) and the rocker (B -> O4)
    u, v = a - b, o4 - b
    mu = math.degrees(math.acos(u @ v / (np.linalg.norm(u) * np.linalg.norm(v))))
    assert pose["mu_deg"] == pytest.approx(90.0, abs=1e-9) and mu == pytest.approx(90.0, abs=1e-7)
    theta2 = math.degrees(math.atan2(*(a - o2)[::-1]))
    assert pose["theta2_deg"] == pytest.approx(theta2, abs=1e-9)
    scene = load_scene(CASE1)
    assert case["assumptions"] == [{"field": x.field, "value": x.value, "note": x.note}
                                   for x in scene.assumptions]
    assert case["assumptions"]  # case 1 assumes its ground length, among others
