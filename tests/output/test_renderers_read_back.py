"""Every renderer of output/ read back by name: each CSV column (by its header) and each JSON
number (by its key) against the result it renders, converted here to the unit its label
names (deg, rev/min, Hz, N m, ...), so a swapped column, a unit written as another or a label
that says the wrong unit fails.

The results are small and hand-made, with values that differ from column to column (a
swap cannot pass), except where a renderer needs a real model (its tests run in seconds).
A CSV cell keeps the significant digits its format prints, so a column is compared to half a
unit in its last printed digit; a JSON number is the float itself (Python's repr round-trips),
so to round-off of the unit conversion (1e-15 relative).
"""

from __future__ import annotations

import dataclasses
import json
import math
from types import SimpleNamespace

import numpy as np
import pytest

from flexlink.commands._options import dumps
from flexlink.studies.cycle.bands import Band, CriticalSpeed
from flexlink.studies.cycle.modal_map import ModalMap
from flexlink.studies.cycle.tracking import TrackedMap, Tracks
from flexlink.studies.running.dynamic_campbell import DynamicCampbell
from flexlink.studies.running.stability_map import InstabilityRange, Integrator, StabilityMap
from flexlink.studies.running.steady_response import ResponseSweep, StrainPoint, SteadyResponse
from flexlink.studies.running.torque import TorqueCurve

from contents import csv_columns

DEG = 180 / math.pi  # [deg] per [rad]
REV_MIN = 60 / (2 * math.pi)  # [rev/min] per [rad/s], written out for the oracle
# a JSON number is the float itself, except a speed in rev/min within 8 ulps of a 12-digit
# decimal, which units.rev_per_min rounds to it (a speed given in rev/min reads back as
# written): 8 ulps, 1.8e-15 relative
JSON_RTOL = 2e-15
RNG = np.random.default_rng(7)
Q = np.sort(RNG.uniform(0, 2 * math.pi, 7))  # crank angles [rad]


def spread(*shape, low=1.0, high=100.0) -> np.ndarray:
    """Distinct positive values: no two columns can be swapped unseen."""
    return RNG.uniform(low, high, shape)


@dataclasses.dataclass
class Rendered:
    """A renderer's output and what each of its named fields must hold: ``columns`` (CSV
    header -> (expected values, significant digits printed, or None for fixed decimals given
    as -places)), ``rows`` (the first cell of a row that precedes the data, such as a mode
    table's "frequency [Hz]" -> (its numbers, digits)), ``numbers`` (JSON path -> expected
    value(s))."""

    csv: str | None = None
    columns: dict = dataclasses.field(default_factory=dict)
    rows: dict = dataclasses.field(default_factory=dict)  # a labelled row -> (values, digits)
    document: dict | None = None
    numbers: dict = dataclasses.field(default_factory=dict)


def _modal_map() -> Rendered:
    from flexlink.output.cycle.modal_map import modal_map_csv

    f = spread(len(Q), 3)
    result = ModalMap("synthetic", Q, f, np.zeros(len(Q), int), {})
    return Rendered(csv=modal_map_csv(result),
                    columns={"crank_angle_deg": (Q * DEG, 6),
                             **{f"f{j + 1}_Hz": (f[:, j], 8) for j in range(3)}})


def _tracked() -> Rendered:
    from flexlink.output.cycle.tracking import tracked_csv

    f, mac = spread(len(Q), 2), RNG.uniform(0.5, 1.0, (len(Q), 2))
    tracks = Tracks(frequencies=f, shapes=tuple(np.eye(3)[:, :2] for _ in Q), mac=mac,
                    rank=np.tile(np.arange(2), (len(Q), 1)), events=())
    result = TrackedMap(scene="synthetic", q=Q, frequencies=f, tracks=tracks, mu90={},
                        labels=("a", "b"), mechanism_counts=np.zeros(len(Q), dtype=int))
    return Rendered(csv=tracked_csv(result),
                    columns={"crank_angle_deg": (Q * DEG, 6), "f1_Hz": (f[:, 0], 8),
                             "f2_Hz": (f[:, 1], 8), "mac1": (mac[:, 0], -6),
                             "mac2": (mac[:, 1], -6)})


