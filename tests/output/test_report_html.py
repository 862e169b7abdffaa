"""The HTML report without a browser: its data are the solved shapes and tables (checked against
the model's own vectors and the modes command), the page carries every section it has data
for and only those, nothing in it points at the network, and it stays small. The browser test
(test_report_browser.py) looks at the page as a person does."""

import dataclasses
import json
import re
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.output.export_vtk import mode_set
from flexlink.output.html_report import render_page
from flexlink.analysis.mesh import COMMAND_LINE, MeshRule
from flexlink.output.pose.scene_summary import comparison_rows
from flexlink.output.report_data import mode_shapes, scene_page
from flexlink.scene import load_scene
from flexlink.studies.report_scene import ReportScene
from flexlink.studies.pose.scene_summary import summary_of

from conftest import ROOT
CASE1 = ROOT / "cases" / "case1.toml"
FAKE_JS = "/* plotly stand-in */"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def case1():
    return analyze(load_scene(CASE1), 3, 8)


class Tags(HTMLParser):
    """Every start tag with its attributes, and each script's text."""

    def __init__(self):
        super().__init__()
        self.tags, self.scripts, self._in_script = [], [], False

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        self._in_script = tag == "script"
        if self._in_script:
            self.scripts.append("")

    def handle_endtag(self, tag):
        self._in_script = False if tag == "script" else self._in_script

    def handle_data(self, data):
        if self._in_script:
            self.scripts[-1] += data


def parsed(page: str) -> Tags:
    tags = Tags()
    tags.feed(page)
    return tags


def test_mode_shapes_are_the_solved_vectors_normalised(case1):
    modes = mode_set(case1, 3, subdivisions=2)
    shapes = mode_shapes(modes)
    model = case1.model
    n_links = len(model.links)
    assert shapes["x"].count(None) == n_links - 1  # one break between consecutive links
    assert len(shapes["x"]) == len(modes.sampled.points) + n_links - 1
    vectors = case1.modes.shapes[:, case1.modes.elastic[:3]]
    for i, mode in enumerate(shapes["modes"]):
        d = np.array([[a, b] for a, b in zip(mode["dx"], mode["dy"]) if a is not None])
        # normalised: the largest sampled displacement is 1 (5 significant digits kept)
        assert np.linalg.norm(d, axis=1).max() == pytest.approx(1.0, abs=2e-5)
        # at a link's first and last node the page shows that node's (ux, uy) of the solved
        # vector, up to the one normalising factor of the mode
        first = model.links[0].nodes[0]
        last = model.links[-1].nodes[-1]
        solved = np.array([vectors[3 * first:3 * first + 2, i], vectors[3 * last:3 * last + 2, i]])
        shown = np.array([d[0], d[-1]])
        # the normalising factor: the largest displacement sampled along the elements
        peak = np.linalg.norm(modes.sampled.displacement[:, :, i], axis=1).max()
        assert np.allclose(shown, solved / peak, atol=5e-5)
        assert mode["frequency_Hz"] == pytest.approx(case1.elastic_frequencies(3)[i], rel=1e-12)


def _summary(result, n_modes):
    return summary_of(result, n_modes, MeshRule(result.elements_per_link, COMMAND_LINE))


def _page(result, cycle=None, reason=None, out=Path("/out")):
    summary = dataclasses.replace(_summary(result, 3), warnings=("a warning <b>",))
    files = {"vtu": [str(out / "case1" / "case1.vtu")], "pvd": [str(out / "case1" / "case1_mode1.pvd")]}
    return scene_page(ReportScene(summary, cycle, reason), files, out)


def test_page_has_each_section_it_has_data_for_and_escapes_text(case1):
    page = render_page([_page(case1)], FAKE_JS)
    for heading in ("Pose", "Natural frequencies", "Assumptions", "Mesh", "Mode shapes",
                    "Files for ParaView"):
        assert f"<h3>{heading}</h3>" in page
    assert "<h3>Cycle map</h3>" not in page  # no map asked for: no section
    assert "a warning &lt;b&gt;" in page and "a warning <b>" not in page
    # the table: every reference column with its error, the computed values as the modes command
    rows = comparison_rows(_summary(case1, 3))
    for row in rows:
        assert f"{row['computed_Hz']:,.2f}" in page
        assert f"{row['error_vs_Ex_pct']:+.1f} %" in page and f"{row['error_vs_FE_pct']:+.1f} %" in page
    links = [a["href"] for tag, a in parsed(page).tags if tag == "a" and not a["href"].startswith("#")]
    assert links == ["case1/case1.vtu", "case1/case1_mode1.pvd"]  # relative: the folder travels


