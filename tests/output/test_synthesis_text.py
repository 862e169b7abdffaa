"""The synthesis line above a synthesised scene's results reads as a person writes the inputs,
with their units, not as a Python dict."""

from flexlink.output.pose.synthesis_text import synthesis_line


def test_inputs_read_with_units():
    record = {"method": "extended-rocker",
              "inputs": {"swing_deg": 30.0, "coupler_ratio": 3.5, "k": 1.0, "tip_m": 0.1},
              "lengths_m": {"ground": 0.132424, "crank": 0.025882}}
    line = synthesis_line(record)
    assert line.startswith("synthesis extended-rocker (swing 30 deg, coupler ratio 3.5, k 1, "
                           "tip 100 mm): ground 132.424 mm, crank 25.882 mm")
    assert "{" not in line and "'" not in line
    assert synthesis_line(record, inputs=False).startswith("synthesis extended-rocker: ground")