def _critical() -> Rendered:
    from flexlink.output.cycle.campbell import critical_csv

    bands = [Band(1, 9.5, 11.25), Band(2, 29.75, 31.5)]
    critical = [CriticalSpeed(mode=2, harmonic=3, low=61.3, high=64.9),
                CriticalSpeed(mode=1, harmonic=1, low=59.1, high=70.2)]
    return Rendered(csv=critical_csv(critical, bands), columns={
        "mode": (np.array([2, 1]), 0), "band_min_Hz": (np.array([29.75, 9.5]), 8),
        "band_max_Hz": (np.array([31.5, 11.25]), 8), "harmonic": (np.array([3, 1]), 0),
        "from_rev_per_min": (np.array([61.3, 59.1]) * REV_MIN, 6),
        "to_rev_per_min": (np.array([64.9, 70.2]) * REV_MIN, 6)})


def _stability() -> Rendered:
    from flexlink.output.running.stability_map import stability_csv, stability_document

    speeds = np.sort(spread(5, low=50.0, high=400.0))
    modulus, rate, floor = spread(5, low=0.5, high=2.0), spread(5, low=-3, high=3), spread(5)
    ranges = (InstabilityRange(speeds[1], speeds[2], (1, 2), 3, "combination", 1.75),)
    result = StabilityMap(speeds, modulus, rate, ranges, floor, Integrator.ADIABATIC,
                          np.array([False, True, False, False, True]))
    model = SimpleNamespace(basis=None, damping_ratio=np.array([0.01, 0.02]),
                            damping_source="given", angles=np.zeros(9),
                            frequencies=np.array([12.5, 31.25]))
    return Rendered(
        csv=stability_csv(result),
        columns={"speed_rev_per_min": (speeds * REV_MIN, 6), "largest_modulus": (modulus, 10),
                 "growth_rate_per_s": (rate, 10), "stiffness_floor_rad2_per_s2": (floor, 6)},
        document=stability_document("synthetic", result, model),
        numbers={("speeds_rev_per_min",): speeds * REV_MIN, ("largest_modulus",): modulus,
                 ("growth_rate_per_s",): rate, ("stiffness_floor_rad2_per_s2",): floor,
                 ("magnus_fallback_rev_per_min",): speeds[[1, 4]] * REV_MIN,
                 ("basis_frequencies_Hz",): [12.5, 31.25], ("damping_ratio",): [0.01, 0.02],
                 ("instability_ranges", 0, "from_rev_per_min"): speeds[1] * REV_MIN,
                 ("instability_ranges", 0, "to_rev_per_min"): speeds[2] * REV_MIN,
                 ("instability_ranges", 0, "largest_growth_rate_per_s"): 1.75,
                 ("instability_ranges", 0, "harmonic"): 3, ("instability_ranges", 0, "modes"): [1, 2]})


def _forced_model(points):
    periodic = SimpleNamespace(damping_ratio=np.array([0.01, 0.03]), damping_source="given",
                               frequencies=np.array([21.0, 57.0]), load_vectors=0)
    # half depths [m] of the links: the made-up deflections stay small against them
    return SimpleNamespace(points=points, periodic=periodic,
                           half_depth=np.full(len(points), 0.5))


POINTS = (StrainPoint("coupler", 0.0625), StrainPoint("rocker", 0.1))


def _response() -> Rendered:
    from flexlink.output.running.steady_response import response_csv, response_document

    strain, deflection = spread(len(Q), 2, low=-1e-4, high=1e-4), spread(len(Q), 2, low=-1e-3,
                                                                          high=1e-3)
    response = SteadyResponse(speed=123.4, angles=Q, deflection=deflection, strain=strain,
                              largest_modulus=0.875)
    model = _forced_model(POINTS)
    columns = {"crank_deg": (Q * DEG, -4)}
    numbers = {("speed_rev_per_min",): 123.4 * REV_MIN, ("largest_modulus",): 0.875,
               ("crank_deg",): Q * DEG, ("basis_frequencies_Hz",): [21.0, 57.0]}
    for k, p in enumerate(POINTS):
        columns[f"{p.label} strain"] = (strain[:, k], 10)
        columns[f"{p.label} deflection_m"] = (deflection[:, k], 10)
        numbers[("points", k, "position_m")] = p.position
        numbers[("points", k, "strain")] = strain[:, k]
        numbers[("points", k, "deflection_m")] = deflection[:, k]
        numbers[("points", k, "peak_strain")] = np.abs(strain[:, k]).max()
        numbers[("points", k, "peak_deflection_m")] = np.abs(deflection[:, k]).max()
        numbers[("points", k, "peak_strain_at_deg")] = Q[np.argmax(np.abs(strain[:, k]))] * DEG
    return Rendered(csv=response_csv(response, model), columns=columns,
                    document=response_document("synthetic", response, model), numbers=numbers)