def test_cycle_section_shows_the_map_or_why_there_is_none(case1):
    from flexlink.studies.cycle.modal_map import modal_map

    cycle = modal_map(case1.scene, 12, 3, 8)
    page = render_page([_page(case1, cycle)], FAKE_JS)
    data = json.loads(re.search(r'id="flexlink-data">(.*?)</script>', page, re.S).group(1))
    [figure] = [f for f in data["figures"] if f["id"].endswith("-cycle")]
    assert len(figure["data"]) == 3 and len(figure["data"][0]["x"]) == 12
    assert figure["data"][0]["x"] == sorted(figure["data"][0]["x"])  # one sweep, left to right
    assert np.allclose([t["y"] for t in figure["data"]],
                       cycle.frequencies[np.argsort(np.degrees(cycle.q) % 360)].T, rtol=1e-4)
    missing = render_page([_page(case1, reason="the crank cannot turn")], FAKE_JS)
    assert "Not available: the crank cannot turn" in missing


def test_page_is_self_contained(case1):
    # a bundle that holds the text "</script>" in a string must not end its script early
    page = render_page([_page(case1)], FAKE_JS + 'var end = "</script>";')
    tags = parsed(page)
    for tag, attrs in tags.tags:
        assert "src" not in attrs, tag  # every script and picture inline
        if tag == "link":
            pytest.fail(f"external resource {attrs}")
        href = attrs.get("href", "")
        assert not re.match(r"[a-z]+://", href), href
    # three scripts: the data, plotly, flexlink's player; the data parse back whole
    assert len(tags.scripts) == 3
    data = json.loads(tags.scripts[0])
    assert 'var end = "<\\/script>";' in tags.scripts[1]  # the same string in JavaScript
    assert list(data["animations"]) == ["case1"]


