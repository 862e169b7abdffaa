"""Rigid joints (``[joints] Kt = "rigid"``) at speed, as ``modes`` takes them: the periodic
equations build, the stability map and the steady response run, and the response is the limit
of ever stiffer pins (the exact constraints against a spring 1000 times the shipped one)."""

from __future__ import annotations

import logging

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import CASES_DIR
from flexlink.analysis.periodic import periodic_model, speed_multipliers
from flexlink.cli import main
from flexlink.errors import NumericalError
from flexlink.scene import load_scene
from flexlink.studies.running.steady_response import forced_model, steady_response
from flexlink.units import RPM


def scene(tmp_path, kt: str):
    path = tmp_path / f"kt_{kt.split()[0]}.toml"
    path.write_text(f'base = "{(CASES_DIR / "case3.toml").as_posix()}"\n'
                    f'[joints]\nKt = "{kt}"\n')
    return load_scene(path)


def test_rigid_pins_run_and_are_the_stiff_pins_limit(tmp_path):
    # case 3 at 600 rev/min, 4 elements a link, 37 poses (13 do not resolve the rigid pins'
    # matrices over the turn: a spurious multiplier of 1e130). The energy scale of the Magnus steps
    # was the square root of the symmetric part of the mean M^-1 K, indefinite with rigid pins
    # (the pins' shared translations turn with one of their links, so M varies over the turn
    # while K is stiff): a sqrt warning, then LinAlgError
    speed = 600 * RPM
    peaks = {}
    for kt in ("rigid", "1e9 N/m"):
        model = forced_model(scene(tmp_path, kt), n_modes=4, poses=37, elements_per_link=4)
        assert np.all(np.isfinite(model.periodic.energy_scale))
        assert speed_multipliers(model.periodic, speed).largest_modulus < 1.0
        peaks[kt] = steady_response(model, speed, samples=36).peak_strain
    # a pin spring of 1e9 N/m (1000 times the shipped one) against the exact constraint:
    # measured 0.97 %, 0.09 %, 0.22 % on the crank, coupler and rocker midspans
    assert np.allclose(peaks["rigid"], peaks["1e9 N/m"], rtol=0.02, atol=0)


def test_too_few_poses_for_rigid_pins_is_numerical_trouble_not_instability(tmp_path):
    """With 13 poses the rigid pins' M^-1 K, interpolated between poses, has an eigenvalue of
    -1.2e8 (rad/s)^2 at rest (every pose's own is above 1.1e5): the Magnus steps gave
    |mu| = 4.8e130 at 600 rev/min, a false instability. The equations frozen at rest grow
    there at 10591 1/s (5 % of max |lambda|; round-off is 1e-16 of it, and 25 or 37 poses
    decay): the model is refused, naming the cure."""
    path = tmp_path / "kt_rigid.toml"
    scene(tmp_path, "rigid")
    with pytest.raises(NumericalError, match=r"use more poses \(25 or more: --poses"):
        periodic_model(load_scene(path), n_modes=4, poses=13, elements_per_link=4)
    result = CliRunner().invoke(main, ["stability-map", str(path), "--speeds", "600:700 rev/min",
                                       "--count", "2", "--poses", "13", "-n", "4", "-e", "4",
                                       "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and result.stderr.count("\n") == 1, result.stderr
    assert "more poses" in result.stderr
    assert not [p for p in (tmp_path / "out").rglob("*") if p.is_file()]
    # response takes the same --poses: refused at 13, an answer at 25
    for poses, code in (("13", 2), ("25", 0)):
        result = CliRunner().invoke(main, ["response", str(path), "--speed", "600 rev/min",
                                           "--poses", poses, "-n", "4", "-e", "4", "--out",
                                           str(tmp_path / "out")])
        assert result.exit_code == code, result.output


def test_local_growth_that_decays_over_the_turn_is_logged_not_refused(caplog):
    """Case 2 with rigid pins at the default 37 poses: the interpolated M^-1 C lets the
    equations at rest grow near 1.3 deg (1.67 1/s, 4.3e-6 of max |lambda|) while they decay
    by 1.75 1/s on average over the turn; its multipliers stay within 8 % of 73 poses' (10 to
    1000 rev/min). It runs, with the advice logged."""
    with caplog.at_level(logging.WARNING, logger="flexlink.analysis.periodic"):
        model = periodic_model(load_scene(CASES_DIR / "case2.toml", {"joints.Kt": "rigid"}),
                               n_modes=6)
    theta, rates, scale = model.rest_rates()
    assert rates.max() > 1e-8 * scale and rates.mean() < 0.0
    assert any("more poses (--poses 73)" in r.getMessage() for r in caplog.records)
