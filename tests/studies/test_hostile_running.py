"""The running linkage's studies on hostile input, each reproduced by one command first: huge
damping is refused at once instead of hours of steps, slow speeds take no steps where the
adiabatic limit decides, a result past the small-deflection range says so, the diagram at
speed samples every frozen range it looks for, and the messages name the true cause."""

import json
import logging

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import CASES_DIR, SCENES_DIR
from flexlink.analysis.periodic import (Integrator, multipliers_by, periodic_model,
                                        quasi_static_multipliers)
from flexlink.cli import main
from flexlink.scene import load_scene
from flexlink.units import RPM

CASE3 = CASES_DIR / "case3.toml"


def run(*args):
    result = CliRunner().invoke(main, [*map(str, args)])
    return result.exit_code, result.stdout, result.stderr


def scene_with(tmp_path, text: str, base=CASE3, name="hostile.toml"):
    path = tmp_path / name
    path.write_text(f'base = "{base.as_posix()}"\n{text}')
    return path


@pytest.fixture(scope="module")
def small():
    """Case 3 on 2 basis vectors (4 elements a link): cheap enough for Magnus steps at a few
    rev/min (the steps follow the stiffest vector's frequency, 700 Hz here)."""
    return periodic_model(load_scene(CASE3), n_modes=1, elements_per_link=4, basis_size=2)


@pytest.mark.parametrize("rpm", [6.0, 10.0])
def test_quasi_static_multipliers_are_the_integrated_ones(small, rpm):
    """Where every frozen mode decays by 20 e-folds or more a turn, the adiabatic limit's
    bound exp(T mean r) is the largest multiplier the Magnus steps integrate: ln|mu| per
    turn within 1e-6 (1e-8 when measured), and never below it (an upper bound)."""
    speed = rpm * RPM
    quasi = quasi_static_multipliers(small, speed)
    assert quasi is not None
    magnus, used = multipliers_by(small, speed, integrator=Integrator.MAGNUS)
    assert used is Integrator.MAGNUS
    assert quasi.growth_rate == pytest.approx(magnus.growth_rate, rel=1e-6)
    assert quasi.largest_modulus >= magnus.largest_modulus * (1 - 1e-6)


def test_no_quasi_static_shortcut_where_modes_keep_their_energy(small):
    """At 600 rev/min a turn is 0.1 s: the lowest mode loses well under 20 e-folds."""
    assert quasi_static_multipliers(small, 600 * RPM) is None


def test_slow_speeds_take_no_steps(tmp_path):
    """`stability-map --speeds "2:4 rev/min" --count 2` took 149 s of Magnus steps."""
    code, out, err = run("stability-map", CASE3, "--speeds", "2:4 rev/min", "--count", "2",
                         "--json", "--out", tmp_path)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["quasi_static_rev_per_min"] == [2.0, 4.0]
    assert doc["magnus_fallback_rev_per_min"] == []
    assert max(doc["largest_modulus"]) < 1e-9


@pytest.mark.parametrize("command, args", [
    ("stability-map", ("--speeds", "0:3000 rev/min", "--count", "3")),
    ("response", ("--speed", "600 rev/min")),
])
def test_overdamped_rayleigh_damping_is_refused_at_once(tmp_path, command, args):
    """[damping] rayleigh_beta = 1 s (inside its declared range) gives case 3's lowest mode
    zeta = 175; the map and the response ran for more than 300 s."""
    path = scene_with(tmp_path, "[damping]\nrayleigh_beta = 1\n")
    code, _, err = run(command, path, *args, "--out", tmp_path / "out")
    assert code == 2 and err.count("\n") == 1, err
    assert "damping.rayleigh_beta" in err and "overdamped" in err and str(path) in err
    assert not (tmp_path / "out" / "hostile").exists() or not any(
        (tmp_path / "out" / "hostile").iterdir())


def test_a_change_point_is_not_told_to_use_more_poses(tmp_path):
    code, _, err = run("stability-map", SCENES_DIR / "change_point.toml", "--speeds",
                       "0:3000 rev/min", "--count", "3", "--out", tmp_path)
    assert code == 2 and err.count("\n") == 1, err
    assert "use more poses" not in err and "singular pose at crank 180 deg" in err


def test_a_deflection_past_the_small_deflection_range_is_flagged(tmp_path):
    """Case 3 at 2800 rev/min: the coupler's midspan swings some 62 mm, 41 times its 1.5 mm
    depth (63.4 mm, 42 times, before the damping acted on each pose's own deformation); the
    response printed it without a word."""
    code, text, err = run("response", CASE3, "--speed", "2800 rev/min", "--out", tmp_path)
    assert code == 0, err
    doc = json.loads((tmp_path / "case3" / "response.json").read_text())
    limit = doc["small_deflection_limit"]
    scene = load_scene(CASE3)
    for point in doc["points"]:
        depth = scene.sections[point["link"]].depth  # the in-plane size
        ratio = point["peak_deflection_m"] / depth
        assert point["deflection_to_depth"] == pytest.approx(ratio, rel=1e-12)
        assert point["small_deflection"] == (ratio <= limit)
    coupler = next(p for p in doc["points"] if p["link"] == "coupler")
    assert coupler["deflection_to_depth"] > 40 and not coupler["small_deflection"]
    assert any(w.startswith(coupler["label"]) for w in doc["warnings"])
    assert f"beyond small deflection ({coupler['deflection_to_depth']:.3g} x depth)" in text
    assert "warning: " + coupler["label"] in text


def test_the_default_damping_names_no_material(tmp_path):
    """The carbon-strip Table II cases were told their default damping was a bolted metal
    frame's."""
    from flexlink.analysis.damping import basis_damping
    scene = load_scene(CASE3)
    source = basis_damping(scene, None, np.array([1.0, 2.0]), None, None).source
    assert "metal" not in source and "bolted" not in source and "0.01" in source


def test_a_refusal_that_does_not_depend_on_the_speed_names_none(tmp_path, caplog):
    """Rayleigh damping overdamps case 3's stiff basis vectors (zeta up to 2.9 with beta
    1.1423e-4 s): the adiabatic basis is refused for a real eigenvalue, which no speed
    changes. The log said "refused at 5.236 rad/s" at every speed (on the aluminium
    four-bar): now once, naming no speed."""
    path = scene_with(tmp_path, "[damping]\nrayleigh_beta = 1.1423e-4\n")
    model = periodic_model(load_scene(path), n_modes=2, elements_per_link=4)
    with caplog.at_level(logging.INFO, logger="flexlink.analysis.periodic"):
        for rpm in (2000.0, 3000.0):
            multipliers_by(model, rpm * RPM)
    refusals = [r.getMessage() for r in caplog.records if "refused" in r.getMessage()]
    assert len(refusals) == 1 and "every speed" in refusals[0], refusals
    assert "rad/s" not in refusals[0] and "rev/min" not in refusals[0]

