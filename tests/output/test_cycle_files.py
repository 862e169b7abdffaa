"""`flexlink cycle`: the CSV, the JSON document and the text summary of one run state the same
frequencies. Each mode's range in the JSON (and in the text) is the range of its CSV column,
at the CSV's crank angles; the CSV's columns are f1 ... fN."""

import csv
import io
import json

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.cli import main
from flexlink.scene import load_scene

CASE1 = CASES_DIR / "case1.toml"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("cycle")
    args = ["cycle", str(CASE1), "-n", "2", "--poses", "12", "-e", "2",
            "--sorted", "--out", str(out)]
    # the help's two spellings of "no resonance check": none, and 0 without a unit
    as_json = CliRunner().invoke(main, [*args, "--speed", "none", "--json"])
    assert as_json.exit_code == 0, as_json.output
    text = CliRunner().invoke(main, [*args, "--speed", "0"])
    assert text.exit_code == 0, text.output
    return json.loads(as_json.output), text.output, (out / "case1" / "cycle.csv").read_text()


def test_json_ranges_are_the_csv_columns(run):
    document, _, table = run
    rows = list(csv.reader(io.StringIO(table)))
    assert rows[0] == ["crank_angle_deg", "f1_Hz", "f2_Hz"]
    values = np.array(rows[1:], dtype=float)
    assert len(values) == document["poses"] == 12
    assert document["command"] == "cycle" and document["scene"] == load_scene(CASE1).name
    assert not document["resonance_check"]["speed_rev_per_min"] and not document["resonances"]
    angles = values[:, 0] % 360.0
    for j, mode in enumerate(document["modes"]):
        column = values[:, 1 + j]
        assert mode["mode"] == j + 1
        # the CSV keeps 8 significant digits, the angles 6
        assert mode["min_Hz"] == pytest.approx(column.min(), rel=1e-7)
        assert mode["max_Hz"] == pytest.approx(column.max(), rel=1e-7)
        assert mode["at_crank_deg"] == pytest.approx(angles[column.argmin()], abs=1e-3)
        assert mode["at_crank_deg_max"] == pytest.approx(angles[column.argmax()], abs=1e-3)


def test_text_rows_are_the_json_ranges(run):
    document, text, _ = run
    for mode in document["modes"]:
        row = next(line.split() for line in text.splitlines()
                   if line.split()[:1] == [str(mode["mode"])] and len(line.split()) >= 5)
        assert [float(x) for x in row[1:5]] == pytest.approx(
            [mode["min_Hz"], mode["at_crank_deg"], mode["max_Hz"], mode["at_crank_deg_max"]],
            abs=0.051)  # the text prints 2 decimals of Hz and 1 of degrees
