"""Inputs of a hostile run, each reproduced by one command: bad input is refused in one line
naming the file (or the command line) and the field, with exit code 2 and no file of an
earlier run lost or half-replaced; an option that would be ignored is refused; a result the
model cannot give (a flat pose's torque) is reported, never averaged in."""

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import CASES_DIR, SCENES_DIR
from flexlink.cli import main
from flexlink.errors import InputError
from flexlink.scene import load_scene

CASE3 = CASES_DIR / "case3.toml"
CHANGE_POINT = SCENES_DIR / "change_point.toml"


def run(*args):
    result = CliRunner().invoke(main, [*map(str, args)])
    return result.exit_code, result.stdout, result.stderr


def one_line_refusal(code, err, *words):
    """Exit 2 and one line of error; a scene with [checks] plausibility = "warn" may log
    its implausible values before it, one line each."""
    assert code == 2, err
    lines = [line for line in err.splitlines() if not line.startswith("warning: ")]
    assert len(lines) == 1 and "Traceback" not in err and "Warning:" not in err, err
    for w in words:
        assert w in lines[0], err


def scene_with(tmp_path, text: str, base=CASE3, name="hostile.toml"):
    path = tmp_path / name
    path.write_text(f'base = "{base.as_posix()}"\n{text}')
    return path


# -- ranges and speeds -----------------------------------------------------------------------

def test_an_infinite_range_end_is_named_as_not_finite():
    """'0:inf rev/min' used to say "unknown unit ''" about the low end."""
    from flexlink.units import parse_range
    with pytest.raises(InputError) as info:
        parse_range("0:inf rev/min", "angular speed", source="command line", field="--speeds")
    message = str(info.value)
    assert "inf" in message and "not a finite number" in message and "unit ''" not in message


def test_a_scene_speed_of_a_billion_rev_per_min_is_implausible(tmp_path):
    path = scene_with(tmp_path, '[operation]\ncrank_speed = "1e9 rev/min"\n')
    with pytest.raises(InputError) as info:
        load_scene(path)
    assert info.value.field == "operation.crank_speed" and "plausible" in str(info.value)
    warned = scene_with(tmp_path, '[operation]\ncrank_speed = "1e9 rev/min"\n'
                        '[checks]\nplausibility = "warn"\n', name="warned.toml")
    assert load_scene(warned).options.crank_speed == pytest.approx(1e9 * math.pi / 30)


def test_a_command_line_speed_of_a_billion_rev_per_min_is_implausible(tmp_path):
    code, _, err = run("torque", CASE3, "--speed", "1e9 rev/min", "--out", tmp_path)
    one_line_refusal(code, err, "command line", "--speed", "plausible")
    assert not list(tmp_path.rglob("torque.*"))


def test_modes_at_an_overflowing_speed_names_the_speed_not_a_singular_stiffness(tmp_path):
    """1e300 rad/s squares to inf: refused as a speed, never as "K is singular", and no numpy
    RuntimeWarning reaches the user; with plausibility "warn" the overflow itself is named."""
    code, _, err = run("modes", CASE3, "--speed", "1e300 rad/s", "--out", tmp_path)
    one_line_refusal(code, err, "--speed")
    assert "singular" not in err
    warned = scene_with(tmp_path, '[checks]\nplausibility = "warn"\n')
    code, _, err = run("modes", warned, "--speed", "1e300 rad/s", "--out", tmp_path)
    one_line_refusal(code, err, "speed", "overflow")
    assert "singular" not in err


# -- torque ---------------------------------------------------------------------------------

def test_an_overflowing_torque_is_refused_before_any_file_is_replaced(tmp_path):
    """--crank-acceleration 1e300 rad/s^2 used to write torque.csv, then fail on the JSON,
    leaving torque.json and torque.png of the earlier run beside a new torque.csv."""
    warned = scene_with(tmp_path, '[checks]\nplausibility = "warn"\n')
    out = tmp_path / "out"
    code, _, err = run("torque", warned, "--speed", "600 rev/min", "--poses", "12",
                       "--out", out)
    assert code == 0, err
    before = {p.name: p.read_bytes() for p in (out / "hostile").iterdir()}
    assert set(before) == {"torque.csv", "torque.json", "torque.png"}
    for option in (("--crank-acceleration", "1e300 rad/s^2"), ("--speed", "1e150 rad/s")):
        args = ("--speed", "600 rev/min", *option) if option[0] != "--speed" else option
        code, _, err = run("torque", warned, *args, "--poses", "12", "--out", out)
        one_line_refusal(code, err, option[0])
        after = {p.name: p.read_bytes() for p in (out / "hostile").iterdir()}
        assert after == before  # every file of the earlier run, byte for byte


