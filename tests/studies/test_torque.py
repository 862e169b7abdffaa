"""``flexlink torque`` and the [[loads]] table: every shipped scene runs or refuses in one line,
bad input names the file and the field, loads enter the torque by superposition, CSV loads
are periodic, and over a turn at constant speed the drive's work balances the loads'."""

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import CASES_DIR, ROOT, SCENES_DIR
from flexlink.cli import main
from flexlink.errors import InputError
from flexlink.scene import load_scene
from flexlink.commands._speeds import operating_speed
from flexlink.studies.running.torque import torque_study

SHIPPED = sorted(CASES_DIR.glob("case*.toml")) + sorted(SCENES_DIR.glob("*.toml"))
CASE3 = CASES_DIR / "case3.toml"


def run(*args):
    result = CliRunner().invoke(main, ["torque", *map(str, args)])
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_shipped_scene_runs_or_refuses_in_one_line(path, tmp_path):
    code, out, err = run(path, "--speed", "600 rev/min", "--poses", "24", "--json",
                         "--out", tmp_path)
    if code == 0:
        doc = json.loads(out)
        assert doc["poses"] == 24 and doc["crank_speed_rad_s"] == pytest.approx(20 * math.pi)
        assert all(math.isfinite(doc[k]) for k in ("peak_torque_N_m", "mean_power_W"))
        assert doc["model"] and all(p.endswith(("csv", "json", "png")) for p in doc["files"])
    else:
        assert code == 2 and err.count("\n") == 1 and str(path) in err, err


@pytest.mark.parametrize("args, field", [
    (("--speed", "600 m"), "--speed"),
    (("--speed", "nan rad/s"), "--speed"),
    (("--speed", "inf rad/s"), "--speed"),
    (("--speed", "1e400 rad/s"), "--speed"),
    (("--speed", "-3 rad/s"), "--speed"),
    (("--crank-acceleration", "5 rad/s^2"), "--crank-acceleration"),
    (("--speed", "3 rad/s", "--crank-acceleration", "5 rad/s"), "--crank-acceleration"),
    ((), "--speed"),
])
def test_bad_operating_point_is_one_line_naming_the_option(args, field, tmp_path):
    code, _, err = run(CASE3, *args, "--out", tmp_path)
    assert code == 2 and err.count("\n") == 1 and "command line" in err and field in err, err
    assert not list(tmp_path.rglob("torque.*"))  # nothing half-written


def scene_with(tmp_path, loads: str, csv: str | None = None, base=CASE3):
    if csv is not None:
        (tmp_path / "load.csv").write_text(csv)
    path = tmp_path / "loaded.toml"
    path.write_text(f'base = "{base.as_posix()}"\n{loads}')
    return path


TORQUE_CSV = '[[loads]]\nkind = "torque"\nlink = "rocker"\ncsv = "load.csv"\nunit = "N*m"\n'


def grid_csv(angles, values, header="crank_angle_deg,torque"):
    return header + "\n" + "".join(f"{a},{v}\n" for a, v in zip(angles, values))


@pytest.mark.parametrize("loads, csv, field, words", [
    ('[[loads]]\nkind = "torque"\nlink = "rocker2"\ntorque = "1 N*m"\n', None,
     "loads[0].link", "unknown body 'rocker2'"),
    (TORQUE_CSV, grid_csv([a for a in range(0, 360, 10) if a != 130], [1.0] * 35),
     "loads[0].csv", "missing crank angle"),
    (TORQUE_CSV, grid_csv(range(0, 180, 10), [1.0] * 18), "loads[0].csv", "not one full turn"),
    (TORQUE_CSV, grid_csv(range(0, 360, 10), [1.0] * 17 + [""] + [1.0] * 18),
     "loads[0].csv", "row 19, column 'torque': missing value"),
    (TORQUE_CSV, "crank_angle_deg,torque\n0,1\n120,1\n240,1\n".replace("120,1", "120,x"),
     "loads[0].csv", "unreadable"),
    (TORQUE_CSV.replace("N*m", "N"), grid_csv(range(0, 360, 10), [1.0] * 36), "loads[0].unit",
     "unknown unit"),
    ('[[loads]]\nkind = "force"\nlink = "coupler"\nforce = ["1 N", "0 N"]\n', None,
     "loads[0].at", "missing"),
    ('[[loads]]\nkind = "torque"\nlink = "rocker"\n', None, "loads[0].torque", "missing"),
])
def test_bad_loads_name_file_and_field(tmp_path, loads, csv, field, words):
    path = scene_with(tmp_path, loads, csv)
    with pytest.raises(InputError) as info:
        load_scene(path)
    message = str(info.value)
    assert field in message and words in message and "\n" not in message, message
    assert str(tmp_path) in message  # the scene or the CSV file


