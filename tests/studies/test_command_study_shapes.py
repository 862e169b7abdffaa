"""The result types of the cycle, Campbell, convergence, synthesis and PRB studies check their
own shapes on construction (as meshio's ``Mesh`` does): a wrong array fails where it is made,
with the field and the shape it should have had. Built from small synthetic arrays, so each
check costs nothing; the commands' own tests run the studies for real."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from flexlink.analysis.mesh import COMMAND_LINE, MeshRule
from flexlink.studies.cycle.bands import bands, critical_speeds, nearest_margin
from flexlink.studies.cycle.campbell import CampbellStudy
from flexlink.studies.verification.convergence import (CHOICES, ConvergenceStudy, Level, relative_errors,
                                          richardson)
from flexlink.studies.pose.crank_rocker import crank_rocker
from flexlink.studies.cycle.modal_map import ModalMap, Resonance
from flexlink.studies.cycle.cycle import CycleStudy
from flexlink.studies.pose.prb import PRBResult, PrbComparison
from flexlink.studies.cycle.tracking import TrackedMap, Tracks

POSES, LINES = 6, 2
Q = np.linspace(0.0, 2 * math.pi, POSES, endpoint=False)
F = np.column_stack([10 + np.sin(Q), 30 + np.cos(Q)])  # two lines [Hz] over the cycle


def tracked() -> TrackedMap:
    tracks = Tracks(frequencies=F, shapes=tuple(np.eye(3)[:, :LINES] for _ in Q),
                    mac=np.ones((POSES, LINES)), rank=np.tile(np.arange(LINES), (POSES, 1)),
                    events=())
    return TrackedMap(scene="synthetic", q=Q, frequencies=F, tracks=tracks, mu90={},
                      labels=("a", "b"), mechanism_counts=np.zeros(POSES, dtype=int))


def cycle() -> CycleStudy:
    found = ModalMap(scene="synthetic", q=Q, frequencies=F, mechanism_counts=np.zeros(POSES),
                     mu90={})
    hit = Resonance(harmonic=2, frequency=10.0, mode=1, angles=Q[:1], closest=0.0)
    return CycleStudy(map=found, mesh=MeshRule(2, COMMAND_LINE), poses=POSES,
                      crank_speed=10 * math.pi, check_speed=10 * math.pi, check_note=None,
                      margin=0.05, harmonics=3, hits=(hit,), nearest=(0.0, 1, 2), note=None)


def test_the_cycle_study_refuses_a_map_of_another_pose_count_and_foreign_hits():
    study = cycle()
    assert study.tracked is False
    with pytest.raises(ValueError, match=r"CycleStudy.map.frequencies has shape \(6, 2\), "
                                         r"expected \(5, 2\)"):
        dataclasses.replace(study, poses=POSES - 1)
    with pytest.raises(ValueError, match=r"CycleStudy.map.q has shape \(5,\), expected \(6,\)"):
        dataclasses.replace(study, map=dataclasses.replace(study.map, q=Q[:-1]))
    with pytest.raises(ValueError, match=r"CycleStudy.nearest has shape \(2,\), expected \(3,\)"):
        dataclasses.replace(study, nearest=(0.0, 1))
    with pytest.raises(ValueError, match="mode 3 and harmonic 2, expected 1..2 and 1..3"):
        dataclasses.replace(study, hits=(dataclasses.replace(study.hits[0], mode=3),))
    with pytest.raises(ValueError, match="mode 1 and harmonic 4, expected 1..2 and 1..3"):
        dataclasses.replace(study, hits=(dataclasses.replace(study.hits[0], harmonic=4),))


def test_the_campbell_study_refuses_bands_of_other_lines_and_a_bad_window():
    window = (0.0, 3000 * 2 * math.pi / 60)
    found = bands(F)
    study = CampbellStudy(tracked=tracked(), mesh=MeshRule(2, COMMAND_LINE), poses=POSES,
                          window=window, margin=0.05, harmonics=3, bands=tuple(found),
                          critical=tuple(critical_speeds(found, window, 0.05, 3)),
                          nearest=nearest_margin(found, window, 3))
    assert study.labels == {1: "a", 2: "b"}
    with pytest.raises(ValueError, match=r"CampbellStudy.tracked.frequencies has shape "
                                         r"\(6, 2\), expected \(6, 1\)"):
        dataclasses.replace(study, bands=study.bands[:1])
    with pytest.raises(ValueError, match=r"CampbellStudy.window has shape \(3,\), "
                                         r"expected \(2,\)"):
        dataclasses.replace(study, window=(0.0, 1.0, 2.0))
    with pytest.raises(ValueError, match="shifts given without the diagram at speed"):
        dataclasses.replace(study, shifts=(object(),))


def test_the_convergence_study_refuses_errors_of_another_level_count():
    # f_h = 1 + h^2 on h = 1, 1/2, 1/4: the Richardson reference is 1 exactly
    levels = [Level(CHOICES[0], n, 3 * n, 0.0, 0.0, np.array([1 + n**-2.0, 2 + n**-2.0]))
              for n in (1, 2, 4)]
    extrapolation = richardson(levels)
    assert extrapolation.reference == pytest.approx([1.0, 2.0], abs=1e-15)  # exact in h^2
    errors = relative_errors(levels, extrapolation.reference)
    study = ConvergenceStudy(scene="synthetic", file="synthetic.toml", n_modes=2, repeats=1,
                             tol=1e-6, levels=tuple(levels), extrapolation=extrapolation,
                             errors=errors, cheapest=None, measured=None)
    with pytest.raises(ValueError, match=r"ConvergenceStudy.errors has shape \(2, 2\), "
                                         r"expected \(3, 2\)"):
        dataclasses.replace(study, errors=errors[:2])
    with pytest.raises(ValueError, match=r"levels\[\].frequencies has shape \(1,\), "
                                         r"expected \(2,\)"):
        dataclasses.replace(study, levels=(dataclasses.replace(levels[0],
                                                               frequencies=np.ones(1)),
                                           *levels[1:]))


def test_the_crank_rocker_refuses_lengths_that_are_not_four():
    result = crank_rocker("minimax", {}, math.radians(100), math.radians(20), 1.0)
    # mini-max: mu_min + mu_max = 180 deg (FACTS.md), to rounding
    assert math.degrees(result.transmission.sum()) == pytest.approx(180, abs=1e-9)
    with pytest.raises(ValueError, match=r"CrankRocker.lengths has shape \(3,\), "
                                         r"expected \(4,\)"):
        dataclasses.replace(result, lengths=result.lengths[:3])
    with pytest.raises(ValueError, match=r"CrankRocker.ratios has shape \(4,\), expected \(3,\)"):
        dataclasses.replace(result, ratios=result.lengths)
    with pytest.raises(ValueError, match=r"CrankRocker.transmission has shape \(1,\), "
                                         r"expected \(2,\)"):
        dataclasses.replace(result, transmission=result.transmission[:1])


def test_the_prb_comparison_refuses_no_fe_frequency_and_points_not_in_the_plane():
    result = PrbComparison(crank_angle=0.0, points={"A": (0.0, 0.0)}, fe=(10.0, 20.0),
                           prb=PRBResult(spring=1.0, stiffness=1.0, mass=1.0, frequency=11.0))
    assert result.prb_vs_fe_pct == pytest.approx(10.0, rel=1e-14)  # (11 - 10) / 10, rounding
    with pytest.raises(ValueError, match=r"PrbComparison.fe has shape \(0,\), expected "
                                         r"\(at least 1,\)"):
        dataclasses.replace(result, fe=())
    with pytest.raises(ValueError, match=r"PrbComparison.points\['A'\] has shape \(3,\), "
                                         r"expected \(2,\)"):
        dataclasses.replace(result, points={"A": (0.0, 0.0, 0.0)})