def test_report_command_writes_the_page_and_the_files_it_links(tmp_path):
    result = run("report", CASE1, ROOT / "cases" / "case2.toml", "-e", "8", "-n", "3",
                 "--cycle-poses", "12", "--json", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    page = (tmp_path / "report.html").read_text()
    assert document["report"] == str(tmp_path / "report.html")
    assert document["bytes"] == len(page.encode())
    hrefs = [a["href"] for tag, a in parsed(page).tags
             if tag == "a" and not a["href"].startswith("#")]
    assert len(hrefs) == 2 * (1 + 3)  # per scene one .vtu and a .pvd per mode
    for href in hrefs:
        assert (tmp_path / href).is_file(), href
    modes = json.loads(run("modes", CASE1, "-e", "8", "-n", "3", "--json",
                           "--out", tmp_path / "m").stdout)
    assert document["scenes"][0]["frequencies_Hz"] == [r["computed_Hz"] for r in modes["cases"][0]["modes"]]
    assert all(s["cycle_map"] for s in document["scenes"])


@pytest.mark.slow
def test_scene_data_leave_room_for_four_cases_under_15_MB(tmp_path):
    """The page is plotly's bundle once plus each scene's data; at the mesh the shipped cases
    get (64 elements/link, the tolerance rule's answer for case 1) and the default cycle map,
    four scenes of case 1's size must fit in 15 MB (the main job measures the real page)."""
    import plotly.offline

    result = run("report", CASE1, "-e", "64", "--json", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    bundle = len(plotly.offline.get_plotlyjs().encode())
    per_scene = json.loads(result.stdout)["bytes"] - bundle
    assert bundle + 4 * per_scene < 15e6, (bundle, per_scene)


def test_scene_without_reference_or_assumptions_shows_no_such_columns_or_section():
    result = analyze(load_scene(ROOT / "scenes" / "wiper.toml"), 2, 4)
    assert result.scene.reference is None
    result = dataclasses.replace(result, scene=dataclasses.replace(result.scene, assumptions=()))
    summary = dataclasses.replace(_summary(result, 2), warnings=())
    page = render_page([scene_page(ReportScene(summary, None), {}, Path("/o"))], FAKE_JS)
    assert "<h3>Natural frequencies</h3>" in page and "<th>error</th>" not in page
    assert "<h3>Assumptions</h3>" not in page and "<h3>Files for ParaView</h3>" not in page
    data = json.loads(parsed(page).scripts[0])
    assert len(data["animations"]["wiper"]["modes"]) == 2


def test_a_failing_scene_is_listed_and_the_others_reported(tmp_path):
    folder = tmp_path / "scenes"
    folder.mkdir()
    for name in ("_table2.toml", "case1.toml"):
        (folder / name).write_text((ROOT / "cases" / name).read_text())
    bad = folder / "case9.toml"
    bad.write_text('base = "_table2.toml"\n[linkage]\nR2 = 0.267\nR3 = 0.800\nR4 = 0.667\n'
                   '[pose]\ntransmission_angle = "20 deg"\n')
    result = run("report", folder, "-e", "4", "-n", "2", "--cycle-poses", "0", "--json",
                 "--out", tmp_path / "out")
    assert result.exit_code == 2
    document = json.loads(result.stdout)
    assert [s["file"] for s in document["scenes"]] == [str(folder / "case1.toml")]
    assert [f["file"] for f in document["failures"]] == [str(bad)]
    page = (tmp_path / "out" / "report.html").read_text()
    assert "Scenes not in this report" in page and str(bad) in page
    assert '<section class="scene" id="scene-case1">' in page
    assert str(bad) in result.stderr.splitlines()[0]


def test_sensitivity_section_shows_end_points_and_the_interval():
    from flexlink.output.html_report import sensitivity_section

    data = {"elements_per_link": 16, "nominal_Hz": [25.3, 45.4],
            "inputs": [{"field": "linkage.ground", "value": "300 mm", "low": "200 mm",
                        "high": "450 mm", "reason": "bench-top sizes", "low_Hz": [56.9, 102.0],
                        "high_Hz": [11.2, 20.2]}],
            "monte_carlo": {"samples": 20, "seed": 1, "failed": 0, "low_Hz": [10.0, 23.0],
                            "high_Hz": [48.0, 112.0], "inside": {"Ex": [True, False]}}}
    page = {"summary": {"sensitivity": data, "modes": [{"Ex_Hz": 27.0}, {"Ex_Hz": 171.0}]}}
    html = sensitivity_section(page, [])
    for text in ("linkage.ground", "200 mm", "56.90", "11.20", "10.0 - 48.0", "23.0 - 112.0",
                 "yes (27)", "no (171)", "bench-top sizes", "20 samples, seed 1"):
        assert text in html, text
    assert sensitivity_section({"summary": {"modes": []}}, []) == ""


def test_energy_shares_and_counts_read_as_text():
    from flexlink.output.counts import counted
    from flexlink.output.html_report import _shares

    # case 3 mode 2's strain energy, as the scene summary gives it (fractions summing to 1)
    cell = _shares({"crank": 0.8478, "coupler": 0.0918, "rocker": 0.0571, "O2": 0.0016,
                    "A": 0.0017})
    shown = re.sub(r"<[^>]+>", "", cell.split(">", 1)[1])
    assert shown == "crank 85 %, coupler 9 %"
    tooltip = re.search(r'title="([^"]*)"', cell)[1]
    assert tooltip == "crank 84.8 %, coupler 9.18 %, rocker 5.71 %, A 0.17 %, O2 0.16 %"
    assert "99.9 %" in _shares({"coupler": 0.99995, "crank": 0.00005})  # not all of it
    assert "0.36 %" in _shares({"coupler": 0.9964, "crank": 0.0036})
    assert [counted(n, "scene") for n in (0, 1, 2)] == ["0 scenes", "1 scene", "2 scenes"]
    assert counted(1, "elastic frequency", "elastic frequencies") == "1 elastic frequency"
