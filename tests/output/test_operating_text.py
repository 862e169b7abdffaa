"""`flexlink modes --speed`'s text of several scenes is each scene's table in order, each followed
by one empty line: nothing between or around them."""

from conftest import CASES_DIR

from flexlink.output.running.modes_at_speed import (format_operating, operating_summary,
                                              operating_text)
from flexlink.studies.running.modes_at_speed import OperatingRequest, scene_operating_modes
from flexlink.units import RPM


def test_text_of_two_scenes_is_their_tables_in_order():
    at = OperatingRequest(speed=600 * RPM)
    ops = [scene_operating_modes(CASES_DIR / f"case{i}.toml", 2, 2, at=at) for i in (1, 2)]
    tables = [format_operating(operating_summary(op)) for op in ops]
    assert tables[0] != tables[1]
    assert operating_text(ops) == tables[0] + "\n\n" + tables[1] + "\n\n"
