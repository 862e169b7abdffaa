"""``modes --speed``: a mode at speed is paired with a static mode only where their shapes agree
(MAC at least the stated threshold), else it is shown unpaired with no change; a real root is a
row of its own kind (a growth rate, no frequency, no change); the warnings name the cause the
matrices show (negative stiffness of the preload or of the centrifugal softening, or the
circulatory term); ``--terms`` keeps any set of the speed terms, the preload alone included,
so the OpenSees check of the preloaded frame runs from the command line."""

import csv
import io
import json

import pytest
from click.testing import CliRunner

from conftest import CASES_DIR, ROOT, SCENES_DIR
from flexlink.cli import main

ALUMINIUM = SCENES_DIR / "kineto_aluminium.toml"


def modes_at_speed(tmp_path, scene, speed, *args):
    result = CliRunner().invoke(main, ["modes", str(scene), "--speed", speed, "-n", "4",
                                       "--json", "--out", str(tmp_path), *args])
    assert result.exit_code == 0, result.output
    [case] = json.loads(result.stdout)["cases"]
    return case


def text_of(tmp_path, scene, speed, *args):
    result = CliRunner().invoke(main, ["modes", str(scene), "--speed", speed, "-n", "4",
                                       "--out", str(tmp_path), *args])
    assert result.exit_code == 0, result.output
    return result.stdout


def test_a_mode_paired_below_the_threshold_shows_no_change(tmp_path):
    """At 1000 rev/min the aluminium four-bar's modes 1-3 resemble their static partners at
    MAC 0.43-0.58: their 'change %' (-29, -13, +78 %) compared different shapes."""
    case = modes_at_speed(tmp_path, ALUMINIUM, "1000 rev/min")
    threshold = case["pairing_mac"]
    assert threshold == pytest.approx(0.8)
    weak = [r for r in case["modes"] if r["mac"] < threshold]
    strong = [r for r in case["modes"] if r["mac"] >= threshold and r["kind"] == "vibrating"]
    assert weak and strong
    for r in weak:
        assert r["paired"] is False and r["change_Hz"] is None and r["change_pct"] is None
    for r in strong:
        assert r["paired"] is True
        assert r["change_pct"] == pytest.approx(
            100 * (r["frequency_Hz"] - r["static_Hz"]) / r["static_Hz"], rel=1e-12)
    text = text_of(tmp_path, ALUMINIUM, "1000 rev/min")
    rows = {int(line.split()[0]): line for line in text.splitlines()
            if line[:4].strip().isdigit()}
    for r in weak:
        assert "unpaired" in rows[r["mode"]] and "%" not in rows[r["mode"]].split("unpaired")[0]
    tables = list(csv.DictReader(io.StringIO((tmp_path / "kineto_aluminium"
                                              / "modes_at_speed.csv").read_text())))
    for r in weak:
        assert tables[r["mode"] - 1]["change_pct"] == "" and tables[r["mode"] - 1]["paired"] == "False"


def test_diverging_roots_are_rows_of_their_own_kind(tmp_path):
    """At 3000 rev/min real roots appeared as 0 Hz (or 1.19e-29 Hz), -100 % change, paired
    with an arbitrary static mode."""
    case = modes_at_speed(tmp_path, ALUMINIUM, "3000 rev/min")
    real = [r for r in case["modes"] if r["kind"] in ("diverging", "decaying")]
    assert any(r["kind"] == "diverging" for r in real)
    for r in real:
        assert r["frequency_Hz"] is None and r["change_pct"] is None and r["change_Hz"] is None
        assert r["paired"] is False and r["static_mode"] is None
        assert (r["growth_rate_1_s"] > 0) == (r["kind"] == "diverging")
    table = list(csv.DictReader(io.StringIO((tmp_path / "kineto_aluminium"
                                             / "modes_at_speed.csv").read_text())))
    for r in real:
        row = table[r["mode"] - 1]
        assert row["kind"] == r["kind"] and row["frequency_Hz"] == "" and row["change_pct"] == ""
    text = text_of(tmp_path, ALUMINIUM, "3000 rev/min")
    assert "0.000" not in text.split("largest axial")[0].split("MAC")[1]  # no 0 Hz, no -100 %
    assert "-100.000" not in text


