"""A scene at its operating speed where no part can be made: the record keeps the declared
speed and acceleration and says why each part is missing (the report prints them)."""

import math

import pytest
from conftest import SCENES_DIR

from flexlink.errors import NumericalError
from flexlink.scene import load_scene
from flexlink.studies import report_scene


def test_parts_that_fail_keep_the_speed_and_their_reasons(monkeypatch):
    def failing(part):
        def fail(*args, **kwargs):
            raise NumericalError(f"{part} failed")
        return fail

    for part in ("torque_study", "forced_model", "operating_modes"):
        monkeypatch.setattr(report_scene, part, failing(part))
    scene = load_scene(SCENES_DIR / "rotor.toml")
    at = report_scene.at_speed(scene, 2, 4)
    # rotor.toml: crank_speed = "500 rev/min", no acceleration given (0)
    assert at.speed == pytest.approx(500 * 2 * math.pi / 60, rel=1e-15)
    assert at.crank_acceleration == 0.0 and at.points == ()
    assert (at.torque, at.forced, at.response) == (None, None, None)
    assert (at.torque_unavailable, at.response_unavailable, at.points_unavailable) == (
        "torque_study failed", "forced_model failed", "operating_modes failed")
