"""The report's per-scene study checks itself on construction: a cycle map or the reason there
is none, never both; a torque curve or its reason, exactly one; one operating point per
speed from rest to the operating speed, or the reason there are none."""

import numpy as np
import pytest

from flexlink.studies.report_scene import SPEED_STEPS, AtSpeed, ReportScene


def test_at_speed_refuses_a_wrong_speed_grid_or_missing_parts():
    speeds = np.linspace(0.0, 60.0, SPEED_STEPS)
    AtSpeed(60.0, 0.0, None, "no masses", speeds, (), "no pose")  # both parts explained: fine
    with pytest.raises(ValueError, match=r"AtSpeed\.speeds"):
        AtSpeed(60.0, 0.0, None, "no masses", speeds[:-1], (), "no pose")
    with pytest.raises(ValueError, match="torque curve or the reason"):
        AtSpeed(60.0, 0.0, None, None, speeds, (), "no pose")
    with pytest.raises(ValueError, match="operating points"):
        AtSpeed(60.0, 0.0, None, "no masses", speeds, ())


def test_report_scene_has_a_cycle_map_or_its_reason_not_both():
    with pytest.raises(ValueError, match="at most one"):
        ReportScene(summary=None, cycle=object(), cycle_unavailable="cannot turn")
