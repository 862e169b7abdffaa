"""The form of every returned result: sorted ascending, complete (n elastic modes asked, n
returned, every zero mode below them listed), finite, the same for any request size, and the
same numbers in the text table, the CSV file and the JSON document of ``flexlink modes``."""

import csv
import json
import math
import re
import tempfile

import numpy as np
from click.testing import CliRunner
from hypothesis import given
from hypothesis import strategies as st
from strategies import fewer, linkages, load, write_scene

from flexlink.analysis.modal import Mass, analyze
from flexlink.analysis.solve import ELASTIC, MECHANISM
from flexlink.cli import main


@given(linkages(), st.integers(1, 5), st.sampled_from(tuple(Mass)))
def test_modes_come_sorted_complete_and_finite(spec, n, mass):
    modes = analyze(load(spec), n, mass=mass).modes
    k = len(modes.kinds)
    assert modes.eigenvalues.shape == modes.frequencies.shape == (k,)
    assert modes.shapes.shape == (modes.shapes.shape[0], k)
    for array in (modes.eigenvalues, modes.frequencies, modes.shapes, modes.residuals,
                  modes.backward_errors):
        assert np.all(np.isfinite(array))
    assert np.all(np.diff(modes.frequencies) >= 0)
    assert set(modes.kinds) <= {ELASTIC, MECHANISM}
    assert list(modes.kinds) == sorted(modes.kinds, key=lambda kind: kind != MECHANISM)
    assert len(modes.elastic) >= n
    assert modes.elastic_frequencies[0] > 0


@given(linkages(), st.integers(1, 3))
def test_asking_for_more_modes_does_not_change_the_first_ones(spec, n):
    scene = load(spec)
    few = analyze(scene, n).elastic_frequencies(n)
    more = analyze(scene, n + 3).elastic_frequencies(n + 3)
    assert len(few) == n and len(more) == n + 3
    # two eigen solves of different size: agreement to the solver's round-off
    np.testing.assert_allclose(more[:n], few, rtol=1e-10)


def _run(args):
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return result.output


TABLE_ROW = re.compile(r"^\s*(\d+)\s+([\d.e+-]+)\s+([\d.]+)\s+([\d.]+)\s+(.+?)\s*$")


@fewer
@given(linkages(), st.integers(1, 4))
def test_text_csv_and_json_outputs_of_modes_agree(spec, n):
    path = write_scene(spec)
    out = tempfile.mkdtemp(prefix="flexlink-props-out-")
    document = json.loads(_run(["modes", str(path), "-n", str(n), "--json", "--out", out]))
    case = document["cases"][0]
    rows = case["modes"]
    assert [r["mode"] for r in rows] == list(range(1, n + 1))
    computed = np.array([r["computed_Hz"] for r in rows])
    assert np.all(np.isfinite(computed)) and np.all(np.diff(computed) >= 0)
    expected = analyze(load(spec), n).elastic_frequencies(n)
    np.testing.assert_allclose(computed, expected, rtol=1e-12)  # same path, same numbers
    assert all(math.isfinite(f) and f < computed[0] for f in case["mechanism_modes_Hz"])

    csv_file = next(f for f in document["files"] if f.endswith(".csv"))
    with open(csv_file) as handle:
        table = list(csv.DictReader(handle))
    assert len(table) == n
    for row, line in zip(rows, table):
        assert float(line["computed_Hz"]) == row["computed_Hz"]  # repr round-trips exactly
        assert line["label"] == row["label"]
        assert float(line["m_eff_x_kg"]) == row["effective_mass_kg"]["x"]
        assert float(line["m_eff_y_kg"]) == row["effective_mass_kg"]["y"]
        for part, value in row["strain_energy"].items():
            assert float(line[f"strain_{part}"]) == value

    text = _run(["modes", str(path), "-n", str(n), "--out", out])
    printed = [m.groups() for m in map(TABLE_ROW.match, text.splitlines()) if m]
    assert len(printed) == n, text
    for row, (mode, hz, mx, my, label) in zip(rows, printed):
        assert int(mode) == row["mode"]
        # the table rounds, it does not recompute: two decimals from 1 Hz up, four significant
        # digits below (so a soft scene's mHz modes do not all read 0.00)
        f = row["computed_Hz"]
        assert hz == (f"{f:.2f}" if f >= 1.0 else f"{f:.4g}")
        assert mx == f"{1e3 * row['effective_mass_kg']['x']:.3f}"
        assert my == f"{1e3 * row['effective_mass_kg']['y']:.3f}"
        assert label == row["label"]
    with open(next(f for f in document["files"] if f.endswith(".json"))) as handle:
        assert json.load(handle)["cases"][0]["modes"] == rows
