"""Output torques for a given input torque (``flexlink outputs``): virtual work at rest against
the kinematics the tool prints, the power balance at speed with friction and bearing losses,
the wiper's torques against a loop closure written here, and the dead points."""

import csv
import math

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import SCENES_DIR
from flexlink.cli import main
from flexlink.scene import load_scene
from flexlink.studies.kinetostatics.outputs import output_study, with_inputs

WIPER = SCENES_DIR / "wiper.toml"
RPM = 2 * math.pi / 60  # [rad/s] per [rev/min]


def table(path) -> list[dict]:
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def test_virtual_work_at_rest_against_the_printed_kinematics(tmp_path):
    """At rest without losses T_in dq = T_out dtheta for every output, so T_out / T_in = 1 / K
    with K the velocity coefficient ``flexlink kinematics`` prints. Tolerance 1e-9: both CSVs
    carry 10 or more significant digits (5e-10 relative rounding at most), and the torque
    solve's error is eps times its condition (about 1/|K| <= 1e3 on this grid)."""
    for command in ("kinematics", "outputs"):
        result = CliRunner().invoke(main, [command, str(WIPER), "--out", str(tmp_path)])
        assert result.exit_code == 0, result.output
    kin = table(tmp_path / "wiper" / "kinematics.csv")
    out = table(tmp_path / "wiper" / "outputs.csv")
    assert len(kin) == len(out) == 360
    worst = 0.0
    for k, o in zip(kin, out):
        assert float(k["crank_angle_deg"]) == pytest.approx(float(o["crank_angle_deg"]), abs=1e-9)
        t_in = float(o["input_torque_N_m"])
        for body in ("rocker1", "rocker2"):
            ratio = float(o[f"T_{body}_N_m"]) / t_in
            worst = max(worst, abs(ratio * float(k[f"{body}_K"]) - 1.0))
    assert worst < 1e-9, worst


def ke_rate(curve) -> np.ndarray:
    """dKE/dt [W] from the kinetic energy the study reports, by spectral differentiation over
    the crank angle (periodic and smooth, so exact to rounding on 360 samples) times Omega."""
    n = len(curve.q)
    k = np.fft.rfftfreq(n, d=1.0 / n)  # harmonics of the crank angle
    return np.fft.irfft(1j * k * np.fft.rfft(curve.kinetic_energy), n) * curve.speed


def test_power_balance_at_speed_with_friction_and_bearing_losses():
    """At 2000 rev/min with m = 0.3 and eta = 0.85: T_in Omega = T_out omega_out + losses +
    dKE/dt at every crank angle. The losses are recomputed here from the torques each output
    receives: (1 - eta) |R omega| at every bearing plus m eta |R1 omega1| at the first
    output's contact. Tolerance 1e-8 of the input power: the spectral derivative is exact to
    rounding; samples next to a dead point are excluded (torques there are 1e4 times larger
    and the balance holds to 1e-8 of those, not of the input)."""
    scene = load_scene(WIPER)
    spec = with_inputs(scene.kinetostatics, friction=0.3, efficiency=0.85)
    omega = 2000 * RPM
    curve = output_study(scene, omega, spec=spec)
    p_in = curve.input_torque * omega
    w = curve.K * omega
    p_out = curve.torques[:, 1] * w[:, 1]
    losses = (0.15 * np.abs(curve.received * w).sum(axis=1)
              + 0.3 * 0.85 * np.abs(curve.received[:, 0] * w[:, 0]))
    np.testing.assert_allclose(curve.loss_power, losses, rtol=1e-12, atol=1e-9)
    gap = (p_in - p_out - losses - ke_rate(curve))[~curve.near]
    assert np.max(np.abs(gap)) < 1e-8 * np.max(np.abs(p_in)), np.max(np.abs(gap))
    # and the losses are not nothing: at this speed and friction they are a real share
    assert np.mean(losses[~curve.near]) > 0.2 * np.mean(p_in)


