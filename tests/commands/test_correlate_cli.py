"""``flexlink correlate`` and ``flexlink export --uff`` from the command line: the shipped
synthetic example, bad test files refused in one line naming the file and the dataset or
field (exit 2, nothing already written lost), and UFF round trips through pyuff both ways."""

from __future__ import annotations

import json

import numpy as np
import pytest
import pyuff
from click.testing import CliRunner

from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.scene import load_scene
from flexlink.studies.correlation.measured import read_test

from conftest import ROOT

SCENE = ROOT / "scenes" / "tests" / "case3_timoshenko.toml"
EXAMPLE = ROOT / "scenes" / "tests" / "case3_synthetic.uff"
SIX_DIGITS = 5e-6  # UFF 55 and 15 keep six significant digits (E13.5): half a unit in the 6th


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def _uff(path, sets):
    pyuff.UFF(str(path)).write_sets(sets, mode="overwrite")
    return path


def _geometry(n=3):
    return pyuff.prepare_15(node_nums=list(range(1, n + 1)), def_cs=[0] * n, disp_cs=[0] * n,
                            color=[0] * n, x=[10.0 * i for i in range(n)], y=[0.0] * n,
                            z=[0.0] * n)


def _mm():
    return pyuff.prepare_164(units_code=3, units_description="mm", temp_mode=1, length=1000.0,
                             force=1.0, temp=1.0, temp_offset=273.15)


def _mode(k, values, freq=100.0, damping=0.01):
    values = np.asarray(values, dtype=float)
    return pyuff.prepare_55(model_type=1, analysis_type=2, data_ch=2, spec_data_type=8,
                            data_type=2, n_data_per_node=3, r1=values[:, 0], r2=values[:, 1],
                            r3=values[:, 2], load_case=1, mode_n=k, freq=freq, modal_m=0.0,
                            modal_damp_vis=damping, modal_damp_his=0.0,
                            node_nums=np.arange(1, len(values) + 1))


@pytest.fixture(scope="module")
def first_run(tmp_path_factory):
    """The shipped example correlated once: (out folder, its correlation.json text)."""
    out = tmp_path_factory.mktemp("out")
    result = run("correlate", SCENE, EXAMPLE, "--no-pictures", "--out", out)
    assert result.exit_code == 0, result.output
    return out, (out / "case3_timoshenko" / "correlation.json").read_text()


def test_the_shipped_synthetic_example_pairs_all_eight_modes(first_run):
    out, text = first_run
    document = json.loads(text)
    assert len(document["pairs"]) == 8 and document["unpaired_test"] == []
    swapped = {(p["test"], p["model"]) for p in document["pairs"]} & {(6, 7), (7, 6)}
    assert swapped == {(6, 7), (7, 6)}
    for name in ("correlation_pairs.csv", "correlation_mac.csv", "correlation_model.vtu",
                 "correlation_test.vtu"):
        assert (out / "case3_timoshenko" / name).is_file()


def _scene_beside(folder, **test_table):
    """A scene in ``folder`` named like the shipped one (so it writes into the same out
    folder) with the given [test] keys changed."""
    folder.mkdir()
    table = {"unit": '"mm"', "offset": '["50 mm", "-20 mm"]', "rotation": '"30 deg"',
             "max_distance": '"2 mm"', **test_table}
    path = folder / "case3_timoshenko.toml"
    path.write_text(f'base = "{SCENE.as_posix()}"\n[test]\n'
                    + "".join(f"{k} = {v}\n" for k, v in table.items()))
    return path


