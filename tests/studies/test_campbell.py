"""Campbell diagram: critical speed ranges and nearest margin (studies/campbell.py), and the
`flexlink campbell` command."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.cli import main
from flexlink.commands._speeds import parse_speeds
from flexlink.errors import InputError
from flexlink.studies.cycle.bands import Band, bands, critical_speeds, nearest_margin
from flexlink.units import RPM


def test_critical_speeds_against_a_hand_computation():
    # band 100-120 Hz, 5 % margin: harmonic n is critical from 60 * 100 * 0.95 / n to
    # 60 * 120 * 1.05 / n rev/min; n = 1 (5700-7560) lies above 3000, n = 2 is 2850-3780 cut
    # at 3000, n = 3 is 1900-2520
    found = [Band(1, 100.0, 120.0)]
    critical = critical_speeds(found, (0.0, 3000 * RPM), 0.05, 3)
    got = [(c.harmonic, c.low / RPM, c.high / RPM) for c in critical]
    assert got == [(2, pytest.approx(2850.0), pytest.approx(3000.0)),
                   (3, pytest.approx(1900.0), pytest.approx(2520.0))]


def test_nearest_margin_when_nothing_is_critical():
    found = [Band(1, 100.0, 120.0), Band(2, 300.0, 310.0)]
    # harmonic 1 reaches 50 Hz at 3000 rev/min: 50 % below the first band's lower edge
    assert critical_speeds(found, (0.0, 3000 * RPM), 0.05, 1) == []
    nearest = nearest_margin(found, (0.0, 3000 * RPM), 1)
    assert (nearest.mode, nearest.harmonic) == (1, 1)
    assert nearest.gap == pytest.approx(0.5)
    assert nearest.speed == pytest.approx(3000 * RPM)
    # a band above the harmonic lines from the low end of the range on
    above = nearest_margin([Band(1, 10.0, 12.0)], (1200 * RPM, 3000 * RPM), 1)
    assert above.gap == pytest.approx((20.0 - 12.0) / 12.0)


def test_bands_are_the_cycle_extremes_and_refuse_missing_modes():
    f = np.array([[1.0, 5.0], [2.0, 4.0], [1.5, 6.0]])
    assert [(b.low, b.high) for b in bands(f)] == [(1.0, 2.0), (4.0, 6.0)]
    with pytest.raises(InputError):
        bands(np.array([[1.0], [np.nan]]))


def test_speed_ranges_are_read_with_their_unit():
    assert parse_speeds("0:3000 rev/min") == (0.0, pytest.approx(3000 * RPM))
    assert parse_speeds("10 rad/s:20 rad/s") == (10.0, 20.0)
    with pytest.raises(InputError):
        parse_speeds("3000 rev/min")
    with pytest.raises(InputError):
        parse_speeds("0:3000")


def test_campbell_command_writes_critical_speeds(tmp_path):
    result = CliRunner().invoke(main, ["campbell", "cases/case1.toml", "--speeds",
                                       "0:3000 rev/min", "-e", "8", "--poses", "12", "--json",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    low = doc["bands"][0]["min_Hz"]
    # the hand formula on the command's own band: 10 x speed reaches 0.95 f_min at
    # 60 * 0.95 f_min / 10 rev/min (case 1's first band starts near 522 Hz: inside 3000)
    expected = [c for c in doc["critical_speeds"] if c["mode"] == 1 and c["harmonic"] == 10]
    assert expected and expected[0]["from_rev_per_min"] == pytest.approx(60 * 0.95 * low / 10)
    for name in ("campbell.png", "campbell.csv", "campbell.json"):
        assert (tmp_path / "case1" / name).stat().st_size > 0
    assert all(b["label"] for b in doc["bands"])
