"""`flexlink mac`'s text: each side's modes from the document, the MAC matrix (rows A, columns B)
and the pairs, as the document states them."""

import numpy as np

from flexlink.output.pose.mac_comparison import mac_text


def test_text_shows_both_sides_the_matrix_and_the_pairs():
    side = {"scene": "case 3", "elements_per_link": 8,
            "modes": [{"mode": 1, "Hz": 12.5, "label": "crank bending 1"},
                      {"mode": 2, "Hz": 40.25, "label": "coupler bending 1"}]}
    document = {"part": "in-plane", "a": {**side, "file": "a.toml"},
                "b": {**side, "file": "b.toml", "elements_per_link": 16},
                "pairs": [{"a": 1, "b": 1, "mac": 0.999, "difference_pct": -0.25},
                          {"a": 2, "b": 2, "mac": 0.98, "difference_pct": 1.5}]}
    lines = mac_text(document, np.array([[0.999, 0.01], [0.02, 0.98]])).splitlines()
    assert lines[0] == "in-plane modes"
    assert lines[1].startswith("A: case 3 (a.toml), 8 elements/link: 1) 12.50 Hz crank")
    assert lines[2].startswith("B: case 3 (b.toml), 16 elements/link: 1) 12.50 Hz crank")
    assert lines[3].split() == ["MAC", "B1", "B2"]
    assert [line.split() for line in lines[4:6]] == [["A1", "0.999", "0.010"],
                                                     ["A2", "0.020", "0.980"]]
    assert lines[6:] == ["pairs:", "  A1 - B1: MAC 0.999, frequency -0.25 %",
                         "  A2 - B2: MAC 0.980, frequency +1.50 %"]
