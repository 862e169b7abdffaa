"""`flexlink modes --speed`'s text ends with what the reader must weigh: each warning of the
model on its own line marked "warning: ", then each assumed value marked "assumed: ", each
exactly as the JSON document states it."""

import dataclasses

from conftest import CASES_DIR

from flexlink.output.running.modes_at_speed import format_operating, operating_summary
from flexlink.studies.running.modes_at_speed import OperatingRequest, scene_operating_modes
from flexlink.units import RPM

WARNINGS = ("link coupler: slenderness 4.2 below 10, shear matters (a warning for the test)",
            "pose near a dead centre (a second warning)")


def test_each_warning_and_assumption_is_its_own_marked_line():
    op = scene_operating_modes(CASES_DIR / "case1.toml", 2, 2, at=OperatingRequest(speed=600 * RPM))
    summary = operating_summary(dataclasses.replace(op, warnings=WARNINGS))
    assert summary["warnings"] == list(WARNINGS)
    assert summary["assumptions"]  # case 1 assumes its ground length, among others
    lines = format_operating(summary).splitlines()
    tail = [f"warning: {w}" for w in WARNINGS] + [f"assumed: {a}" for a in summary["assumptions"]]
    assert lines[-len(tail):] == tail