def test_the_flat_pose_of_a_change_point_linkage_is_reported_not_averaged(tmp_path):
    """At crank 180 deg every link of scenes/change_point.toml lies on the ground line: its
    pin forces are not determined there. The default 360 poses land on it; its torque (1.6e6
    N m from round-off) used to be the peak and dominate the mean power. Passing through the
    flat pose along the branch, the torque stays that of the neighbouring poses: 361 poses
    (none on the flat pose) give a peak of 2.1 N m at 1000 rev/min."""
    code, out, err = run("torque", CHANGE_POINT, "--speed", "1000 rev/min", "--json",
                         "--out", tmp_path)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["singular_poses_deg"] == [pytest.approx(180.0)]
    code, out361, _ = run("torque", CHANGE_POINT, "--speed", "1000 rev/min", "--poses", "361",
                          "--json", "--out", tmp_path)
    reference = json.loads(out361)
    assert reference["singular_poses_deg"] == []
    # the other 359 poses sample the same smooth curve: peaks and means agree to the grid
    assert abs(doc["peak_torque_N_m"]) < 1.2 * abs(reference["peak_torque_N_m"])
    assert abs(doc["mean_power_W"]) < 0.05 * abs(reference["peak_power_W"])
    for force in doc["joint_forces"].values():
        assert force["peak_N"] < 1e4
    code, text, _ = run("torque", CHANGE_POINT, "--speed", "1000 rev/min", "--out", tmp_path)
    assert "warning: singular pose at crank 180" in text
    csv_rows = (tmp_path / "change_point" / "torque.csv").read_text().splitlines()
    flat = next(r for r in csv_rows[1:] if r.startswith("180,"))
    assert flat.split(",")[1] == ""  # no torque where none is determined


def test_a_turn_that_ends_on_another_assembly_is_said(tmp_path):
    """Past its flat pose the change-point linkage continues on its crossed assembly: at 359
    deg the coupler is at -36 deg where it began at +37, so the torque curve jumps at the
    turn's start and its mean power (-0.6 W with no loads) is no cycle's. Case 3 closes."""
    code, out, err = run("torque", CHANGE_POINT, "--speed", "1000 rev/min", "--json",
                         "--out", tmp_path)
    assert code == 0, err
    assert json.loads(out)["turn_closes"] is False
    code, text, _ = run("torque", CHANGE_POINT, "--speed", "1000 rev/min", "--out", tmp_path)
    assert "warning: after one turn the linkage is on another assembly" in text
    code, out, err = run("torque", CASE3, "--speed", "1000 rev/min", "--json", "--out",
                         tmp_path)
    assert code == 0 and json.loads(out)["turn_closes"] is True, err


def test_torque_reports_the_scene_pose_whatever_the_grid(tmp_path):
    """The pose of case 3 (mu = 90 deg) lies between 1-degree steps. Its torque at constant
    speed without loads is dE/dq (power balance: tau Omega = dE/dt), checked by central
    differences of the kinetic energy at the poses beside it."""
    from flexlink.studies.running.torque import torque_at
    scene = load_scene(CASE3)
    speed, h = 60.0, 1e-4
    at = torque_at(scene, speed, 0.0, scene.start)
    ahead = torque_at(scene, speed, 0.0, scene.start + h).kinetic_energy
    behind = torque_at(scene, speed, 0.0, scene.start - h).kinetic_energy
    # central difference error h^2 E'''/6 ~ 1e-8 of E' here
    assert at.torque == pytest.approx((ahead - behind) / (2 * h), rel=1e-6)
    code, out, err = run("torque", CASE3, "--speed", "60 rad/s", "--json", "--out", tmp_path)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["at_pose"]["crank_angle_deg"] == pytest.approx(math.degrees(scene.start))
    assert doc["at_pose"]["torque_N_m"] == pytest.approx(at.torque, rel=1e-12)
    assert min(abs(math.degrees(scene.start) - k) for k in range(360)) > 0.01  # off the grid


def test_torque_echoes_the_loads_it_applied(tmp_path):
    path = scene_with(tmp_path, '[[loads]]\nkind = "force"\nlink = "coupler"\n'
                      'force = ["3 N", "-4 N"]\nat = ["100 mm", "0 mm"]\n')
    code, out, err = run("torque", path, "--speed", "100 rev/min", "--poses", "12", "--json",
                         "--out", tmp_path)
    assert code == 0, err
    [load] = json.loads(out)["loads"]
    assert load["field"] == "loads[0]" and load["kind"] == "force" and load["link"] == "coupler"
    assert load["value"] == pytest.approx([3.0, -4.0]) and load["at_m"] == pytest.approx([0.1, 0.0])
    code, text, _ = run("torque", path, "--speed", "100 rev/min", "--poses", "12",
                        "--out", tmp_path)
    assert "load loads[0]: force (3, -4) N on coupler at (100, 0) mm" in text, text