def _bad_files(tmp_path):
    """(scene, test file, what the one-line message must hold) for each kind of bad input."""
    good = EXAMPLE.read_bytes()
    cut = tmp_path / "truncated.uff"
    cut.write_bytes(good[:len(good) // 2])  # ends inside a dataset 55
    binary = tmp_path / "binary.uff"
    binary.write_bytes(b"    -1\n    55\n" + bytes(range(256)) + b"\n    -1\n")
    no55 = _uff(tmp_path / "no55.uff", [_mm(), _geometry()])
    zero = _uff(tmp_path / "zero.uff", [_mm(), _geometry(), _mode(1, [[0, 1, 0]] * 3),
                                        _mode(2, np.zeros((3, 3)))])
    csv = tmp_path / "bad.csv"
    csv.write_text("sensor,x [mm],y [mm],z [mm],dx,dy,dz,mode 1\nfrequency [Hz],,,,,,,10\n"
                   "a,0,0,0,0,1,0,abc\n")
    return [
        (SCENE, no55, r"no55.uff: dataset 55: no dataset 55 \(mode shapes\); datasets found: 164, 15"),
        (SCENE, zero, r"zero.uff: dataset 4 \(55\): the mode shape is zero at every channel"),
        (SCENE, cut, r"truncated.uff: dataset \d+: truncated"),
        (SCENE, binary, r"binary.uff: file: binary content"),
        (SCENE, csv, r"bad.csv: row 3, column 'mode 1': got 'abc'"),
        (_scene_beside(tmp_path / "metres", unit='"m"'), EXAMPLE,
         r"case3_synthetic.uff: dataset 1 \(164\) length: the file's length unit is 0.001 m but "
         r"the scene's \[test\] unit is 'm'"),
        (_scene_beside(tmp_path / "shifted", offset='["150 mm", "-20 mm"]'), EXAMPLE,
         r"case3_synthetic.uff: sensor 1: at .* mm from the nearest link"),
    ]


def test_bad_test_files_are_one_line_exit_2_and_nothing_written_is_lost(first_run, tmp_path):
    """Each bad input: exit 2, one line on stderr naming the file and the dataset, row or
    sensor, and the earlier correlation.json of the same scene untouched."""
    import re

    out, before = first_run
    for scene, test, message in _bad_files(tmp_path):
        result = run("correlate", scene, test, "--no-pictures", "--out", out)
        assert result.exit_code == 2, (test, result.output)
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and re.search(message, lines[0]), (message, result.stderr)
        assert (out / "case3_timoshenko" / "correlation.json").read_text() == before


def test_a_pyuff_written_file_reads_back_with_the_same_numbers(tmp_path):
    """Values written by pyuff itself (datasets 164, 2411, 55) come back from flexlink's
    reader: coordinates exact (2411 keeps 17 digits), shapes, frequencies and damping to six
    digits; the unmeasured Z direction makes no channel."""
    rng = np.random.default_rng(5)
    values = [np.column_stack([rng.normal(size=4), rng.normal(size=4), np.zeros(4)])
              for _ in range(3)]
    geometry = pyuff.prepare_2411(node_nums=[1, 2, 3, 4], def_cs=[0] * 4, disp_cs=[0] * 4,
                                  color=[0] * 4, x=[0.0, 1.5, 3.25, 7.0], y=[1.0, 2.0, 3.0, 4.0],
                                  z=[0.0] * 4)
    path = _uff(tmp_path / "pyuff.uff", [_mm(), geometry] + [
        _mode(k + 1, v, 50.0 * (k + 1) + 0.123, 0.01 * (k + 1)) for k, v in enumerate(values)])
    test = read_test(path)
    np.testing.assert_array_equal(test.coordinates[:, 0], [0.0, 1.5, 3.25, 7.0])
    assert test.metres_per_unit == pytest.approx(1e-3, rel=1e-15)
    assert len(test.channel_point) == 8  # 4 nodes x (X, Y)
    for k, v in enumerate(values):
        expected = v[test.channel_point, np.argmax(test.channel_direction, axis=1)]
        np.testing.assert_allclose(test.shapes[:, k], expected, rtol=0,
                                   atol=SIX_DIGITS * np.abs(v).max())
    np.testing.assert_allclose(test.frequencies, [50.123, 100.123, 150.123], rtol=SIX_DIGITS)
    np.testing.assert_allclose(test.damping, [0.01, 0.02, 0.03], rtol=SIX_DIGITS)


def test_flexlinks_uff_export_reads_back_in_pyuff_with_the_model_numbers(tmp_path):
    """``export --uff`` at every node, read by pyuff: one 55 per mode holding each node's
    (ux, uy, 0) of the model's mass-normalised shapes, and the nodes' coordinates, to six
    digits; the frequencies too."""
    result = run("export", SCENE, "--uff", "--no-pictures", "-n", "3", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    path = tmp_path / "case3_timoshenko" / "case3_timoshenko_modes.uff"
    sets = pyuff.UFF(str(path)).read_sets()
    assert [s["type"] for s in sets] == [164, 15, 55, 55, 55]
    case = analyze(load_scene(SCENE), 3, 16)
    chosen = case.modes.elastic[:3]
    nodal = case.modes.shapes[:, chosen].reshape(-1, 3, 3)
    np.testing.assert_allclose(sets[1]["x"], case.model.nodes[:, 0], rtol=0,
                               atol=SIX_DIGITS * np.abs(case.model.nodes).max())
    for k, dataset in enumerate(sets[2:]):
        scale = np.abs(nodal[:, :2, k]).max()
        np.testing.assert_allclose(dataset["r1"], nodal[:, 0, k], rtol=0, atol=SIX_DIGITS * scale)
        np.testing.assert_allclose(dataset["r2"], nodal[:, 1, k], rtol=0, atol=SIX_DIGITS * scale)
        assert not np.any(dataset["r3"])
        assert dataset["freq"] == pytest.approx(case.modes.frequencies[chosen[k]], rel=SIX_DIGITS)


def test_the_model_exported_at_the_tests_points_correlates_perfectly_with_itself(tmp_path):
    """``export --uff --uff-points`` writes the model's shapes at the synthetic test's
    points, in its frame and unit; correlated with the same scene, every mode pairs with
    itself at MAC 1 (to the six digits kept) and 0 % frequency error: placement, frames and
    units undo each other exactly."""
    result = run("export", SCENE, "--uff", "--uff-points", EXAMPLE, "--no-pictures", "-n", "6",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    exported = tmp_path / "case3_timoshenko" / "case3_timoshenko_modes.uff"
    again = run("correlate", SCENE, exported, "-n", "6", "--no-pictures", "--json",
                "--out", tmp_path / "again")
    assert again.exit_code == 0, again.output
    document = json.loads(again.stdout)
    assert [(p["test"], p["model"]) for p in document["pairs"]] == [(k, k) for k in range(1, 7)]
    assert min(p["mac"] for p in document["pairs"]) > 1 - 1e-8
    assert max(abs(p["error_pct"]) for p in document["pairs"]) < 1e-3


@pytest.mark.parametrize("layout", ["sensors.csv", "sensors.uff"])
def test_a_sensor_layout_reads_back_as_a_pre_test_of_the_same_model(tmp_path, layout):
    """``flexlink sensors`` writes its layout, in the scene's [test] frame, with the target
    modes the model predicts there (CSV: along each chosen direction; UFF: the whole
    displacement at each chosen point); ``flexlink correlate`` reads either file back and
    pairs every target mode with itself at MAC 1 (to the digits kept)."""
    result = run("sensors", SCENE, "--count", "8", "--modes", "5", "--no-pictures", "--json",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    planned = document["effective_independence"]
    assert len(planned["sensors"]) == 8 and planned["unseen_modes"] == []
    path = tmp_path / "case3_timoshenko" / layout
    again = run("correlate", SCENE, path, "-n", "5", "--no-pictures", "--json",
                "--out", tmp_path / "again")
    assert again.exit_code == 0, again.output
    pairs = json.loads(again.stdout)["pairs"]
    assert [(p["test"], p["model"]) for p in pairs] == [(k, k) for k in range(1, 6)]
    assert min(p["mac"] for p in pairs) > 1 - 1e-8


def test_the_report_gets_a_test_correlation_section(tmp_path):
    """``report --test`` adds the section: the MAC heat map's figure and one table row per
    pair (8 for the shipped example), the swapped pair among them; without --test the page
    has no such section."""
    import re

    result = run("report", SCENE, "--test", EXAMPLE, "--cycle-poses", "0", "-n", "2",
                 "--out", tmp_path / "with")
    assert result.exit_code == 0, result.output
    page = (tmp_path / "with" / "report.html").read_text()
    section = page[page.index("<h3>Test correlation</h3>"):]
    section = section[:section.index("</tbody>")]
    assert 'id="fig-case3_timoshenko-mac"' in section
    rows = re.findall(r"<tr><td class=\"num\">(\d+)</td><td class=\"num\">[^<]*</td>"
                      r"<td class=\"num\">(\d+)</td>", section)
    assert len(rows) == 8 and ("6", "7") in rows and ("7", "6") in rows
    plain = run("report", SCENE, "--cycle-poses", "0", "-n", "2", "--out", tmp_path / "without")
    assert plain.exit_code == 0, plain.output
    assert "Test correlation" not in (tmp_path / "without" / "report.html").read_text()


def test_calibrate_with_a_test_needs_free_inputs_and_one_scene(tmp_path):
    no_free = run("calibrate", SCENE, "--test", EXAMPLE, "--out", tmp_path)
    assert no_free.exit_code == 2 and "--free" in no_free.stderr
    two = run("calibrate", SCENE, ROOT / "cases" / "case3.toml", "--test", EXAMPLE,
              "--free", "Kt=1e5 N/m:1e8 N/m", "--out", tmp_path)
    assert two.exit_code == 2 and "a test belongs to one" in two.stderr


def test_a_3d_layout_reads_out_of_plane_modes_back_through_the_z_channels(tmp_path):
    """The 3d family: the plan takes z channels for the out-of-plane modes, and the layout
    read back pairs every mode, in-plane and out-of-plane, with itself at MAC 1, through the
    out-of-plane model's own reading of w."""
    scene = tmp_path / "case3_3d.toml"
    scene.write_text(f'base = "{SCENE.as_posix()}"\n[model]\nfamily = "3d"\n')
    result = run("sensors", scene, "--count", "10", "--modes", "6", "--no-pictures", "--json",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    parts = {m["part"] for m in document["target_modes"]}
    kinds = {s["kind"] for s in document["effective_independence"]["sensors"]}
    assert parts == {"in-plane", "out-of-plane"} and "z" in kinds
    again = run("correlate", scene, tmp_path / "case3_3d" / "sensors.csv", "-n", "6",
                "--no-pictures", "--json", "--out", tmp_path / "again")
    assert again.exit_code == 0, again.output
    pairs = json.loads(again.stdout)["pairs"]
    assert [(p["test"], p["model"]) for p in pairs] == [(k, k) for k in range(1, 7)]
    assert min(p["mac"] for p in pairs) > 1 - 1e-8


def test_a_complex_mode_is_read_as_its_real_shape_frequency_and_damping(tmp_path):
    """A complex mode (UFF 55 analysis type 3) whose entries share one phase is that phase
    times a real shape: read back as the real shape (up to sign and the six digits kept),
    f = |lambda| / 2 pi and zeta = -Re(lambda) / |lambda|."""
    import cmath
    import math

    shape = np.array([[0.3, -1.0, 0.0], [0.7, 0.2, 0.0], [-0.4, 0.5, 0.0]])
    phase = cmath.exp(0.7j)
    zeta, f = 0.02, 80.0
    w = 2 * math.pi * f
    eig = complex(-zeta * w, w * math.sqrt(1 - zeta**2))
    values = shape * phase
    mode = pyuff.prepare_55(model_type=1, analysis_type=3, data_ch=2, spec_data_type=8,
                            data_type=5, n_data_per_node=3, r1=values[:, 0], r2=values[:, 1],
                            r3=values[:, 2] + 0j, load_case=1, mode_n=1, eig=eig,
                            modal_a=0j, modal_b=0j, node_nums=np.arange(1, 4))
    test = read_test(_uff(tmp_path / "complex.uff", [_mm(), _geometry(), mode]))
    expected = shape[test.channel_point, np.argmax(test.channel_direction, axis=1)]
    sign = np.sign(test.shapes[0, 0] / expected[0])
    np.testing.assert_allclose(sign * test.shapes[:, 0], expected, rtol=0, atol=SIX_DIGITS)
    assert test.frequencies[0] == pytest.approx(f, rel=SIX_DIGITS)
    assert test.damping[0] == pytest.approx(zeta, rel=1e-4)