# the wiper's geometry as the scene states it [m], rewritten here for an independent closure
O1, O2 = np.array([0.0, 0.0]), np.array([0.458, 0.0])
O3 = np.array([-0.057930, 0.072509])  # O2 + 521 mm at 172 deg, rounded to 1 um as in the scene
CRANK, LINK1, ARM_B, ARM_C, LINK2, ROCKER2 = 0.041, 0.450, 0.052, 0.049, 0.517, 0.053


def circle_meet(p, r_p, c, r_c, side):
    """The point at distance r_p from p and r_c from c on the ``side`` (+1 left, -1 right) of
    the line p -> c."""
    d = np.linalg.norm(c - p)
    a = (r_p**2 - r_c**2 + d**2) / (2 * d)
    h = math.sqrt(r_p**2 - a**2)
    e = (c - p) / d
    return p + a * e + side * h * np.array([-e[1], e[0]])


def rocker_angles(q):
    """(theta3, theta4) [rad] at crank angle q, by two circle intersections: b left of a -> O2
    and d right of c -> O3 (the scene's sketch: b and d above the frame line)."""
    a = O1 + CRANK * np.array([math.cos(q), math.sin(q)])
    b = circle_meet(a, LINK1, O2, ARM_B, +1)
    t3 = math.atan2(*(b - O2)[::-1])
    c = O2 + ARM_C * np.array([math.cos(t3 - math.radians(20)), math.sin(t3 - math.radians(20))])
    d = circle_meet(c, LINK2, O3, ROCKER2, -1)
    return t3, math.atan2(*(d - O3)[::-1])


def test_wiper_output_torques_at_80_N_m_against_a_hand_loop_closure():
    """T3 = T2 / K3 and T4 = T2 / K4 at rest (virtual work), with K from central differences
    of the closure above (step 1e-6 rad: truncation ~1e-12, rounding ~1e-10 relative).
    Tolerance 1e-6: well above both, far below any modelling difference (O3 at 521 mm and 172 deg
    exactly, not rounded to the scene's micrometre, moves T4 by 1e-5)."""
    scene = load_scene(WIPER)
    curve = output_study(scene, 0.0, poses=12)  # 0, 30, ..., 330 deg
    h = 1e-6
    for i, q in enumerate(curve.q):
        t3p, t4p = rocker_angles(q + h)
        t3m, t4m = rocker_angles(q - h)
        k3 = math.remainder(t3p - t3m, 2 * math.pi) / (2 * h)
        k4 = math.remainder(t4p - t4m, 2 * math.pi) / (2 * h)
        assert curve.torques[i, 0] == pytest.approx(80.0 / k3, rel=1e-6), math.degrees(q)
        assert curve.torques[i, 1] == pytest.approx(80.0 / k4, rel=1e-6), math.degrees(q)
        assert curve.ratios["T[rocker2]/T[rocker1]"][i] == pytest.approx(k3 / k4, rel=1e-6)


def test_losses_scale_the_static_torques_as_the_model_states():
    """At rest: T3 = eta T2/K3, T4 = eta^2 (1 - m) T2/K4 (rocker 1's bearing, its blade, rocker
    2's bearing), to rounding."""
    scene = load_scene(WIPER)
    lossless = output_study(scene, 0.0, poses=24)
    lossy = output_study(scene, 0.0, poses=24,
                         spec=with_inputs(scene.kinetostatics, friction=0.4, efficiency=0.7))
    np.testing.assert_allclose(lossy.torques[:, 0], 0.7 * lossless.torques[:, 0], rtol=1e-10)
    np.testing.assert_allclose(lossy.torques[:, 1], 0.7**2 * 0.6 * lossless.torques[:, 1],
                               rtol=1e-10)
    np.testing.assert_allclose(lossy.friction_torque, 0.4 * np.abs(lossy.torques[:, 0]),
                               rtol=1e-10)