# -- loads ----------------------------------------------------------------------------------

def test_a_load_point_far_off_its_body_is_implausible(tmp_path):
    """A point 5 m from a 270 mm coupler is a unit slip (5 m for 5 mm), not a lever."""
    table = ('[[loads]]\nkind = "force"\nlink = "coupler"\nforce = ["1 N", "0 N"]\n'
             'at = ["5 m", "0 m"]\n')
    with pytest.raises(InputError) as info:
        load_scene(scene_with(tmp_path, table))
    assert info.value.field == "loads[0].at" and "plausible" in str(info.value)
    load_scene(scene_with(tmp_path, table + '[checks]\nplausibility = "warn"\n', name="w.toml"))


def test_a_load_with_both_a_value_and_a_csv_says_so(tmp_path):
    table = ('[[loads]]\nkind = "torque"\nlink = "rocker"\ntorque = "1 N*m"\ncsv = "l.csv"\n'
             'unit = "N*m"\n')
    with pytest.raises(InputError) as info:
        load_scene(scene_with(tmp_path, table))
    message = str(info.value)
    assert "missing" not in message and "not both" in message, message


def test_a_load_csv_that_is_a_folder_says_so(tmp_path):
    (tmp_path / "l.csv").mkdir()
    table = '[[loads]]\nkind = "torque"\nlink = "rocker"\ncsv = "l.csv"\nunit = "N*m"\n'
    with pytest.raises(InputError) as info:
        load_scene(scene_with(tmp_path, table))
    message = str(info.value)
    assert "no such file" not in message and "a folder" in message, message


# -- kinematics -----------------------------------------------------------------------------

NON_GRASHOF = ('name = "non-Grashof"\n[linkage]\nground = "300 mm"\ncrank = "180 mm"\n'
               'coupler = "200 mm"\nrocker = "150 mm"\n[pose]\ncrank_angle = "60 deg"\n'
               '[material]\nE = "70 GPa"\ndensity = "2700 kg/m^3"\n[section]\nwidth = "12 mm"\n'
               'thickness = "3 mm"\nbending = "flatwise"\n[joints]\nKt = "rigid"\nKr = "0 N*m/rad"\n'
               '[drive]\nlink = "crank"\njoint = "O2"\nstiffness = "rigid"\n')


@pytest.mark.parametrize("command, args", [
    ("kinematics", []), ("cycle", []), ("response", ["--speed", "600 rev/min"]),
    ("stability-map", ["--speeds", "300:600 rev/min", "--count", "2"])])
def test_a_crank_that_cannot_turn_fully_is_named(tmp_path, command, args):
    path = tmp_path / "nongrashof.toml"
    path.write_text(NON_GRASHOF)
    code, _, err = run(command, path, *args, "--out", tmp_path / "out")
    one_line_refusal(code, err, "cannot turn fully")
    assert "Newton-Raphson" not in err


def test_kinematics_csv_headers_are_unique(tmp_path):
    code, _, err = run("kinematics", CASE3, "--out", tmp_path)
    assert code == 0, err
    header = (tmp_path / "case3" / "kinematics.csv").read_text().splitlines()[0].split(",")
    assert len(header) == len(set(header)), header


# -- options that would be ignored ----------------------------------------------------------

def test_response_count_without_a_range_is_refused(tmp_path):
    code, _, err = run("response", CASE3, "--speed", "600 rev/min", "--count", "5",
                       "--out", tmp_path)
    one_line_refusal(code, err, "--count", "--speeds")


def test_campbell_speed_steps_without_dynamic_is_refused(tmp_path):
    code, _, err = run("campbell", CASE3, "--speeds", "0:3000 rev/min", "--speed-steps", "7",
                       "--out", tmp_path)
    one_line_refusal(code, err, "--speed-steps", "--dynamic")


# -- text tables ----------------------------------------------------------------------------

def test_a_reference_shorter_than_the_modes_keeps_the_columns_aligned(tmp_path):
    """The README's steel example: three reference values, four modes; the fourth row's
    effective masses used to slide under the reference columns."""
    path = scene_with(tmp_path, '[reference]\nsource = "a tap test"\nEx_Hz = [80, 200]\n')
    code, out, err = run("modes", path, "-n", "4", "-e", "8", "--out", tmp_path)
    assert code == 0, err
    lines = out.splitlines()
    header = next(i for i, line in enumerate(lines) if line.lstrip().startswith("mode"))
    end = lines[header].index("m_y g") + len("m_y g")
    rows = lines[header + 1:header + 5]
    for row in rows:  # each row's m_y value ends under the header's m_y g
        assert row[end - 1] != " " and row[end] == " ", rows


