"""A critical range's shift in the dynamic Campbell document: each edge moved by the difference
of its at-speed and frozen values, in rev/min and in % of the frozen value; an edge both take
from the ends of the speed range did not move (cut: null); no range on one side: no shift."""

import pytest

from flexlink.output.running.dynamic_campbell import shift_json
from flexlink.studies.running.dynamic_campbell import CriticalShift
from flexlink.units import RPM


def test_each_edge_moves_by_the_difference_of_its_two_values():
    ends = (0.0, 3000 * RPM)
    shift = CriticalShift(2, 3, (1000 * RPM, 3000 * RPM), (1100 * RPM, 3000 * RPM))
    doc = shift_json(shift, ends)
    assert (doc["mode"], doc["harmonic"]) == (2, 3)
    assert doc["frozen_rev_per_min"] == pytest.approx([1000, 3000])
    assert doc["at_speed_rev_per_min"] == pytest.approx([1100, 3000])
    # from: +100 rev/min = +10 % of 1000; to: both at the range's end, so cut
    assert doc["moved"]["from"] == pytest.approx({"rev_per_min": 100.0, "percent": 10.0})
    assert doc["moved"]["to"] is None
    lower = shift_json(CriticalShift(1, 1, (1000 * RPM, 1200 * RPM), (950 * RPM, 1140 * RPM)),
                       ends)["moved"]
    assert lower == {"from": pytest.approx({"rev_per_min": -50.0, "percent": -5.0}),
                     "to": pytest.approx({"rev_per_min": -60.0, "percent": -5.0})}
    assert shift_json(CriticalShift(1, 1, (1000 * RPM, 1200 * RPM), None), ends)["moved"] is None