def _sweep() -> Rendered:
    from flexlink.output.running.steady_response import sweep_csv, sweep_document

    speeds = np.sort(spread(4, low=10.0, high=300.0))
    strain, deflection = spread(4, 2, low=1e-6, high=1e-4), spread(4, 2, low=1e-5, high=1e-3)
    modulus = spread(4, low=0.2, high=0.9)
    sweep = ResponseSweep(speeds=speeds, points=POINTS, peak_strain=strain,
                          peak_deflection=deflection, largest_modulus=modulus)
    columns = {"speed_rev_per_min": (speeds * REV_MIN, 6), "largest_modulus": (modulus, 10)}
    numbers = {("speeds_rev_per_min",): speeds * REV_MIN, ("largest_modulus",): modulus}
    for k, p in enumerate(POINTS):
        columns[f"{p.label} peak_strain"] = (strain[:, k], 10)
        columns[f"{p.label} peak_deflection_m"] = (deflection[:, k], 10)
        numbers[("points", k, "peak_strain")] = strain[:, k]
        numbers[("points", k, "peak_deflection_m")] = deflection[:, k]
    model = _forced_model(POINTS)
    return Rendered(csv=sweep_csv(sweep), columns=columns,
                    document=sweep_document("synthetic", sweep, model), numbers=numbers)


def _torque() -> Rendered:
    from flexlink.output.running.torque import torque_csv, torque_document

    n = len(Q)
    forces = {"A:coupler": spread(n, 2, low=-50, high=50), "O2:crank": spread(n, 2, low=-9, high=9)}
    torque, power = spread(n, low=-2, high=3), spread(n, low=-20, high=30)
    energy, load = spread(n, low=0.1, high=0.5), spread(n, low=-1, high=1)
    curve = TorqueCurve(scene="synthetic", speed=31.5, crank_acceleration=2.5, q=Q,
                        torque=torque, power=power, kinetic_energy=energy, load_power=load,
                        forces=forces, masses=(), singular=np.zeros(len(Q), dtype=bool))
    columns = {"crank_angle_deg": (Q * DEG, 10), "torque_N_m": (torque, 10),
               "power_W": (power, 10), "kinetic_energy_J": (energy, 10),
               "load_power_W": (load, 10)}
    numbers = {("crank_speed_rad_s",): 31.5, ("crank_speed_rev_per_min",): 31.5 * REV_MIN,
               ("crank_acceleration_rad_s2",): 2.5, ("mean_torque_N_m",): torque.mean(),
               ("max_torque_N_m",): torque.max(), ("min_torque_N_m",): torque.min(),
               ("mean_power_W",): power.mean(),
               ("max_torque_at_deg",): (Q[np.argmax(torque)] * DEG) % 360}
    for key, f in forces.items():
        magnitude = np.hypot(f[:, 0], f[:, 1])
        columns[f"{key}_Fx_N"], columns[f"{key}_Fy_N"] = (f[:, 0], 10), (f[:, 1], 10)
        columns[f"{key}_F_N"] = (magnitude, 10)
        numbers[("joint_forces", key, "peak_N")] = magnitude.max()
        numbers[("joint_forces", key, "at_deg")] = (Q[np.argmax(magnitude)] * DEG) % 360
    return Rendered(csv=torque_csv(curve), columns=columns,
                    document=torque_document(curve, ()), numbers=numbers)


