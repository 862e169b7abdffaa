"""The steady response's files (CSV, PNG) and JSON document say the same thing as the result.

Results are built by hand (no model is solved); the renderer only needs the points, the basis
frequencies and the damping of the model, so a plain namespace stands in for it."""

import csv
import io
import math
import re
from types import SimpleNamespace

import numpy as np
import pytest

import flexlink.output.figures
from flexlink.output.running.steady_response import (response_lines, sweep_csv, sweep_document,
                                             write_response)
from flexlink.studies.running.steady_response import ResponseSweep, SteadyResponse, StrainPoint
from flexlink.units import RPM

POINTS = (StrainPoint("coupler", 0.06), StrainPoint("rocker", 0.1))
# half depths [m] of the two points' links: their peak deflections (3e-3 at most) stay within
# the small-deflection range
MODEL = SimpleNamespace(points=POINTS, half_depth=np.array([0.01, 0.02]), periodic=SimpleNamespace(
    damping_ratio=np.array([0.01, 0.02]), damping_source="declared",
    frequencies=np.array([20.0, 55.0]), load_vectors=0))
# one turn sampled from 30 deg, the angles as the integration leaves them (past 360 deg)
ANGLES = np.radians([390.0, 480.0, 570.0, 660.0])
STRAIN = np.array([[1e-4, -2e-5], [-3e-4, 4e-5], [2e-4, -6e-5], [0.0, 1e-5]])
DEFLECTION = np.array([[1e-4, 2e-3], [-1e-3, 1e-4], [5e-4, -3e-3], [0.0, 0.0]])


@pytest.fixture
def figures(monkeypatch):
    """The pyplot figures the renderer writes, kept for inspection (the file is still written)."""
    kept, write = [], flexlink.output.figures.write_figure

    def keep(fig, path, dpi=120):
        kept.append(fig)
        write(fig, path, dpi)
    monkeypatch.setattr(flexlink.output.figures, "write_figure", keep)
    return kept


def test_one_speed_csv_json_and_plot_hold_the_same_curves(tmp_path, figures):
    response = SteadyResponse(1200 * RPM, ANGLES, DEFLECTION, STRAIN, 0.75)
    document, paths = write_response(response, MODEL, tmp_path, "case1")
    assert [p.name for p in paths] == ["response.png", "response.csv"]
    assert all(p.parent == tmp_path and p.stat().st_size > 0 for p in paths)
    rows = list(csv.reader(io.StringIO(paths[1].read_text())))
    assert rows[0] == ["crank_deg", "coupler@60mm strain", "coupler@60mm deflection_m",
                       "rocker@100mm strain", "rocker@100mm deflection_m"]
    table = np.array(rows[1:], dtype=float)
    assert table[:, 0] == pytest.approx([30.0, 120.0, 210.0, 300.0], abs=1e-9)
    assert document["crank_deg"] == pytest.approx(table[:, 0], abs=1e-9)
    for k, point in enumerate(document["points"]):
        # 1e-9: the CSV keeps 10 significant digits
        assert table[:, 1 + 2 * k] == pytest.approx(STRAIN[:, k], rel=1e-9, abs=1e-30)
        assert table[:, 2 + 2 * k] == pytest.approx(DEFLECTION[:, k], rel=1e-9, abs=1e-30)
        assert point["strain"] == STRAIN[:, k].tolist()
        assert point["deflection_m"] == DEFLECTION[:, k].tolist()
        assert (point["label"], point["link"], point["position_m"]) == (
            POINTS[k].label, POINTS[k].link, POINTS[k].position)
    coupler, rocker = document["points"]
    # peaks by hand: |-3e-4| at 120 deg, |-6e-5| at 210 deg; deflections 1e-3 and 3e-3 m
    assert (coupler["peak_strain"], coupler["peak_strain_at_deg"]) == (3e-4, pytest.approx(120))
    assert (rocker["peak_strain"], rocker["peak_strain_at_deg"]) == (6e-5, pytest.approx(210))
    assert (coupler["peak_deflection_m"], rocker["peak_deflection_m"]) == (1e-3, 3e-3)
    assert document["speed_rev_per_min"] == pytest.approx(1200, rel=1e-12)
    lines = response_lines(document)
    assert "damping ratio 0.01 to 0.02 over the basis vectors (declared)" in lines
    assert any(line.split() == ["coupler@60mm", "300", "120.0", "1"] for line in lines)

    [fig] = figures
    top, bottom = fig.axes
    assert top.get_shared_x_axes().joined(top, bottom)
    assert (top.get_ylabel(), bottom.get_ylabel(), bottom.get_xlabel()) == (
        "bending strain [1e-6]", "deflection [mm]", "crank angle [deg]")
    for k, (strain_line, deflection_line) in enumerate(zip(top.lines, bottom.lines)):
        assert strain_line.get_xdata() == pytest.approx([30, 120, 210, 300])
        assert strain_line.get_ydata() == pytest.approx(STRAIN[:, k] * 1e6)
        assert deflection_line.get_ydata() == pytest.approx(DEFLECTION[:, k] * 1e3)


