"""Sensor planning (studies/correlation/sensor_plan.py) on a uniform pinned-pinned beam built
as a flexlink model, where the modes and their nodal points are known in closed form, and on a
shipped four-bar."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flexlink.analysis.families import PartModes
from flexlink.analysis.modal import pose_modes
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology
from flexlink.fe.motions import Part
from flexlink.studies.correlation.correlation import ModelModes
from flexlink.studies.correlation.sensor_plan import plan_for_modes, plan_sensors

from conftest import ROOT


def _pinned_beam_modes(n_modes=4):
    """A steel strip 1 m long, pinned at both ends (rigid bearings, free rotation), 40
    elements: its bending modes are sin(n pi x / L) to within the mesh's error."""
    section = Section.rectangle(E=210e9, G=80e9, density=7850.0, width=0.02, thickness=0.005,
                                bending="flatwise")
    topology = Topology(links=(LinkSpec("beam", "O1", "O2", section, 40),),
                        joints=(JointSpec("O1", True, math.inf, 0.0),
                                JointSpec("O2", True, math.inf, 0.0)))
    model, result, _ = pose_modes(topology, {"O1": (0.0, 0.0), "O2": (1.0, 0.0)}, n_modes + 2)
    elastic = result.elastic
    # bending only: the axial modes of a steel bar are far above these
    bending = [k for k in elastic if np.abs(result.shapes[1::3, k]).max()
               > np.abs(result.shapes[0::3, k]).max()][:n_modes]
    part = PartModes(Part.IN_PLANE, model, result.frequencies[bending], result.shapes[:, bending])
    return ModelModes(part.frequencies, (Part.IN_PLANE,) * n_modes,
                      tuple((0, k) for k in range(n_modes)),
                      tuple(f"bending {k + 1}" for k in range(n_modes)), (part,), 40)


def test_the_beams_modes_are_the_closed_form_sines():
    """The oracle's premise: f_n = n^2 pi/2 sqrt(EI / rhoA) / L^2 within 0.1 %."""
    modes = _pinned_beam_modes()
    s = modes.solved[0].model.links[0].section
    closed = np.arange(1, 5) ** 2 * math.pi / 2 * math.sqrt(s.EI / s.mass_per_length)
    np.testing.assert_allclose(modes.frequencies, closed, rtol=1e-3)


def test_effective_independence_keeps_off_the_nodes_and_beats_the_uniform_layout():
    """4 sensors for the 4 lowest modes. The nodes of modes 1-4 are at x/L = 0, 1/4, 1/3,
    1/2, 2/3, 3/4, 1: every chosen sensor keeps at least 2 % of L from them, and measures
    across the beam (the axial direction reads nothing of bending). The uniform layout
    (x/L = 0, 1/3, 2/3, 1) sees mode 3 nowhere and modes 2 and 4 as one pattern (autoMAC 1);
    the chosen layout's largest off-diagonal autoMAC is far lower, and its Fisher
    information positive where the uniform one's is about zero."""
    plan = plan_for_modes(_pinned_beam_modes(), 4, stations=50)
    x = plan.chosen.fraction
    nodes = np.array([0.0, 1 / 4, 1 / 3, 1 / 2, 2 / 3, 3 / 4, 1.0])
    assert np.min(np.abs(x[:, None] - nodes[None, :])) >= 0.02
    assert set(plan.chosen.kinds) == {"transverse"}
    np.testing.assert_allclose(plan.uniform.fraction, [0, 1 / 3, 2 / 3, 1], atol=1e-12)
    assert plan.uniform.unseen == (2,)
    assert plan.uniform.max_auto_mac == pytest.approx(1.0, abs=1e-6)
    assert plan.chosen.max_auto_mac < 0.5
    assert plan.chosen.fisher > 1e6 * abs(plan.uniform.fisher)


def test_a_four_bar_plan_has_more_fisher_information_than_the_uniform_layout():
    """On Table II case 3 (8 sensors, 6 modes) Effective Independence maximises what it
    aims at, det(Phi^T Phi), above the uniform layout's, and every target mode is seen."""
    from flexlink.scene import load_scene

    plan = plan_sensors(load_scene(ROOT / "scenes" / "tests" / "case3_timoshenko.toml"), 8, 6)
    assert plan.chosen.unseen == () and plan.count == 8
    assert plan.chosen.fisher > plan.uniform.fisher