def _dynamic() -> Rendered:
    from flexlink.output.running.dynamic_campbell import dynamic_csv, dynamic_json

    speeds = np.sort(spread(3, low=10.0, high=300.0))
    f = spread(3, len(Q), 2)
    result = DynamicCampbell(scene="synthetic", q=Q, speeds=speeds, frequencies=f,
                             static=f[0], basis=5, crank_acceleration=1.5)
    low, high = f.min(axis=1), f.max(axis=1)
    columns = {"rev_per_min": (speeds * REV_MIN, 6)}
    numbers = {("crank_acceleration_rad_s2",): 1.5, ("basis_static_modes",): 5}
    for j in range(2):
        columns[f"mode{j + 1}_min_Hz"] = (low[:, j], 8)
        columns[f"mode{j + 1}_max_Hz"] = (high[:, j], 8)
    for k in range(3):
        numbers[("bands_at_speed", k, "rev_per_min")] = speeds[k] * REV_MIN
        numbers[("bands_at_speed", k, "min_Hz")] = low[k]
        numbers[("bands_at_speed", k, "max_Hz")] = high[k]
    return Rendered(csv=dynamic_csv(result), columns=columns,
                    document=dynamic_json(result, []), numbers=numbers)


def _motion() -> Rendered:
    from flexlink.output.cycle.rigid_motion import motion_csv

    names = ("crank", "coupler", "rocker")
    angles, K, L = spread(len(Q), 3, low=-3, high=3), spread(len(Q), 3), spread(len(Q), 3)
    cycle = SimpleNamespace(body_names=names, q=Q, angles=angles, K=K, L=L)
    w = 12.5
    columns = {"crank_angle_deg": (Q * DEG, 10)}
    for j, b in enumerate(names):
        # a body named "crank" would repeat the crank angle's header: its own is renamed
        angle = f"{b}_body_angle_deg" if f"{b}_angle_deg" == "crank_angle_deg" else f"{b}_angle_deg"
        columns[angle] = (angles[:, j] * DEG, 10)
        columns[f"{b}_K"], columns[f"{b}_L"] = (K[:, j], 10), (L[:, j], 10)
        columns[f"{b}_omega_rad_s"] = (K[:, j] * w, 10)
        columns[f"{b}_alpha_rad_s2"] = (L[:, j] * w * w, 10)
    return Rendered(csv=motion_csv(cycle, w), columns=columns)


def _mac() -> Rendered:
    from flexlink.output.pose.mac_comparison import mac_csv

    mac = RNG.uniform(0, 1, (3, 2))
    return Rendered(csv=mac_csv(SimpleNamespace(mac=mac)),
                    columns={"mode_a": (np.arange(1, 4), 0), "b1": (mac[:, 0], -6),
                             "b2": (mac[:, 1], -6)})


def _convergence() -> Rendered:
    from flexlink.output.verification.convergence import convergence_csv, convergence_document
    from flexlink.studies.verification.convergence import (CHOICES, ConvergenceStudy, Level,
                                                           relative_errors, richardson)

    levels = [Level(CHOICES[0], e, 3 * e + 9, 1e-3 * e, 2e-3 * e,
                    np.array([10 + e**-2.0, 25 + 3 * e**-2.0])) for e in (1, 2, 4)]
    ext = richardson(levels)
    errors = relative_errors(levels, ext.reference)
    study = ConvergenceStudy(scene="synthetic", file="synthetic.toml", n_modes=2, repeats=1,
                             tol=1e-6, levels=tuple(levels), extrapolation=ext, errors=errors,
                             cheapest=None, measured=None)
    f = np.array([lv.frequencies for lv in levels])
    numbers = {}
    for i, lv in enumerate(levels):
        numbers[("levels", i, "frequencies_Hz")] = lv.frequencies
        numbers[("levels", i, "relative_error")] = errors[i]
        numbers[("levels", i, "assembly_s")] = lv.assembly_s
        numbers[("levels", i, "solve_s")] = lv.solve_s
    return Rendered(csv=convergence_csv(study), columns={
        "elements_per_link": (np.array([1, 2, 4]), 0), "dofs": (np.array([12, 15, 21]), 0),
        "assembly_s": (1e-3 * np.array([1, 2, 4]), 6), "solve_s": (2e-3 * np.array([1, 2, 4]), 6),
        "f1_Hz": (f[:, 0], 15), "f2_Hz": (f[:, 1], 15),
        "err1": (errors[:, 0], 4), "err2": (errors[:, 1], 4)},
        document=convergence_document(study), numbers=numbers)


def _case1():
    from flexlink.scene import load_scene

    from conftest import CASES_DIR
    return load_scene(CASES_DIR / "case1.toml")