def _negative(case):
    return case["negative_stiffness_eigenvalues"]


def test_warnings_name_the_cause_the_matrices_show(tmp_path):
    """Each term alone says whether it makes the stiffness indefinite; the full run's warning
    names exactly those, and blames the circulatory term only when it is in."""
    full = modes_at_speed(tmp_path, ALUMINIUM, "3000 rev/min")
    alone = {term: _negative(modes_at_speed(tmp_path, ALUMINIUM, "3000 rev/min", "--terms",
                                            term)) for term in ("preload", "centrifugal")}
    assert _negative(full) > 0
    causes = full["instability_causes"]
    assert ("preload" in causes) == (alone["preload"] > 0)
    assert ("centrifugal" in causes) == (alone["centrifugal"] > 0)
    warning = full["stability"]
    if alone["preload"]:
        assert "buckling under the inertia preload" in warning
    without = modes_at_speed(tmp_path, ALUMINIUM, "3000 rev/min", "--terms",
                             "preload,centrifugal,coriolis")
    assert "circulatory" not in (without["stability"] or "")
    assert "circulatory" not in without["instability_causes"]


def test_the_circulatory_term_is_named_where_it_alone_makes_modes_grow(tmp_path):
    """At 1000 rev/min the aluminium four-bar's stiffness stays positive definite, yet a pair
    of modes grows: a conservative gyroscopic system cannot (Kelvin-Tait-Chetaev), so the
    skew angular-acceleration term is the cause; without it no mode grows."""
    case = modes_at_speed(tmp_path, ALUMINIUM, "1000 rev/min")
    assert _negative(case) == 0 and any(r["growth_rate_1_s"] > 1e-3 for r in case["modes"])
    assert case["instability_causes"] == ["circulatory"]
    assert "circulatory" in case["stability"]
    off = modes_at_speed(tmp_path, ALUMINIUM, "1000 rev/min", "--terms",
                         "preload,centrifugal,coriolis")
    assert off["stable"] and off["instability_causes"] == []


def test_preload_only_from_the_command_line_matches_opensees(tmp_path):
    """The OpenSees record (tests/data/operating_opensees.json): case 1 at 2000 rev/min under
    the inertia preload alone, 16 elements per link, K_g of the chords (OpenSees's PDelta:
    --geometric string); flexlink matched it to 4e-9 when it was recorded.
    --no-centrifugal --no-coriolis kept the angular-acceleration term: 62.08 Hz."""
    record = json.loads((ROOT / "tests" / "data" / "operating_opensees.json").read_text())
    expected = record["cases"]["cases/case1.toml"]["meshes"]["16"]["frequencies_Hz"]
    case = modes_at_speed(tmp_path, CASES_DIR / "case1.toml", "2000 rev/min", "--terms",
                          "preload", "-e", "16", "--geometric", "string")
    assert case["terms"] == {"preload": True, "centrifugal": False, "coriolis": False,
                             "angular_acceleration": False, "geometric_stiffness": "string"}
    got = [r["frequency_Hz"] for r in case["modes"]]
    # the record's own agreement was 4.2e-9; both solve the same discrete frame
    assert got == pytest.approx(expected, rel=1e-7)


@pytest.mark.parametrize("args, words", [
    (("--terms", "preload,gravity"), "gravity"),
    (("--terms", "preload", "--no-coriolis"), "--no-coriolis"),
])
def test_bad_terms_are_one_line(tmp_path, args, words):
    result = CliRunner().invoke(main, ["modes", str(CASES_DIR / "case1.toml"), "--speed",
                                       "2000 rev/min", *args, "--out", str(tmp_path)])
    assert result.exit_code == 2 and result.stderr.count("\n") == 1, result.output
    assert "--terms" in result.stderr and words in result.stderr, result.stderr