def test_a_balanced_rotor_needs_no_torque_and_shows_none(tmp_path):
    """scenes/rotor.toml spins a bar about its end at constant speed: no work is done, the
    torque is exactly 0; the pin solve left +-1e-13 N m of round-off (from its 2138 N pin
    force), which the report plotted as a jagged curve."""
    code, out, err = run("torque", SCENES_DIR / "rotor.toml", "--poses", "72", "--json",
                         "--out", tmp_path)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["joint_forces"]["O:rotor"]["peak_N"] > 1e3  # the forces themselves stay
    # set to 0 below the round-off floor, so exactly 0 (not a computed float)
    assert doc["peak_torque_N_m"] == 0.0 and doc["rms_torque_N_m"] == 0.0
    assert doc["at_pose"]["torque_N_m"] == 0.0
    # a torque that is not round-off stays: case 3's is some N m
    code, out, err = run("torque", CASE3, "--speed", "600 rev/min", "--poses", "72", "--json",
                         "--out", tmp_path)
    assert abs(json.loads(out)["peak_torque_N_m"]) > 1e-3


def test_a_range_edge_in_rev_per_min_comes_back_as_written(tmp_path):
    """2900 rev/min went to rad/s and back as 2900.0000000000005 in campbell.json."""
    from flexlink.units import RPM, rev_per_min
    assert repr(rev_per_min(2900 * RPM)) == "2900.0"  # rounded to 12 digits: exact by design
    # a speed that is no short decimal keeps every digit, bit for bit (the division as it is)
    assert list(rev_per_min(np.array([2900 * RPM, 10.0]))) == [2900.0, 10.0 / RPM]
    code, out, err = run("campbell", CASE3, "--speeds", "0:2900 rev/min", "--json",
                         "--out", tmp_path)
    assert code == 0, err
    assert "2900.0000000000005" not in out
    assert json.loads(out)["speeds_rev_per_min"] == [0.0, 2900.0]


def test_a_grid_angle_in_degrees_comes_back_as_written(tmp_path):
    """The 1-degree grid's 19 deg came back as 18.999999999999996 in torque.json."""
    from flexlink.units import degrees_in_turn
    assert repr(degrees_in_turn(math.radians(19.0))) == "19.0"  # rounded: exact by design
    assert degrees_in_turn(-math.pi / 2) == 270.0
    code, out, err = run("torque", CASE3, "--speed", "2700 rev/min", "--json", "--out", tmp_path)
    assert code == 0, err
    document = json.loads(out)
    angles = [v["at_deg"] for v in document["joint_forces"].values()]
    angles += [v for k, v in document.items() if k.endswith("_at_deg")]
    assert angles and all(a == round(a, 9) for a in angles), angles


def test_overdamped_modes_are_named(tmp_path):
    """[damping] rayleigh_beta = 1 s (inside its declared range) gives case 3's first mode
    zeta = beta omega / 2 = 175 times critical; modes printed 17506 % without a word."""
    path = scene_with(tmp_path, "[damping]\nrayleigh_beta = 1\n")
    code, out, err = run("modes", path, "-n", "2", "-e", "8", "--json", "--out", tmp_path)
    assert code == 0, err
    [case] = json.loads(out)["cases"]
    first = case["modes"][0]["computed_Hz"]
    assert case["damping_ratio"][0] == pytest.approx(2 * math.pi * first / 2, rel=1e-9)
    assert any("mode(s) 1, 2 overdamped" in w for w in case["warnings"]), case["warnings"]
    code, text, _ = run("modes", path, "-n", "2", "-e", "8", "--out", tmp_path)
    assert "warning: mode(s) 1, 2 overdamped" in text
    light = scene_with(tmp_path, "[damping]\nratio = 0.02\n", name="light.toml")
    code, out, _ = run("modes", light, "-n", "2", "-e", "8", "--json", "--out", tmp_path)
    assert not any("overdamped" in w for w in json.loads(out)["cases"][0]["warnings"])


