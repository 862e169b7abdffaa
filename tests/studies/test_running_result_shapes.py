"""The running linkage's result types check their own shapes on construction: a wrong array
fails where it is made, naming the field and the shape it should have had. Built from small
synthetic arrays, so each check costs nothing; the commands' own tests run the studies."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from flexlink.analysis.periodic import Integrator, PeriodicModel
from flexlink.fe.speed_terms import SpeedTerms, UnitMotion
from flexlink.studies.running.dynamic_campbell import Divergence, DynamicCampbell, ProjectedPose
from flexlink.studies.running.stability_map import InstabilityRange, RangeKind, StabilityMap
from flexlink.studies.running.steady_response import (ForcedModel, ResponseSweep,
                                                      SteadyResponse, StrainPoint)

POSES, N, SPEEDS = 5, 2, 4


def periodic(**changes) -> PeriodicModel:
    stack = np.broadcast_to(np.eye(N), (POSES, N, N))
    fields = dict(angles=np.linspace(0, 2 * np.pi, POSES, endpoint=False), mass=stack,
                  coriolis=0 * stack, stiffness=stack, speed_stiffness=0 * stack,
                  frequencies=np.array([1.0, 2.0]), damping_ratio=0.01,
                  inertia_forcing=np.ones((POSES, N)), external_forcing=np.zeros((POSES, N)))
    return PeriodicModel(**{**fields, **changes})


def stability_map(**changes) -> StabilityMap:
    fields = dict(speeds=np.arange(SPEEDS, dtype=float), largest_modulus=np.ones(SPEEDS),
                  growth_rate=np.zeros(SPEEDS), ranges=(), stiffness_floor=np.ones(SPEEDS),
                  integrator=Integrator.ADIABATIC, magnus_fallback=np.zeros(SPEEDS, bool))
    return StabilityMap(**{**fields, **changes})


def test_the_stability_map_refuses_a_value_per_speed_of_another_count():
    stability_map()
    for name in ("largest_modulus", "growth_rate", "stiffness_floor", "magnus_fallback"):
        with pytest.raises(ValueError, match=f"StabilityMap.{name} has shape"):
            stability_map(**{name: np.ones(SPEEDS + 1)})


def test_an_instability_range_refuses_modes_that_its_kind_does_not_have():
    assert InstabilityRange(1.0, 2.0, (1,), 2, "primary", 0.1).kind is RangeKind.PRIMARY
    InstabilityRange(1.0, 2.0, (1, 2), 1, RangeKind.COMBINATION, 0.1)
    InstabilityRange(1.0, 2.0, (), 0, RangeKind.DIVERGENCE, 0.1)
    with pytest.raises(ValueError, match="InstabilityRange.modes has shape"):
        InstabilityRange(1.0, 2.0, (1, 2), 2, RangeKind.PRIMARY, 0.1)
    with pytest.raises(ValueError, match="InstabilityRange.harmonic"):
        InstabilityRange(1.0, 2.0, (), 3, RangeKind.DIVERGENCE, 0.1)
    with pytest.raises(ValueError, match="above high"):
        InstabilityRange(2.0, 1.0, (1,), 2, RangeKind.PRIMARY, 0.1)
    with pytest.raises(ValueError):  # not a kind
        InstabilityRange(1.0, 2.0, (1,), 2, "flutter", 0.1)


def test_the_periodic_model_refuses_matrices_and_forcing_of_other_sizes():
    periodic()
    with pytest.raises(ValueError, match="PeriodicModel.coriolis has shape"):
        periodic(coriolis=np.zeros((POSES, N + 1, N + 1)))
    with pytest.raises(ValueError, match="PeriodicModel.inertia_forcing has shape"):
        periodic(inertia_forcing=np.ones((POSES + 1, N)))
    with pytest.raises(ValueError, match="both forcings or neither"):
        periodic(external_forcing=None)


def forced(**changes) -> ForcedModel:
    rows = np.ones((POSES, 1, N))
    fields = dict(periodic=periodic(), points=(StrainPoint("a", 0.0),), deflection=rows,
                  curvature=rows, half_depth=np.array([1e-3]))
    return ForcedModel(**{**fields, **changes})


def test_the_forced_model_refuses_rows_of_another_basis_or_point_count():
    forced()
    with pytest.raises(ValueError, match="ForcedModel.curvature has shape"):
        forced(curvature=np.ones((POSES, 1, N + 1)))
    with pytest.raises(ValueError, match="ForcedModel.half_depth has shape"):
        forced(half_depth=np.array([1e-3, 2e-3]))
    with pytest.raises(ValueError, match="carries no forcing"):
        forced(periodic=periodic(inertia_forcing=None, external_forcing=None))


def test_the_steady_response_refuses_strain_of_another_shape_than_deflection():
    angles = np.linspace(0, 2 * np.pi, 6, endpoint=False)
    SteadyResponse(1.0, angles, np.zeros((6, 2)), np.zeros((6, 2)), 0.5)
    with pytest.raises(ValueError, match="SteadyResponse.strain has shape"):
        SteadyResponse(1.0, angles, np.zeros((6, 2)), np.zeros((6, 3)), 0.5)
    with pytest.raises(ValueError, match="SteadyResponse.deflection has shape"):
        SteadyResponse(1.0, angles, np.zeros((5, 2)), np.zeros((5, 2)), 0.5)


def test_the_response_sweep_refuses_peaks_of_another_speed_or_point_count():
    points = (StrainPoint("a", 0.0), StrainPoint("b", 0.1))
    ok = dict(speeds=np.arange(3.0), points=points, peak_strain=np.zeros((3, 2)),
              peak_deflection=np.zeros((3, 2)), largest_modulus=np.zeros(3))
    ResponseSweep(**ok)
    with pytest.raises(ValueError, match="ResponseSweep.peak_deflection has shape"):
        ResponseSweep(**{**ok, "peak_deflection": np.zeros((3, 1))})
    with pytest.raises(ValueError, match="ResponseSweep.largest_modulus has shape"):
        ResponseSweep(**{**ok, "largest_modulus": np.zeros(4)})


def test_the_dynamic_campbell_refuses_frequencies_of_another_grid():
    ok = dict(scene="s", q=np.arange(3.0), speeds=np.arange(2.0),
              frequencies=np.ones((2, 3, 2)), static=np.ones((3, 2)), basis=4)
    DynamicCampbell(**ok)
    with pytest.raises(ValueError, match="DynamicCampbell.frequencies has shape"):
        DynamicCampbell(**{**ok, "frequencies": np.ones((2, 4, 2))})
    with pytest.raises(ValueError, match="DynamicCampbell.static has shape"):
        DynamicCampbell(**{**ok, "static": np.ones((3, 3))})


def test_a_divergence_refuses_arrays_for_its_numbers_and_a_line_below_one():
    Divergence(speed=None, q=0.1, line=1, grid_speed=2.0, growth_rate=0.5)
    with pytest.raises(ValueError, match="Divergence.q has shape"):
        Divergence(speed=1.0, q=np.zeros(2), line=1, grid_speed=2.0, growth_rate=0.5)
    with pytest.raises(ValueError, match="Divergence.line"):
        Divergence(speed=1.0, q=0.1, line=0, grid_speed=2.0, growth_rate=0.5)


def test_a_projected_pose_refuses_coefficients_of_another_basis_size():
    ok = dict(static_hz=np.ones(2), k0=np.eye(2), k2=np.eye(2), g1=np.eye(2), k1=np.eye(2),
              frame=np.ones((9, 2)))
    ProjectedPose(**ok)
    with pytest.raises(ValueError, match="ProjectedPose.g1 has shape"):
        ProjectedPose(**{**ok, "g1": np.eye(3)})


def test_the_speed_terms_and_unit_motion_refuse_parts_of_other_sizes():
    UnitMotion(omega=np.ones(3), alpha=np.ones(3), acceleration=np.ones((7, 2)))
    with pytest.raises(ValueError, match="UnitMotion.alpha"):
        UnitMotion(omega=np.ones(3), alpha=np.ones(2), acceleration=np.ones((7, 2)))
    with pytest.raises(ValueError, match="both start_alpha and start_acceleration"):
        UnitMotion(omega=np.ones(3), alpha=np.ones(3), acceleration=np.ones((7, 2)),
                   start_alpha=np.ones(3))
    ok = dict(centrifugal=np.eye(2), circulatory=np.eye(2), coriolis=np.eye(2),
              preload=np.eye(2), external_preload=np.eye(2), inertia_loads=np.ones(6),
              external_loads=np.ones(6), inertia_forces=(), external_forces=())
    terms = SpeedTerms(**ok)
    with pytest.raises(ValueError, match="SpeedTerms.coriolis has shape"):
        dataclasses.replace(terms, coriolis=np.eye(3))
