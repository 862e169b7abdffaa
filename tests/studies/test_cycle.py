"""Whole-cycle modal map, resonance check, general scenes and the PRB model: invariants."""

import dataclasses
import math

import numpy as np
import pytest

from flexlink.analysis.modal import analyze
from flexlink.fe.model_at_pose import in_plane_eigen_scale
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.studies.cycle.modal_map import ModalMap, crossings, kinematic_cycle, modal_map, resonances, runs
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model
from flexlink.kinematics.motion import body_summary, limit_positions
from flexlink.studies.pose.prb import prb_frequency
from flexlink.scene import load_scene
from flexlink.analysis.solve import solve_modes

from conftest import ROOT
SCENES = ROOT / "scenes"


def test_modal_map_agrees_with_single_pose_analysis_at_mu_90():
    scene = load_scene(ROOT / "cases" / "case2.toml")
    result = modal_map(scene, n_poses=8, n_modes=3, elements_per_link=4, reduction=None)
    fb = scene.four_bar
    np.testing.assert_allclose(np.sort(result.mu90["coupler/rocker"]),
                               fb.crank_angles_for_mu(math.pi / 2),
                               atol=0.05)  # linear interpolation over 45 deg steps
    # a four-bar's map runs from crank angle 0 (whatever pose the scene analyses): its first
    # row is the single-pose analysis at crank angle 0
    at_zero = dataclasses.replace(scene, start=0.0)
    single = analyze(at_zero, 3, 4).elastic_frequencies(3)
    np.testing.assert_allclose(result.q[0], 0.0, atol=1e-15)
    np.testing.assert_allclose(result.frequencies[0], single, rtol=1e-10)
    # the default map (Craig-Bampton links) is within its stated 1e-6 of the full model
    reduced = modal_map(scene, n_poses=8, n_modes=3, elements_per_link=4)
    np.testing.assert_allclose(reduced.frequencies[0], single, rtol=1e-6)


def test_crossings_and_runs():
    q = np.radians(np.arange(0, 360, 10.0))
    values = np.cos(q)
    np.testing.assert_allclose(np.degrees(crossings(q, values, 0.0)), [90.0, 270.0], atol=1.0)
    step = math.radians(10)
    np.testing.assert_allclose(runs(np.radians([10, 20, 30, 100, 110]), step),
                               np.radians([[10, 30], [100, 110]]))


def test_resonance_check_finds_harmonics_by_construction():
    q = np.radians(np.arange(0, 360, 1.0))
    f1 = 100 + 10 * np.sin(q)  # mode 1 between 90 and 110 Hz
    f2 = np.full_like(q, 305.0)
    m = ModalMap("synthetic", q, np.column_stack([f1, f2]), np.zeros(len(q), int), {})
    omega = 2 * math.pi * 50.0  # 50 Hz crank: harmonic 2 = 100 Hz crosses mode 1, 6 = 300 Hz
    hits = {(h.harmonic, h.mode): h for h in resonances(m, omega, margin=0.02, harmonics=8)}
    assert set(hits) == {(2, 1), (6, 2)}
    assert hits[(2, 1)].closest == 0.0  # crossed
    assert hits[(6, 2)].closest == pytest.approx(5 / 305)
    near = np.degrees(hits[(2, 1)].angles)  # |10 sin q| <= 2 Hz
    assert near.min() == pytest.approx(0.0) and near.max() <= 360
    assert all(abs(10 * math.sin(math.radians(a))) <= 2.0 + 1e-9 for a in near)


def test_wiper_scene_geometry_and_tube_walls():
    scene = load_scene(SCENES / "wiper.toml")
    g = scene.linkage.ground
    assert math.dist(g["O1"], g["O3"]) == pytest.approx(0.092, abs=1e-3)  # the O1O3
    links = {s.name: s for s in scene.links}
    for name, mass, length in (("link1", 0.0882, 0.450), ("link2", 0.1595, 0.517)):
        section = links[name].section
        assert section.mass_per_length * length == pytest.approx(mass, rel=1e-12)
        inner = math.sqrt(section.depth**2 / 4 - section.area / math.pi)
        assert inner == pytest.approx(6.4e-3, rel=1e-9)
    cycle = kinematic_cycle(scene, 90)
    for body in ("rocker1", "rocker2"):  # a wiper: each rocker has exactly two limit positions
        assert len(limit_positions(scene.linkage, cycle, body)) == 2
    state = cycle.states[0]
    assert math.dist(state.points["b"], state.points["c"]) == pytest.approx(0.0178, abs=2e-4)


def test_welded_ground_joint_makes_one_rigid_body():
    # an L-shaped body of two beams welded at a bearing behaves like one body: with the weld,
    # free rotation about the bearing is the only mechanism mode; without it, each arm swings
    steel = Section.rectangle(E=210e9, G=81e9, density=7850.0, width=0.01, thickness=0.005)
    arms = (LinkSpec("a", "P", "O", steel, 6), LinkSpec("b", "O", "Q", steel, 6))
    points = {"P": (-0.3, 0.0), "O": (0.0, 0.0), "Q": (0.0, 0.2)}

    def kinds(welded):
        joints = (JointSpec("P", False, 0.0, 0.0), JointSpec("O", True, math.inf, 0.0,
                                                              welded=welded),
                  JointSpec("Q", False, 0.0, 0.0))
        model = build_model(Topology(arms, joints), points)
        K, M = assemble(model)
        res = solve_modes(K, M, 4, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model))
        return [k for k in res.kinds if k != "elastic"]

    assert len(kinds(True)) == 1 and len(kinds(False)) == 2


def test_extended_rocker_family_unit_time_ratio_only_at_k_1():
    for k, unit in ((0.8, False), (1.0, True), (1.2, False)):
        scene = load_scene(SCENES / "extended_rocker.toml", overrides={"linkage.synthesis.k": k})
        cycle = kinematic_cycle(scene, 72)
        limits = limit_positions(scene.linkage, cycle, "rocker")
        forward = (limits[1].crank_deg - limits[0].crank_deg) % 360
        assert (abs(forward - 180) < 1e-9) == unit
        swing = abs(limits[1].angle_deg - limits[0].angle_deg)
        assert (abs(swing - 30) < 1e-9) == unit
        omega = 2000 * 2 * math.pi / 60
        s = body_summary(cycle, "rocker", omega, output=True)
        assert s.alpha.max == pytest.approx(cycle.L[:, 2].max() * omega**2)


def test_prb_frequency_close_to_fe_with_strip_as_beam():
    scene = load_scene(SCENES / "compliant_wiper.toml")
    state = scene.linkage.solve(scene.start, scene.guess)
    # the strip is straight at this pose: B lies on O4 -> C at gamma l
    O4, B, C = (np.array(state.points[j]) for j in ("O4", "B", "C"))
    assert np.linalg.norm(B - O4) / np.linalg.norm(C - O4) == pytest.approx(0.85, rel=1e-12)
    prb = prb_frequency(scene, state, "strip", "B", "rocker", "coupler", 0.85, 2.65)
    model = build_model(scene.topology(8), state.points)
    K, M = assemble(model)
    fe = solve_modes(K, M, 3, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model))
    assert fe.kinds[0] == "elastic"
    # PRB idealisations: K_Theta = 2.65 is a large-deflection average (small deflection:
    # 3 gamma = 2.55, 4 % lower stiffness), the strip's mass split at the pivot, and the beam
    # model's own compliance of crank and coupler: agreement expected within 10 %
    assert prb.frequency == pytest.approx(fe.frequencies[0], rel=0.10)
