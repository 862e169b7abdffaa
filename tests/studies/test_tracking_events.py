"""Crossings are sign changes of the difference of two tracked lines: two lines that start
at exactly the same frequency (a double mode at the first pose) and part have not crossed.
A map whose shapes drift too far over the turn to pair with their start says so, and why."""

import math

import numpy as np
import pytest

from flexlink.studies.cycle.tracking import PAIR_MAC, periodicity, track


def test_lines_equal_at_the_first_pose_cross_only_where_their_order_changes():
    swapped = np.eye(2)[:, ::-1]
    # line 1 keeps shape e1 at 10 Hz; line 2 (shape e2) starts on it, rises, then falls below
    frequencies = np.array([[10.0, 10.0], [10.0, 11.0], [10.0, 12.0], [9.0, 10.0]])
    shapes = [np.eye(2)] * 3 + [swapped]
    tracks = track(frequencies, shapes, 2)
    assert tracks.frequencies[:, 1].tolist() == [10.0, 11.0, 12.0, 9.0]
    assert [(e.kind, e.lines, e.pose) for e in tracks.events] == [("crossing", (1, 2), 3)]


def test_a_shape_drifting_over_the_turn_says_the_map_does_not_close_and_why():
    # line 1's shape turns 5 deg per pose out into a third coordinate, 60 deg in all: each
    # step pairs (MAC cos^2 5 deg), the last pose with the first only at cos^2 60 deg = 0.25
    turns = np.radians(np.arange(0.0, 61.0, 5.0))
    shapes = [np.array([[math.cos(t), 0.0], [0.0, 1.0], [math.sin(t), 0.0]]) for t in turns]
    closing = periodicity(track(np.tile([10.0, 20.0], (len(turns), 1)), shapes, 2))
    assert not closing.closes and closing.permutation == (0, 1)
    assert closing.mac[0] == pytest.approx(0.25, abs=1e-12) and closing.mac[0] < PAIR_MAC
    assert closing.note == ("the tracked map does not close after one turn: line 1's shape at "
                            "the last pose pairs with its start shape with MAC 0.25 only (too "
                            "few poses for the shapes' changes?)")
