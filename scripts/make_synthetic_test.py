"""Write a SYNTHETIC modal test of Table II case 3 (Timoshenko links) as a UFF file.

Nothing here was measured. The "test structure" is the scene
scenes/tests/case3_timoshenko.toml perturbed the way a real prototype differs from its model:
    - a point mass of 2 g on the coupler at 3/8 of its length from A (an accelerometer and
      its mount),
    - the crank's ground bearing O2 three times stiffer (Kt 3e6 N/m instead of 1e6),
    - a 3 % lower Young's modulus of every link.
The mass drops the coupler's fourth bending mode (791 Hz in the model) below the rocker's
second (776 Hz in the model): a pair of close modes whose order the test swaps.
Its modes are computed on a fine mesh (48 elements per link, three times the model's 16), read
at nodes of that mesh that are not nodes of the model's mesh (so no sensor sits where the
model's own nodal values are), in the directions of a test frame turned 30 deg from the
scene's and shifted by (50, -20) mm, and given 2 % Gaussian noise (standard deviation 2 % of
each mode's RMS reading, seeded). Damping ratios are set to 0.5 % (not computed). The file
holds datasets 164 (mm), 15 (geometry, or 2411 with --geometry 2411) and one 55 per mode,
written by pyuff.

It reads the perturbed model's nodal displacements directly: no flexlink code that places
sensors or interpolates shapes is used, so a correlation of this file with the model checks
that code against an independent reading.

    python scripts/make_synthetic_test.py [--out scenes/tests/case3_synthetic.uff]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "tests" / "case3_timoshenko.toml"
PERTURBATION = {"joints.O2.Kt": "3e6 N/m"}
MODULUS_FACTOR = 0.97
POINT_MASS = 0.002  # [kg] on the coupler
POINT_MASS_AT = 3 / 8  # of the coupler's length from its first joint
FINE = 48  # elements per link of the "test structure"
MODEL = 16  # the model's mesh, whose nodes the sensors avoid
MODES = 8
NOISE = 0.02
FRAME_ROTATION = math.radians(30.0)
FRAME_OFFSET = np.array([0.050, -0.020])  # [m]
SENSORS_PER_LINK = {"crank": 4, "coupler": 10, "rocker": 6}
DAMPING = 0.005


# For the calibration check: a test structure that differs from the model only in inputs
# `flexlink calibrate --free` can fit (every bearing three times stiffer, 3 g on every pin).
CALIBRATION_PERTURBATION = {"joints.Kt": "3e6 N/m", "joints.O2.mass": "3 g",
                            "joints.A.mass": "3 g", "joints.B.mass": "3 g",
                            "joints.O4.mass": "3 g"}


def truth_modes(scene_path=SCENE, modes=MODES, calibration: bool = False):
    """(model, frequencies [Hz], shapes (n_dofs, modes)) of the perturbed scene, fine mesh;
    ``calibration``: the perturbation of scene inputs only (CALIBRATION_PERTURBATION)."""
    import functools

    from flexlink.analysis.solve import lowest_elastic, solve_modes
    from flexlink.fe.assembly import assemble, rigid_elimination
    from flexlink.fe.model_at_pose import in_plane_eigen_scale, pose_model
    from flexlink.scene import load_scene

    scene = load_scene(scene_path, overrides=CALIBRATION_PERTURBATION if calibration
                       else PERTURBATION)
    topology = scene.topology(FINE)
    if not calibration:
        links = tuple(dataclasses.replace(l, section=dataclasses.replace(
            l.section, E=MODULUS_FACTOR * l.section.E)) for l in topology.links)
        topology = dataclasses.replace(topology, links=links)
    model = pose_model(topology, scene.rigid_pose().joints, warn=False)
    if not calibration:
        coupler = next(l for l in model.links if l.name == "coupler")
        node = coupler.first_node + round(POINT_MASS_AT * FINE)
        model = dataclasses.replace(model, point_masses=model.point_masses
                                    + ((node, POINT_MASS),))
    K, M = assemble(model)
    result = lowest_elastic(functools.partial(
        solve_modes, K, M, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model)),
        modes)
    chosen = result.elastic[:modes]
    return model, result.frequencies[chosen], result.shapes[:, chosen]


def sensor_nodes(model) -> list[int]:
    """Fine-mesh nodes spread along each link, none on a node of the model's mesh."""
    step = FINE // MODEL
    out = []
    for link in model.links:
        inner = [i for i in range(1, FINE) if i % step]
        picks = np.linspace(0, len(inner) - 1, SENSORS_PER_LINK[link.name]).round().astype(int)
        out += [int(link.first_node + inner[i]) for i in picks]
    return out