def test_report_on_a_kinematics_only_scene_shows_its_motion(tmp_path):
    """scenes/extended_rocker.toml has no beams; report exited 2 ("kinematics only") where
    `flexlink kinematics` answers: its page now holds the pose and the rigid motion."""
    code, out, err = run("report", SCENES_DIR / "extended_rocker.toml", "--json",
                         "--out", tmp_path)
    assert code == 0, err
    [scene] = json.loads(out)["scenes"]
    assert scene["frequencies_Hz"] == [] and "kinematics only" in scene["note"]
    html = (tmp_path / "report.html").read_text()
    assert "Rigid motion" in html and "kinematics only" in html
    code, kin, _ = run("kinematics", SCENES_DIR / "extended_rocker.toml", "--poses", "120",
                       "--out", tmp_path / "k")
    first = kin.splitlines()[0]
    assert first in html  # the motion as `flexlink kinematics` prints it


def test_the_report_draws_a_flat_pose_as_a_gap_in_the_torque():
    """The report's 72 torque poses land on the change point's flat pose, whose torque is
    not determined: the page's data has a gap (null) there, never NaN (which JSON refuses)."""
    from flexlink.output.report_data import at_speed_data
    from flexlink.studies.report_scene import SPEED_STEPS, AtSpeed
    from flexlink.studies.running.torque import torque_study
    curve = torque_study(load_scene(CHANGE_POINT), 60.0, poses=72)
    at = AtSpeed(60.0, 0.0, curve, None, np.linspace(0.0, 60.0, SPEED_STEPS), (), "none asked",
                 response_unavailable="none asked")
    data = at_speed_data(at)["torque"]
    json.dumps(data, allow_nan=False)
    gaps = [d for d, t in zip(data["crank_deg"], data["torque_N_m"]) if t is None]
    assert gaps == [pytest.approx(180.0)]


def test_the_diagram_at_speed_samples_every_frozen_range(tmp_path):
    """`campbell --speeds "0:1e6 rev/min" --dynamic` listed 30 frozen critical ranges, then
    'no critical speed in the range, frozen or at speed': its 20408 rev/min grid stepped over
    every one of them."""
    code, text, err = run("campbell", CASE3, "--speeds", "0:1e6 rev/min", "--dynamic",
                          "--speed-steps", "10", "--poses", "24", "-e", "8", "--out", tmp_path)
    assert code == 0, err
    assert "no critical speed in the range, frozen or at speed" not in text
    doc = json.loads((tmp_path / "case3" / "campbell.json").read_text())
    shifts = doc["at_speed"]["critical_speeds"]
    both = [s for s in shifts if s["frozen_rev_per_min"] and s["at_speed_rev_per_min"]]
    assert doc["critical_speeds"] and both  # ranges found at speed beside the frozen ones
    for s in both:  # paired by overlap, as the study pairs them
        a, b = s["frozen_rev_per_min"], s["at_speed_rev_per_min"]
        assert a[0] <= b[1] and b[0] <= a[1]
    # mode 1 diverges near 3300 rev/min: the comparison stops at the grid's last speed before
    # it, and the text says so (the table's 'range end' is that speed, not the user's 1e6)
    low, high = doc["at_speed"]["critical_speeds_compared_rev_per_min"]
    assert low == 0.0 and high < 1e4 and doc["at_speed"]["divergence"] is not None
    assert f"critical ranges compared from 0 to {high:.6g} rev/min" in text
    assert all(s["at_speed_rev_per_min"] is None or s["at_speed_rev_per_min"][1] <= high
               for s in shifts)


def test_a_map_down_to_rest_has_finite_growth_rates(tmp_path):
    """Speeds so slow (0.01 rev/min: T = 6000 s) that the adiabatic bound exp(T r) underflows
    to 0 keep its exponent:
    the growth rate is the turn's mean slowest decay rate, finite, and the JSON holds it."""
    code, out, err = run("stability-map", CASE3, "--speeds", "0:0.03 rev/min", "--count", "4",
                         "-n", "2", "-e", "4", "--json", "--out", tmp_path)
    assert code == 0, err
    assert "Traceback" not in err and "RuntimeWarning" not in err
    document = json.loads(out)
    rates = np.array(document["growth_rate_per_s"][1:])  # the first speed is 0: at rest
    assert np.isfinite(rates).all() and (rates < 0).all()
    # the bound's exponent over the period: the same mean decay rate at every slow speed
    np.testing.assert_allclose(rates, rates[0], rtol=1e-9)


def test_a_document_that_json_cannot_hold_is_refused_before_any_file(tmp_path):
    from flexlink.commands._written import finite_document
    from flexlink.errors import NumericalError

    with pytest.raises(NumericalError, match=r"\['rates'\]\[1\] is not a finite number"):
        finite_document({"name": "x", "rates": [0.5, -math.inf]})
    assert finite_document({"rates": [0.5]}) == {"rates": [0.5]}