def _modes() -> Rendered:
    from flexlink.output.pose.scene_summary import comparison_csv, summary_document
    from flexlink.studies.pose.scene_summary import scene_summary

    from conftest import CASES_DIR
    summary = scene_summary(CASES_DIR / "case1.toml", 3, 4)
    f, identity = summary.frequencies, summary.identity
    columns = {"mode": (np.arange(1, 4), 0), "computed_Hz": (f, 15)}
    numbers = {}
    for i in range(3):
        numbers[("modes", i, "computed_Hz")] = f[i]
    for name, values in summary.reference.items():
        ref = np.array(values[:3], dtype=float)
        columns[f"{name}_Hz"] = (ref, 15)
        columns[f"error_vs_{name}_pct"] = (100 * (f - ref) / ref, 13)  # computed vs reference
    for k, axis in enumerate(("x", "y")):
        columns[f"m_eff_{axis}_kg"] = (identity.effective_mass[:3, k], 15)
    for p, part in enumerate(identity.parts):
        columns[f"strain_{part}"] = (identity.strain[:3, p], 15)
        columns[f"kinetic_{part}"] = (identity.kinetic[:3, p], 15)
    return Rendered(csv=comparison_csv([summary]), columns=columns,
                    document=summary_document(summary), numbers=numbers)


def _at_speed() -> Rendered:
    from flexlink.output.running.modes_at_speed import (operating_csv, operating_document,
                                                        operating_summary)
    from flexlink.studies.running.modes_at_speed import operating_modes

    speed = 2000 / REV_MIN
    op = operating_modes(_case1(), speed, 2, 4)
    summary = operating_summary(op)
    f, static = op.frequencies, op.static_frequencies
    columns = {"speed_rev_per_min": (np.full(2, 2000.0), 10),
               "crank_angle_deg": (np.full(2, op.motion.q * DEG), 10),
               "mode": (np.arange(1, 3), 0), "frequency_Hz": (f, 10), "static_Hz": (static, 10),
               "change_Hz": (f - static, 10), "change_pct": (100 * (f - static) / static, 10),
               "growth_rate_1_s": (op.modes.growth_rates, 10), "mac": (op.mac, -6),
               "static_mode": (op.static_index + 1, 0)}
    numbers = {("cases", 0, "speed_rad_s"): speed, ("cases", 0, "speed_rev_per_min"): 2000.0,
               ("cases", 0, "crank_angle_deg"): op.motion.q * DEG}
    for i in range(2):
        numbers[("cases", 0, "modes", i, "frequency_Hz")] = f[i]
        numbers[("cases", 0, "modes", i, "static_Hz")] = static[i]
    for link, w, a in zip(op.axial_forces, op.link_omega, op.link_alpha):
        numbers[("cases", 0, "links", link, "omega_rad_s")] = w
        numbers[("cases", 0, "links", link, "alpha_rad_s2")] = a
    return Rendered(csv=operating_csv([summary]), columns=columns,
                    document=operating_document([summary], {}), numbers=numbers)


def _mac_matrix() -> Rendered:
    from flexlink.output.correlation.correlation import mac_matrix_csv

    mac = RNG.uniform(0, 1, (2, 3))
    c = SimpleNamespace(correlation=SimpleNamespace(mac=mac))
    return Rendered(csv=mac_matrix_csv(c), columns={
        "test_mode": (np.arange(1, 3), 0),
        **{f"model{j + 1}": (mac[:, j], -6) for j in range(3)}})


def _pairs() -> Rendered:
    from flexlink.output.correlation.correlation import pairs_csv

    pairs = [{"test": t, "test_Hz": th, "model": m, "model_Hz": mh,
              "error_pct": 100 * (mh - th) / th, "mac": mac, "quality": "good",
              "test_damping": z, "scale": scale}
             for t, th, m, mh, mac, z, scale in ((1, 31.25, 2, 33.5, 0.97, 0.012, 1.5e-3),
                                                 (2, 88.125, 1, 86.0, 0.91, 0.021, -2.25e-3))]
    column = {key: np.array([p[key] for p in pairs], dtype=float) for key in pairs[0]
              if key != "quality"}
    return Rendered(csv=pairs_csv({"pairs": pairs}), columns={
        "test_mode": (column["test"], 0), "model_mode": (column["model"], 0),
        "test_Hz": (column["test_Hz"], -6), "model_Hz": (column["model_Hz"], -6),
        "error_pct": (column["error_pct"], -4), "mac": (column["mac"], -6),
        "test_damping": (column["test_damping"], 6), "scale": (column["scale"], 6)})


