"""The tracked cycle map's picture marks each crossing (x) and veering (o) where it happens: at
the event's crank angle, midway between the two lines' frequencies there. A hand-built map
(a plain namespace: the picture reads only these fields)."""

from types import SimpleNamespace

import numpy as np
import pytest

import flexlink.output.cycle.tracking as tracking_report
from flexlink.studies.cycle.tracking import Event


def test_events_are_marked_between_their_lines_at_their_pose(tmp_path, monkeypatch):
    kept = []
    monkeypatch.setattr(tracking_report, "write_figure", lambda fig, path: kept.append(fig))
    q = np.radians(np.arange(0.0, 360.0, 30.0))
    f = np.c_[10.0 + np.arange(12), 20.0 - np.arange(12)]  # they cross near pose 5
    events = (Event("crossing", (1, 2), 5, 0.05), Event("veering", (1, 2), 8, 0.02))
    result = SimpleNamespace(q=q, frequencies=f, labels=("a", "b"), mu90={}, scene="x",
                             tracks=SimpleNamespace(events=events))
    tracking_report.plot_tracked(result, tmp_path / "cycle.png")
    [fig] = kept
    [ax] = fig.axes
    marks = {c.get_label(): np.asarray(c.get_offsets()) for c in ax.collections}
    assert sorted(marks) == ["crossing", "veering"]
    # pose 5 is at 150 deg, pose 8 at 240 deg; the two lines' mean is 15 Hz at every pose
    assert marks["crossing"] == pytest.approx(np.array([[150.0, 15.0]]), abs=1e-9)
    assert marks["veering"] == pytest.approx(np.array([[240.0, 15.0]]), abs=1e-9)
