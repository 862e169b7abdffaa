"""The Campbell study shows its long work: the frozen-pose map walks its poses through the
``progress`` wrapper and the diagram at speed through ``progress_at_speed``, each pose once."""

import math

from conftest import CASES_DIR

from flexlink.scene import load_scene
from flexlink.studies.cycle.campbell import campbell_study

RPM = 2 * math.pi / 60


def test_both_stages_walk_their_poses_through_their_progress_wrappers():
    seen = {"map": 0, "speed": 0}

    def counting(stage):
        def wrap(items):
            for item in items:
                seen[stage] += 1
                yield item
        return wrap

    study = campbell_study(load_scene(CASES_DIR / "case1.toml"), (0.0, 1000 * RPM), 2, 6, 4, None,
                           0.1, 1, speed_steps=2, progress=counting("map"),
                           progress_at_speed=counting("speed"))
    assert study.at_speed is not None
    assert seen == {"map": 6, "speed": 6}