def _shapes() -> Rendered:
    from flexlink.output.correlation.measured import shapes_csv
    from flexlink.studies.correlation.correlation import ModesAtPoints

    values = spread(2, 3, 2, low=-1, high=1)
    values[1, 2] = 0.0  # a direction read in no mode: no row
    coordinates, f, damping = spread(2, 3, low=-50, high=50), np.array([12.5, 40.25]), [0.01, 0.02]
    shapes = ModesAtPoints(np.array([3, 7]), coordinates, values, f, "mm")
    rows = [(i, axis) for i in range(2) for axis in range(3) if values[i, axis].any()]
    columns = {"sensor": (np.array([[3, 7][i] for i, _ in rows]), 0)}
    for k, name in enumerate(("x [mm]", "y [mm]", "z [mm]")):
        columns[name] = (np.array([coordinates[i, k] for i, _ in rows]), 9)
    for k, name in enumerate(("dx", "dy", "dz")):
        columns[name] = (np.array([float(axis == k) for _, axis in rows]), 0)
    for j in range(2):
        columns[f"mode {j + 1}"] = (np.array([values[i, axis, j] for i, axis in rows]), 9)
    return Rendered(csv=shapes_csv(shapes, damping), columns=columns,
                    rows={"frequency [Hz]": (f, 9), "damping": (np.array(damping), 6)})


def _layout() -> Rendered:
    from flexlink.output.correlation.sensor_plan import layout_csv
    from flexlink.studies.correlation.sensor_plan import plan_sensors

    plan = plan_sensors(_case1(), 4, 3)  # no [test] table: the scene's frame, in mm
    chosen = plan.chosen
    columns = {"x [mm]": (1e3 * chosen.points[:, 0], 9), "y [mm]": (1e3 * chosen.points[:, 1], 9),
               "z [mm]": (np.zeros(len(chosen.points)), 9)}
    for k, name in enumerate(("dx", "dy", "dz")):
        columns[name] = (chosen.directions[:, k], 9)
    for j in range(3):
        columns[f"mode {j + 1}"] = (chosen.readings[:, j], 9)
    return Rendered(csv=layout_csv(plan), columns=columns,
                    rows={"frequency [Hz]": (plan.modes.frequencies, 9)})


def _stress_field() -> Rendered:
    from flexlink.output.life.life import field_csv

    n, count = len(Q), 4
    points = SimpleNamespace(links=("coupler", "rocker"), link=np.array([0, 0, 1, 1]),
                             element=np.array([1, 2, 1, 3]), end=np.array([0, 1, 1, 0]),
                             position=spread(count, low=0.001, high=0.2),
                             fibre=np.array([0, 1, 1, 0]))
    total, quasi = spread(n, count, low=-1e8, high=1e8), spread(n, count, low=-1e8, high=1e8)
    field = SimpleNamespace(points=points, angles=Q, total=total, quasi_static=quasi,
                            dynamic=total - quasi)
    rows = [(i, k) for i in range(n) for k in range(count)]
    return Rendered(csv=field_csv(SimpleNamespace(field=field)), columns={
        "crank_deg": (np.array([(Q[i] * DEG) % 360 for i, _ in rows]), -4),
        "element": (np.array([points.element[k] for _, k in rows]), 0),
        "end": (np.array([points.end[k] for _, k in rows]), 0),
        "position_m": (np.array([points.position[k] for _, k in rows]), 6),
        "stress_Pa": (np.array([total[i, k] for i, k in rows]), 8),
        "quasi_static_Pa": (np.array([quasi[i, k] for i, k in rows]), 8),
        "dynamic_Pa": (np.array([total[i, k] - quasi[i, k] for i, k in rows]), 8)})