def test_dead_points_are_the_rockers_limit_positions_and_no_peak_sits_on_one():
    """The dead points are where the rockers stop (``flexlink kinematics``: 4.857 and 182.305
    deg); every peak reported as a result lies outside the dead-point band, and the sampled
    values inside it are only named as samples beside their dead point."""
    scene = load_scene(WIPER)
    curve = output_study(scene, 0.0)
    angles = sorted(curve.dead_point_angles())
    assert angles == pytest.approx([4.857, 182.305], abs=1e-3)
    deg = np.degrees(curve.q) % 360
    for p in curve.peaks():
        i = int(np.argmin(np.abs(deg - p.at_deg)))
        bounded = p.name == "T[rocker2]/T[rocker1]"
        assert bounded or not curve.near[i], p
        if p.near_value is not None:
            assert p.dead_point_deg in angles and abs(p.near_value) > abs(p.value)


def test_split_sharing_gives_each_output_its_share_of_the_power_at_rest():
    """'split' with share s: T3 K3 = s T2 and T4 K4 = (1 - s) T2 at rest without losses."""
    scene = load_scene(WIPER, {"kinetostatics.sharing": "split", "kinetostatics.share": 0.3})
    curve = output_study(scene, 0.0, poses=24)
    ok = ~curve.near
    np.testing.assert_allclose((curve.torques[:, 0] * curve.K[:, 0])[ok], 0.3 * 80, rtol=1e-9)
    np.testing.assert_allclose((curve.torques[:, 1] * curve.K[:, 1])[ok], 0.7 * 80, rtol=1e-9)


def test_input_torque_from_a_csv_over_the_crank_angle(tmp_path):
    """A CSV input torque is interpolated periodically; the output follows it linearly at rest."""
    rows = "\n".join(f"{a},{80 + 20 * math.sin(math.radians(a))}" for a in range(0, 360, 10))
    (tmp_path / "t.csv").write_text("crank_angle_deg,torque\n" + rows + "\n")
    path = tmp_path / "w.toml"
    own = WIPER.read_text().split("[kinetostatics]")[0]
    path.write_text(own + '[kinetostatics]\ncsv = "t.csv"\nunit = "N*m"\n'
                    'outputs = ["rocker1", "rocker2"]\n')
    scene = load_scene(path)
    curve = output_study(scene, 0.0, poses=36)
    expected = 80 + 20 * np.sin(curve.q)
    np.testing.assert_allclose(curve.input_torque, expected, rtol=1e-12)
    constant = output_study(load_scene(WIPER), 0.0, poses=36)
    np.testing.assert_allclose(curve.torques, constant.torques * (expected / 80)[:, None],
                               rtol=1e-9)


def test_extended_rocker_k_family_shares_its_quasi_static_driving_torque():
    """With L41 and the swing fixed the k family has one angular motion, and the tip force's
    torque about the pivot (100 N x L41) is the same for every k: so at a crawl (inertia
    ~ Omega^2, 1e-12 of the tip torque at 1e-3 rad/s) the driving torque -100 N L41 K4 agrees
    across k to 1e-9; at 2000 rev/min the members differ by their links' inertia only."""
    from flexlink.studies.kinetostatics.families import family_torques

    path = SCENES_DIR / "extended_rocker_torque.toml"
    scene = load_scene(path)
    slow = [m for m in family_torques(path, scene, 1e-3, poses=36).members
            if m.field == "linkage.synthesis.k"]
    assert [m.value for m in slow] == [0.8, 1.0, 1.2]
    for m in slow:
        assert m.summary["peak_torque_N_m"] == pytest.approx(
            slow[1].summary["peak_torque_N_m"], rel=1e-9)
        assert m.pivot_inertia["rocker"] > 0
    # the tip torque times the rocker's largest |K| (0.2755 on this 36-pose grid or finer)
    assert abs(slow[1].summary["peak_torque_N_m"]) == pytest.approx(10.0 * 0.2755, rel=2e-2)
