"""The sensitivity study's JSON document and its text table say the same thing as the study.

The study is built by hand (no model is solved), with Monte Carlo samples whose 2.5 % and
97.5 % quantiles follow by hand: 41 evenly spaced values v_0 ... v_40 have them at v_1 and
v_39 exactly (numpy's linear quantile puts q at index q (n - 1) = 1 and 39)."""

import numpy as np
import pytest

from flexlink.output.calibration.sensitivity import (alternative_document, alternative_line,
                                                format_sensitivity, sensitivity_document)
from flexlink.studies.pose.alternatives import Alternative
from flexlink.studies.calibration.sensitivity import EndPoints, Interval, SceneSensitivity, Span

SPANS = (Span("section.width", "20 mm", "19 mm", "21 mm", "printing tolerance"),
         Span("joints.Kr", "rigid", "50 N m/rad", "rigid", "pin friction unknown"))
ENDS = (np.array([[9.5, 38.0], [10.5, 42.0]]), np.array([[7.0, 35.0], [10.0, 40.0]]))
# column 1: 8.0, 8.1, ..., 12.0 -> 95 % interval 8.1 .. 11.9; column 2: 30 ... 70 -> 31 .. 69;
# one more draw failed (NaN in every mode), so 42 samples of which 1 failed
SAMPLES = np.vstack([np.c_[8.0 + 0.1 * np.arange(41), 30.0 + np.arange(41)],
                     [np.nan, np.nan]])
REFERENCE = {"Ex": (10.0, 75.0), "FE": (8.05, 40.0)}


@pytest.fixture(scope="module")
def study():
    return SceneSensitivity(EndPoints("x.toml", np.array([10.0, 40.0]), SPANS, ENDS),
                            Interval("x.toml", SAMPLES, 7), REFERENCE, 6)


def test_document_holds_the_study(study):
    doc = sensitivity_document(study)
    assert doc["elements_per_link"] == 6 and doc["nominal_Hz"] == [10.0, 40.0]
    for row, span, ends in zip(doc["inputs"], SPANS, ENDS, strict=True):
        assert {k: row[k] for k in ("field", "value", "low", "high", "reason")} == {
            "field": span.field, "value": span.value, "low": span.low, "high": span.high,
            "reason": span.reason}
        assert row["low_Hz"] == ends[0].tolist() and row["high_Hz"] == ends[1].tolist()
    mc = doc["monte_carlo"]
    assert (mc["samples"], mc["seed"], mc["failed"]) == (42, 7, 1)
    # 1e-12: the quantiles are grid values, off only by the rounding of 0.1 k
    assert mc["low_Hz"] == pytest.approx([8.1, 31.0], rel=1e-12)
    assert mc["high_Hz"] == pytest.approx([11.9, 69.0], rel=1e-12)
    # Ex: 10 Hz inside 8.1 .. 11.9, 75 Hz above 69; FE: 8.05 Hz below 8.1, 40 Hz inside
    assert mc["inside"] == {"Ex": [True, False], "FE": [False, True]}


def _numbers(line: str) -> list[float]:
    return [float(t) for t in line.split() if t.replace(".", "", 1).isdigit()]


def test_text_table_shows_every_number_of_the_document(study):
    doc = sensitivity_document(study)
    lines = format_sensitivity(doc).splitlines()
    assert "6 elements/link" in lines[0]
    assert lines[1].split() == ["input", "end", "f1", "Hz", "f2", "Hz"]
    nominal = next(line for line in lines if line.startswith("nominal"))
    assert _numbers(nominal) == doc["nominal_Hz"]
    for row in doc["inputs"]:
        at = next(i for i, line in enumerate(lines) if line.startswith(row["field"]))
        low, high = lines[at], lines[at + 1]
        assert row["low"] in low and row["high"] in high and not high.startswith(row["field"])
        assert _numbers(low)[-2:] == row["low_Hz"] and _numbers(high)[-2:] == row["high_Hz"]
    assert "42 samples, seed 7, 1 failed" in format_sensitivity(doc)
    intervals = next(line for line in lines if "-" in line and line.startswith(" "))
    assert intervals.split() == ["8.1-11.9", "31-69"]
    for name, flags in doc["monte_carlo"]["inside"].items():
        row = next(line for line in lines if line.startswith(f"{name} inside (*)"))
        assert row.split()[-2:] == ["*" if f else "-" for f in flags]


def test_alternative_document_and_line_agree():
    alt = Alternative("section.bending", "edgewise", np.array([12.5, 50.25]),
                      {"Ex": 3.25}, "flatwise")
    doc = alternative_document(alt)
    assert doc == {"field": "section.bending", "value": "edgewise",
                   "computed_Hz": [12.5, 50.25], "mean_abs_error_pct": {"Ex": 3.25},
                   "used": "flatwise"}
    line = alternative_line("orientation", alt)
    # the line's numbers are the document's: 4 significant digits, errors to 0.1 %
    assert line == ("orientation (used: flatwise): with section.bending = 'edgewise': "
                    "12.5, 50.25 Hz; mean |error| vs Ex 3.2 %")
    unused = Alternative("section.bending", "edgewise", np.array([12.5]), {}, None)
    assert "used" not in alternative_document(unused) and alternative_document(None) is None