def _compliant() -> Rendered:
    from flexlink.output.life.compliant_cycle import compliant_csv

    n = len(Q)
    fibre = spread(n, 3, 2, low=-2e8, high=2e8)
    prb = SimpleNamespace(clamp_stress=spread(n, 2, low=-2e8, high=2e8),
                          drive_torque=spread(n, low=-1, high=1), Theta=spread(n, low=-0.3, high=0.3))
    cycle = SimpleNamespace(crank_angles=Q, stress=SimpleNamespace(fibre_stress=fibre), prb=prb,
                            reaction=spread(n, low=-1, high=1), energy_torque=spread(n, low=-1, high=1))
    return Rendered(csv=compliant_csv(cycle), columns={
        "crank_angle_deg": (Q * DEG, 10), "fe_clamp_stress_plus_Pa": (fibre[:, 0, 0], 10),
        "fe_clamp_stress_minus_Pa": (fibre[:, 0, 1], 10),
        "prb_clamp_stress_plus_Pa": (prb.clamp_stress[:, 0], 10),
        "prb_clamp_stress_minus_Pa": (prb.clamp_stress[:, 1], 10),
        "fe_strip_peak_Pa": (np.abs(fibre).max(axis=(1, 2)), 10),
        "fe_torque_N_m": (cycle.reaction, 10), "fe_energy_torque_N_m": (cycle.energy_torque, 10),
        "prb_torque_N_m": (prb.drive_torque, 10), "prb_Theta_deg": (prb.Theta * DEG, 10)})


def _output_torques() -> Rendered:
    from flexlink.output.kinetostatics.outputs import outputs_csv

    n = len(Q)
    curve = SimpleNamespace(
        q=Q, outputs=("rocker1", "rocker2"), input_torque=spread(n, low=-90, high=90),
        K=spread(n, 2, low=-2, high=2), torques=spread(n, 2, low=-500, high=500),
        received=spread(n, 2, low=-500, high=500),
        ratios={"TR1": spread(n, low=-9, high=9), "TR2": spread(n, low=-9, high=9)},
        friction_torque=spread(n, low=0, high=5), loss_power=spread(n, low=0, high=50),
        kinetic_energy=spread(n, low=0, high=3),
        forces={"O2": spread(n, 2, low=-1e3, high=1e3)}, near=np.arange(n) % 2 == 0)
    return Rendered(csv=outputs_csv(curve), columns={
        "crank_angle_deg": (Q * DEG, 12), "input_torque_N_m": (curve.input_torque, 12),
        "K_rocker1": (curve.K[:, 0], 12), "T_rocker1_N_m": (curve.torques[:, 0], 12),
        "R_rocker1_N_m": (curve.received[:, 0], 12), "K_rocker2": (curve.K[:, 1], 12),
        "T_rocker2_N_m": (curve.torques[:, 1], 12), "R_rocker2_N_m": (curve.received[:, 1], 12),
        "ratio TR1": (curve.ratios["TR1"], 12), "ratio TR2": (curve.ratios["TR2"], 12),
        "friction_torque_N_m": (curve.friction_torque, 12),
        "loss_power_W": (curve.loss_power, 12), "kinetic_energy_J": (curve.kinetic_energy, 12),
        "O2_Fx_N": (curve.forces["O2"][:, 0], 12), "O2_Fy_N": (curve.forces["O2"][:, 1], 12),
        "O2_F_N": (np.hypot(*curve.forces["O2"].T), 12),
        "near_dead_point": (curve.near.astype(float), 0)})


def _parametric() -> Rendered:
    from flexlink.output.kinetostatics.parametric import parametric_csv
    from flexlink.studies.kinetostatics.parametric import Factor

    levels = {Factor.SPEED: spread(3, low=0, high=3000), Factor.TORQUE: spread(3, low=0, high=1000)}
    sweeps = [SimpleNamespace(factor=f, levels=v, medians={"TR1": spread(3), "TR2": spread(3)})
              for f, v in levels.items()]
    study = SimpleNamespace(base={"TR1": 1.0, "TR2": 2.0}, sweeps=sweeps)
    return Rendered(csv=parametric_csv(study), columns={
        "level": (np.concatenate(list(levels.values())), 6),
        "median |TR1|": (np.concatenate([s.medians["TR1"] for s in sweeps]), 10),
        "median |TR2|": (np.concatenate([s.medians["TR2"] for s in sweeps]), 10)})