def test_sweep_marks_unstable_speeds_and_draws_every_campbell_line_in_range(tmp_path, figures):
    speeds = np.array([0.0, 1000.0, 2000.0, 3000.0]) * RPM
    peak = np.array([[1e-5, 2e-6], [np.nan, np.nan], [3e-5, 1e-6], [2e-5, 5e-6]])
    sweep = ResponseSweep(speeds, POINTS, peak, 10 * peak, np.array([np.nan, 1.2, 0.9, 0.95]))
    document, paths = write_response(sweep, MODEL, tmp_path, "case1")
    assert document == sweep_document("case1", sweep, MODEL)
    assert document["unstable_speeds_rev_per_min"] == pytest.approx([1000.0])
    assert document["points"][0]["peak_strain"] == [1e-5, None, 3e-5, 2e-5]
    rows = list(csv.reader(io.StringIO(paths[1].read_text())))
    assert rows[0][:2] == ["speed_rev_per_min", "largest_modulus"]
    assert rows[2] == ["1000", "1.2", "", "", "", ""]  # unstable: empty, not 0 or nan
    assert paths[1].read_text() == sweep_csv(sweep)
    assert any("largest peak strain 30 microstrain at 2000 rev/min" in line
               for line in response_lines(document))

    [fig] = figures
    [ax] = fig.axes
    # k Omega = f: Omega = 60 f / k rev/min for f = 20, 55 Hz and k = 1 ... 4, kept inside
    # 0 ... 3000 rev/min (55 Hz at k = 1 is 3300 rev/min, outside)
    expected = sorted(60.0 * f / k for f in (20.0, 55.0) for k in range(1, 5)
                      if 60.0 * f / k <= 3000.0)
    dotted = sorted(line.get_xdata()[0] for line in ax.lines if line.get_linestyle() == ":")
    assert dotted == pytest.approx(expected)
    labels = {t.get_text(): t.get_position()[0] for t in ax.texts}
    assert labels == pytest.approx({f"f{i + 1}/{k}": 60.0 * f / k
                                    for i, f in enumerate((20.0, 55.0)) for k in range(1, 5)
                                    if 60.0 * f / k <= 3000.0})
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("crank speed [rev/min]",
                                                  "peak bending strain [1e-6]")
    assert math.isclose(ax.get_xlim()[1], 3000.0)


def test_report_page_shows_the_documents_curves_and_peaks_in_its_units():
    from flexlink.output.html_report import _steady_response_part
    from flexlink.output.running.steady_response import response_document

    # strains 10 x the others' (up to 3000 microstrain): the table's 3 decimals then show
    # a factor off by 1e-6
    document = response_document("case1", SteadyResponse(1200 * RPM, ANGLES, DEFLECTION,
                                                         10 * STRAIN, 0.75), MODEL)
    figures = []
    html = _steady_response_part({"id": "case1"}, figures, document)
    [figure] = figures
    for trace, k in zip(figure["data"], range(len(POINTS)), strict=True):
        assert trace["x"] == document["crank_deg"]
        assert trace["y"] == pytest.approx(10 * STRAIN[:, k] * 1e6)  # microstrain, as the axis says
    assert figure["layout"]["yaxis"]["title"]["text"] == "bending strain [1e-6]"
    rows = [re.findall(r"<td[^>]*>([^<]*)</td>", row) for row in html.split("<tr>")[2:]]
    # peak strain [1e-6], peak deflection [mm] and deflection over depth, by hand: 3000 and 600
    # microstrain, 1 and 3 mm, 1 mm / 20 mm and 3 mm / 40 mm
    assert [(r[0], *(float(x.replace(",", "")) for x in r[1:])) for r in rows] == [
        ("coupler@60mm", 3000.0, 1.0, 0.05), ("rocker@100mm", 600.0, 3.0, 0.075)]


def test_a_sweep_names_where_the_deflection_is_largest_and_where_it_first_passes():
    """The sweep's warning paired its largest deflection with the first speed past the limit
    ("41.3 times ... from 600 rev/min on"): it names both speeds now."""
    from flexlink.output.running.steady_response import deflection_warnings
    from flexlink.studies.running.steady_response import StrainPoint

    ratio = np.array([[0.2], [0.8], [41.3], [3.0]])  # (speeds, points)
    [line] = deflection_warnings((StrainPoint("coupler", 0.135),), ratio,
                                 speeds=[300.0, 600.0, 2800.0, 3000.0])
    assert "41.3 times the link's depth at 2800 rev/min" in line
    assert "from 600 rev/min on the sweep" in line
    assert deflection_warnings((StrainPoint("coupler", 0.135),), ratio[:1], speeds=[300.0]) == []
