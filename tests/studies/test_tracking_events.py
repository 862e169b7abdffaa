"""Crossings are sign changes of the difference of two tracked lines: two lines that start
at exactly the same frequency (a double mode at the first pose) and part have not crossed."""

import numpy as np

from flexlink.studies.tracking import track


def test_lines_equal_at_the_first_pose_cross_only_where_their_order_changes():
    swapped = np.eye(2)[:, ::-1]
    # line 1 keeps shape e1 at 10 Hz; line 2 (shape e2) starts on it, rises, then falls below
    frequencies = np.array([[10.0, 10.0], [10.0, 11.0], [10.0, 12.0], [9.0, 10.0]])
    shapes = [np.eye(2)] * 3 + [swapped]
    tracks = track(frequencies, shapes, 2)
    assert tracks.frequencies[:, 1].tolist() == [10.0, 11.0, 12.0, 9.0]
    assert [(e.kind, e.lines, e.pose) for e in tracks.events] == [("crossing", (1, 2), 3)]