def _families() -> Rendered:
    from flexlink.output.kinetostatics.families import families_csv

    names = ("value", "peak_torque_N_m", "peak_torque_at_deg", "max_torque_N_m",
             "min_torque_N_m", "rms_torque_N_m")
    values = {name: spread(4, low=-50, high=50) for name in names}
    members = [{"family": "k", "field": "linkage.synthesis.k",
                **{name: float(values[name][i]) for name in names}} for i in range(4)]
    return Rendered(csv=families_csv({"members": members}),
                    columns={name: (values[name], 10) for name in names})


RENDERERS = {"modal map": _modal_map, "tracked map": _tracked, "critical speeds": _critical,
             "stability map": _stability, "response": _response, "response sweep": _sweep,
             "torque": _torque, "dynamic campbell": _dynamic, "rigid motion": _motion,
             "mac": _mac, "convergence": _convergence, "modes": _modes, "modes at speed": _at_speed,
             "test-model MAC": _mac_matrix, "test-model pairs": _pairs, "mode shapes": _shapes,
             "sensor layout": _layout, "stress field": _stress_field,
             "compliant cycle": _compliant, "output torques": _output_torques,
             "parametric kinetostatics": _parametric, "family torques": _families}


def _at(document, path):
    for key in path:
        document = document[key]
    return document


@pytest.mark.parametrize("renderer", list(RENDERERS))
def test_every_named_field_holds_what_the_result_says_in_the_unit_its_label_names(renderer):
    rendered = RENDERERS[renderer]()
    if rendered.csv is not None:
        lines = rendered.csv.splitlines()
        for label, (expected, digits) in rendered.rows.items():
            [row] = [line.split(",") for line in lines if line.split(",")[0] == label]
            found = np.array([float(c) for c in row[1:] if c != ""])
            np.testing.assert_allclose(found, expected, rtol=0.5 * 10.0 ** (1 - digits),
                                       atol=0, err_msg=label)
        read = csv_columns("\n".join(line for line in lines
                                     if line.split(",")[0] not in rendered.rows))
        assert set(rendered.columns) <= set(read["header"]), set(rendered.columns) - set(
            read["header"])
        for name, (expected, digits) in rendered.columns.items():
            found = np.asarray(read["columns"][name], dtype=float)
            expected = np.asarray(expected, dtype=float)
            if digits == 0:  # integers and unit vectors
                np.testing.assert_array_equal(found, expected, err_msg=name)
            elif digits < 0:  # fixed decimals: half a unit in the last place printed
                np.testing.assert_allclose(found, expected, rtol=0, atol=0.5 * 10.0**digits,
                                           err_msg=name)
            else:  # significant digits
                np.testing.assert_allclose(found, expected, rtol=0.5 * 10.0 ** (1 - digits),
                                           atol=0, err_msg=name)
    if rendered.document is not None:
        document = json.loads(dumps(rendered.document))  # as the commands print and write it
        for path, expected in rendered.numbers.items():
            found = _at(document, path)
            np.testing.assert_allclose(np.asarray(found, dtype=float),
                                       np.asarray(expected, dtype=float), rtol=JSON_RTOL,
                                       atol=0, err_msg="/".join(map(str, path)))


def test_every_csv_renderer_of_output_is_read_back_here():
    # a new CSV renderer joins RENDERERS; the ones rendering a whole command's summaries
    # are read back by their commands' tests (modes, operating, kinematics)
    import importlib
    import pkgutil

    import flexlink.output as output

    found = set()
    for info in pkgutil.walk_packages(output.__path__, "flexlink.output."):
        module = importlib.import_module(info.name)
        found |= {f"{info.name}.{name}" for name in dir(module)
                  if name.endswith("_csv") and not name.startswith("write_")
                  and callable(getattr(module, name))
                  and getattr(module, name).__module__ == info.name}
    covered = {"modal_map_csv", "tracked_csv", "critical_csv", "stability_csv", "response_csv",
               "sweep_csv", "torque_csv", "dynamic_csv", "motion_csv", "mac_csv",
               "convergence_csv", "comparison_csv", "operating_csv", "mac_matrix_csv",
               "pairs_csv", "shapes_csv", "layout_csv", "field_csv", "compliant_csv",
               "outputs_csv", "parametric_csv", "families_csv"}
    assert {name.rsplit(".", 1)[1] for name in found} <= covered, found