def synthetic_test(seed: int = 7, scene_path=SCENE, calibration: bool = False):
    """(test-frame coordinates (P, 3) [mm], readings (P, 3, modes) along the test frame's
    X, Y, Z, frequencies [Hz]) of the synthetic test (``calibration``: of the calibration
    check's structure)."""
    model, freqs, shapes = truth_modes(scene_path, calibration=calibration)
    nodes = sensor_nodes(model)
    c, s = math.cos(FRAME_ROTATION), math.sin(FRAME_ROTATION)
    to_test = np.array([[c, s], [-s, c]])  # scene -> test frame (the inverse rotation)
    xy = (model.nodes[nodes] - FRAME_OFFSET) @ to_test.T
    scene_disp = shapes.reshape(-1, 3, shapes.shape[1])[nodes][:, :2, :]  # (P, 2, k) ux, uy
    test_disp = np.einsum("ij,pjk->pik", to_test, scene_disp)
    rng = np.random.default_rng(seed)
    rms = np.sqrt(np.mean(test_disp**2, axis=(0, 1)))
    test_disp = test_disp + NOISE * rms * rng.standard_normal(test_disp.shape)
    readings = np.concatenate([test_disp, np.zeros((len(nodes), 1, shapes.shape[1]))], axis=1)
    coordinates = np.column_stack([xy * 1e3, np.zeros(len(nodes))])
    return coordinates, readings, freqs


def write_uff(path, coordinates, readings, frequencies, geometry: int = 15) -> None:
    """The test as UFF datasets 164, 15 (or 2411) and 55, by pyuff."""
    import pyuff

    labels = np.arange(1, len(coordinates) + 1)
    zeros = [0] * len(labels)
    units = pyuff.prepare_164(units_code=3, units_description="mm (synthetic test)",
                              temp_mode=1, length=1000.0, force=1.0, temp=1.0,
                              temp_offset=273.15)
    prepare = pyuff.prepare_15 if geometry == 15 else pyuff.prepare_2411
    points = prepare(node_nums=labels.tolist(), def_cs=zeros, disp_cs=zeros, color=zeros,
                     x=coordinates[:, 0].tolist(), y=coordinates[:, 1].tolist(),
                     z=coordinates[:, 2].tolist())
    sets = [units, points]
    for k, f in enumerate(frequencies):
        sets.append(pyuff.prepare_55(
            id1="SYNTHETIC modal test, not measured (scripts/make_synthetic_test.py)",
            id2="Table II case 3, Timoshenko; coupler +2 g, O2 Kt x3, E -3 %, 2 % noise",
            id4=f"mode {k + 1}", model_type=1, analysis_type=2, data_ch=2, spec_data_type=8,
            data_type=2, n_data_per_node=3, r1=readings[:, 0, k], r2=readings[:, 1, k],
            r3=readings[:, 2, k], load_case=1, mode_n=k + 1, freq=float(f), modal_m=0.0,
            modal_damp_vis=DAMPING, modal_damp_his=0.0, node_nums=labels))
    path = Path(path)
    if path.exists():
        path.unlink()
    pyuff.UFF(str(path)).write_sets(sets, mode="overwrite")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "scenes" / "tests" / "case3_synthetic.uff"))
    parser.add_argument("--geometry", type=int, choices=(15, 2411), default=15)
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    coordinates, readings, freqs = synthetic_test(args.seed)
    write_uff(args.out, coordinates, readings, freqs, args.geometry)
    print(f"wrote {args.out}: {len(coordinates)} sensors, modes at "
          + ", ".join(f"{f:.2f}" for f in freqs) + " Hz (synthetic)")


if __name__ == "__main__":
    main()