def test_cli_bad_load_is_one_line(tmp_path):
    path = scene_with(tmp_path, TORQUE_CSV, grid_csv(range(0, 180, 10), [1.0] * 18))
    code, _, err = run(path, "--speed", "3 rad/s", "--out", tmp_path / "out")
    assert code == 2 and err.count("\n") == 1 and "load.csv" in err and "loads[0].csv" in err


def test_csv_load_is_periodic_and_linear(tmp_path):
    angles = np.arange(0, 360, 30)
    values = np.cos(np.radians(angles)) + 0.1 * np.arange(12)
    path = scene_with(tmp_path, TORQUE_CSV, grid_csv(angles, values) + "360,1.0\n")
    [load] = load_scene(path).loads
    for a, v in zip(angles, values):  # on the samples, also a turn later and earlier
        for turn in (-360, 0, 720):
            assert load.value_at(math.radians(a + turn))[0] == pytest.approx(v, abs=1e-12)
    mid = load.value_at(math.radians(345.0))[0]  # between the last sample and the first
    assert mid == pytest.approx((values[-1] + values[0]) / 2, abs=1e-12)


def test_loads_enter_the_torque_by_superposition(tmp_path):
    """Inverse dynamics is linear in the loads: a torque T on the rocker adds -T K_rocker to
    the driving torque; a force f normal to the crank at radius r adds -r f."""
    speed = 30.0
    plain = torque_study(load_scene(CASE3), speed, poses=36)
    loads = ('[[loads]]\nkind = "torque"\nlink = "rocker"\ntorque = "2 N*m"\n'
             '[[loads]]\nkind = "force"\nlink = "crank"\nforce = ["0 N", "5 N"]\n'
             'at = ["20 mm", "0 mm"]\nframe = "body"\n')
    scene = load_scene(scene_with(tmp_path, loads))
    loaded = torque_study(scene, speed, poses=36)
    K_rocker = np.array([s.K[2] for s in scene.linkage.cycle(
        plain.q, scene.cycle_origin()[1]).states])
    expected = plain.torque - 2.0 * K_rocker - 0.020 * 5.0
    # the loads are 1e4 times the inertia torque here: round-off of the pin solve ~1e-15
    assert loaded.torque == pytest.approx(expected, rel=1e-10, abs=1e-12)


def test_work_over_a_turn_balances_at_constant_speed(tmp_path):
    """At constant speed T(q) is periodic, so the mean drive power equals minus the mean
    power of the loads (a CSV load varying over the turn); without loads it is zero."""
    speed = 50.0
    angles = np.arange(0, 360, 5)
    path = scene_with(tmp_path, TORQUE_CSV, grid_csv(angles, 1 + np.sin(np.radians(2 * angles))))
    curve = torque_study(load_scene(path), speed, poses=720)
    scale = np.abs(curve.power).max()
    # mean of dT/dt over evenly spaced samples of a smooth periodic T: spectrally small
    assert abs(curve.power.mean() + curve.load_power.mean()) <= 1e-6 * scale
    bare = torque_study(load_scene(CASE3), speed, poses=360)
    assert abs(bare.power.mean()) <= 1e-12 * np.abs(bare.power).max()


def test_scene_operation_is_the_default(tmp_path):
    path = scene_with(tmp_path, '[operation]\ncrank_speed = "60 rev/min"\n'
                                'crank_acceleration = "2 rad/s^2"\n')
    scene = load_scene(path)
    assert operating_speed(scene) == pytest.approx((2 * math.pi, 2.0))
    assert operating_speed(scene, 3.0) == pytest.approx((3.0, 0.0))  # the speed given alone
    bad = scene_with(tmp_path, '[operation]\ncrank_acceleration = "2 rad/s^2"\n')
    with pytest.raises(InputError, match="operation.crank_speed: missing"):
        load_scene(bad)


def test_outputs_agree(tmp_path):
    code, out, _ = run(CASE3, "--speed", "3.27 rad/s", "--poses", "72", "--json",
                       "--out", tmp_path)
    assert code == 0
    doc = json.loads(out)
    rows = np.loadtxt(tmp_path / "case3" / "torque.csv", delimiter=",", skiprows=1)
    assert rows.shape == (72, 5 + 3 * len(doc["joint_forces"]))
    assert doc["peak_torque_N_m"] == pytest.approx(rows[np.argmax(np.abs(rows[:, 1])), 1],
                                                   rel=1e-9)
    # the CSV keeps 10 significant digits
    assert doc["mean_power_W"] == pytest.approx(rows[:, 2].mean(), abs=1e-9 * abs(rows[:, 2]).max())
    assert (tmp_path / "case3" / "torque.png").read_bytes()[:4] == b"\x89PNG"
    assert (ROOT / "docs" / "dynamics.md").is_file()
