"""The HTML report's figures and frequency table as a reader gets them: every figure is a valid
Plotly figure (plotly.js drops a misspelt layout key or a colour it cannot read without a word,
so the page would lose that axis title, legend placement or height silently; Plotly's own
Python validator refuses them), every axis title carries its unit in brackets, and the
table's reference cells are the scene file's reference values.

One page of case 1 on 2 elements per link, with its cycle map over 6 poses and the scene at
300 rev/min (torque curve and the frequencies from rest; the steady response is left out, as
the page does for a scene it cannot give one)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.analysis.mesh import COMMAND_LINE, MeshRule
from flexlink.analysis.modal import analyze
from flexlink.output.html_report import render_page
from flexlink.output.report_data import scene_page
from flexlink.scene import load_scene
from flexlink.studies.cycle.modal_map import modal_map
from flexlink.studies.running.modes_at_speed import operating_modes
from flexlink.studies.report_scene import SPEED_STEPS, AtSpeed, ReportScene
from flexlink.studies.pose.scene_summary import summary_of
from flexlink.studies.running.torque import torque_study

CASE1 = CASES_DIR / "case1.toml"
ELEMENTS, MODES = 2, 3
SPEED = 300 * 2 * math.pi / 60  # [rad/s]


@pytest.fixture(scope="module")
def page():
    scene = load_scene(CASE1)
    result = analyze(scene, MODES, ELEMENTS)
    summary = summary_of(result, MODES, MeshRule(ELEMENTS, COMMAND_LINE))
    speeds = np.linspace(0.0, SPEED, SPEED_STEPS)
    at = AtSpeed(speed=SPEED, crank_acceleration=0.0,
                 torque=torque_study(scene, SPEED, poses=24), torque_unavailable=None,
                 speeds=speeds,
                 points=tuple(operating_modes(scene, w, MODES, ELEMENTS) for w in speeds),
                 response_unavailable="left out of this test")
    report_scene = ReportScene(summary, modal_map(scene, 6, MODES, ELEMENTS), None, at)
    out = Path("/out")
    files = {"vtu": [str(out / "case1" / "case1.vtu")], "pvd": []}
    return render_page([scene_page(report_scene, files, out)], "/* plotly stand-in */")


def _figures(html: str) -> list[dict]:
    data = re.search(r'id="flexlink-data">(.*?)</script>', html, re.S).group(1)
    return json.loads(data.replace("<\\/", "</"))["figures"]


def test_every_figure_is_a_valid_plotly_figure_with_units_on_its_axes(page):
    from plotly import graph_objects

    figures = {f["id"].rsplit("-", 1)[1]: f for f in _figures(page)}
    assert {"pose", "cycle", "torque", "speed"} <= set(figures)
    for name, figure in figures.items():
        # raises ValueError naming the first key or value Plotly does not know
        graph_objects.Figure(data=figure["data"], layout=figure["layout"])
        for axis in ("xaxis", "yaxis"):
            title = figure["layout"][axis]["title"]["text"]
            assert re.search(r"\[[^\]]+\]$", title), (name, axis, title)
    # the quantities each figure plots, as its caption says
    assert figures["cycle"]["layout"]["xaxis"]["title"]["text"] == "crank angle [deg]"
    assert figures["cycle"]["layout"]["yaxis"]["title"]["text"] == "natural frequency [Hz]"
    assert figures["torque"]["layout"]["yaxis"]["title"]["text"] == "driving torque [N m]"
    assert figures["speed"]["layout"]["xaxis"]["title"]["text"] == "crank speed [rev/min]"


def _rows(table_html: str) -> list[list[str]]:
    return [re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", row)
            for row in re.findall(r"<tr>(.*?)</tr>", table_html)]


def test_frequency_table_reference_cells_are_the_scene_files_values(page):
    section = page.split("<h3>Natural frequencies</h3>", 1)[1].split("</table>", 1)[0]
    header, *body = _rows(section)
    reference = load_scene(CASE1).reference.columns
    assert len(body) == MODES
    for name, values in reference.items():
        column = header.index(f"{name} [Hz]")
        # the page shows a reference value to 0.1 Hz, as the file gives it
        assert [row[column] for row in body] == [f"{v:,.1f}" for v in values[:MODES]]
        assert header[column + 1] == "error"
