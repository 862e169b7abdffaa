"""The steady elastic response of a running linkage (``studies.steady_response``).

Each check is an independent route to the same answer: a time integration from rest run to
steady state, the quasi-static deflection under the inertia loads, the full finite-element
static solution, and the Campbell lines (k times the crank frequency on a frozen-pose
frequency).
"""
import math
import os

import numpy as np
import pytest
import scipy.linalg as la
from conftest import CASES_DIR
from helpers import written_out_equations
from scipy.integrate import solve_ivp

from flexlink.errors import InputError
from flexlink.fe.assembly import assemble_reduced_dense, reduced_columns, rigid_elimination
from flexlink.fe.model_at_pose import pose_model
from flexlink.fe.preload import inertia_loads, static_displacement
from flexlink.kinematics.dynamics import rigid_motion
from flexlink.scene import load_scene
from flexlink.analysis.frame_motion import link_motion
from flexlink.analysis.periodic import PeriodicModel, periodic_model, speed_multipliers
from flexlink.commands._options import parse_point
from flexlink.studies.running.steady_response import (
    ForcedModel,
    StrainPoint,
    forced_model,
    midspans,
    periodic_solution,
    response_sweep,
    UnstableError,
    steady_response,
)
from flexlink.units import RPM

MESH = 4  # elements per link: enough for the checks, cheap for CI


@pytest.fixture(scope="module")
def case1():
    return load_scene(CASES_DIR / "case1.toml")


@pytest.fixture(scope="module")
def full(case1):
    """Case 1 at 1 element per link in all its modes (17), at 9 poses: a basis that spans
    every pose, so the reduced model is the finite-element one in other coordinates (a few
    reference modes do not represent the other poses well: docs/critical-speeds.md)."""
    return forced_model(case1, n_modes=_reduced_size(case1, 1), poses=19, elements_per_link=1)


def _rows(rows, angles, theta):
    """Samples (poses, ...) at crank angles theta by trigonometric interpolation, written
    out here: sample p sits at angles[p]."""
    N = len(angles)
    k = np.fft.fftfreq(N, 1.0 / N)
    c = np.fft.fft(rows, axis=0) / N
    return np.tensordot(np.exp(1j * np.outer(np.atleast_1d(theta) - angles[0], k)), c,
                        axes=(1, 0)).real


@pytest.mark.skipif(os.environ.get("HYPOTHESIS_PROFILE") != "thorough",
                    reason="10 s: run with HYPOTHESIS_PROFILE=thorough")
def test_periodic_solution_is_the_time_integration_over_a_turn(case1):
    # The same reduced equations, written out here from the model's samples, by DOP853
    # (rtol 1e-10) over one turn from the harmonic-balance state: it must close on itself
    # and pass through every sampled state. In CI the linkage's periodic solution is checked
    # against a run from rest to steady state on a 2-vector basis
    # (test_linkage_steady_state.py); this checked 7-vector basis runs with the thorough
    # profile, beside the run from rest on the same model.
    # (the modal basis alone: the loads' static answers would add vectors of tens of kHz)
    model = forced_model(case1, n_modes=1, poses=19, damping_ratio=0.5, elements_per_link=2,
                         load_vectors=False)
    p, speed = model.periodic, 1200 * RPM
    response = steady_response(model, speed, samples=24)
    solution = periodic_solution(model, speed)
    x0 = np.concatenate([solution.at([0.0])[0], speed * solution.at([0.0], derivative=1)[0]])
    n = len(p.frequencies)
    rhs = written_out_equations(model, speed)
    period = 2 * np.pi / speed
    run = solve_ivp(rhs, (0, period), x0, method="DOP853", rtol=1e-10, atol=1e-20,
                    dense_output=True)
    closing = np.abs(run.sol(period) - x0).max() / np.abs(run.sol(run.t)).max()
    q = run.sol((response.angles - p.angles[0]) / speed)[:n].T
    strain = -model.half_depth * np.einsum(
        "spn,sn->sp", _rows(model.curvature, p.angles, response.angles), q)
    error = np.abs(response.strain - strain).max() / np.abs(strain).max()
    assert closing < 1e-6 and error < 1e-6, (closing, error)


def synthetic(poses: int = 9, zeta: float = 0.01) -> ForcedModel:
    """Two modes, 50 and 120 Hz, stiffness varying by 30 % over the turn, a Coriolis coupling,
    a centrifugal softening, inertia loads of the first two crank harmonics and one output
    point: the study's equations without a linkage's basis (whose reference modes make the
    stiffness jump sharply near the reference pose, docs/steady-response.md)."""
    angles = 0.3 + 2 * np.pi * np.arange(poses) / poses
    w = 2 * np.pi * np.array([50.0, 120.0])
    c = 1 + 0.3 * np.cos(angles)
    stiffness = np.array([[[w[0]**2 * ci, 0.1 * w[0] * w[1]], [0.1 * w[0] * w[1], w[1]**2 * ci]]
                          for ci in c])
    skew = np.array([[0.0, 1.0], [-1.0, 0.0]])
    periodic = PeriodicModel(angles=angles, mass=np.broadcast_to(np.eye(2), (poses, 2, 2)),
                             coriolis=np.broadcast_to(0.2 * skew, (poses, 2, 2)),
                             stiffness=stiffness,
                             speed_stiffness=np.broadcast_to(-np.eye(2), (poses, 2, 2)),
                             frequencies=w / (2 * np.pi), damping_ratio=zeta,
                             inertia_forcing=np.stack([np.cos(angles) + 0.5,
                                                       np.sin(2 * angles)], axis=1),
                             external_forcing=np.zeros((poses, 2)))
    rows = np.broadcast_to(np.array([[1.0, 0.5]]), (poses, 1, 2))
    return ForcedModel(periodic=periodic, points=(StrainPoint("a", 0.0),),
                       deflection=rows, curvature=rows, half_depth=np.array([0.001]))


def test_low_speed_tends_to_the_quasi_static_deflection():
    # as Omega -> 0 the response tends to K(theta)^-1 Omega^2 f2(theta); what is left is the
    # damping's lag, of order 2 zeta Omega / omega_1, and the dynamic excess
    # (k Omega / omega_1)^2 of the forcing's harmonics k = 1, 2: it falls between first and
    # second order in the speed
    model = synthetic()
    p = model.periodic
    gaps = []
    for r in (0.02, 0.01):
        speed = r * 2 * np.pi * p.frequencies[0]
        response = steady_response(model, speed, samples=36)
        K = _rows(p.stiffness + speed**2 * p.speed_stiffness, p.angles, response.angles)
        f = speed**2 * _rows(model.periodic.inertia_forcing, p.angles, response.angles)
        q = np.linalg.solve(K, f[..., None])[..., 0]
        static = -model.half_depth * np.einsum(
            "spn,sn->sp", _rows(model.curvature, p.angles, response.angles), q)
        gaps.append(np.abs(response.strain - static).max() / np.abs(static).max())
    assert gaps[0] < 5e-3, gaps
    assert 1.8 < gaps[0] / gaps[1] < 4.2, gaps


def test_coupled_modes_equal_a_long_time_integration():
    # two modes coupled by the Coriolis matrix (a 1 x 1 skew matrix is zero, so the linkage
    # check above cannot see it): DOP853 from rest, 3 turns at 10 Hz with zeta 0.3 decay the
    # free motion by exp(-0.3 * 2 pi 50 Hz * 0.2 s) ~ 6e-9 before the last turn starts
    model = synthetic(zeta=0.3)
    p, speed = model.periodic, 2 * np.pi * 10.0
    response = steady_response(model, speed, samples=20)
    damping = np.diag(2 * p.damping_ratio * 2 * np.pi * p.frequencies)
    N = len(p.angles)
    k = np.fft.fftfreq(N, 1.0 / N)
    coefficients = [np.fft.fft(a, axis=0) / N for a in (
        p.mass, p.coriolis, p.stiffness, p.speed_stiffness, model.periodic.inertia_forcing)]

    def rhs(t, x):
        e = np.exp(1j * k * speed * t)
        m, g, k0, k2, f2 = (np.tensordot(e, c, axes=(0, 0)).real for c in coefficients)
        return np.concatenate([x[2:], np.linalg.solve(
            m, speed**2 * f2 - (damping + speed * g) @ x[2:] - (k0 + speed**2 * k2) @ x[:2])])
    turns, period = 3, 2 * np.pi / speed
    run = solve_ivp(rhs, (0, turns * period), np.zeros(4), method="DOP853", rtol=1e-12,
                    atol=1e-20, dense_output=True)
    q = run.sol((turns - 1) * period + (response.angles - p.angles[0]) / speed)[:2].T
    strain = -model.half_depth * np.einsum(
        "spn,sn->sp", _rows(model.curvature, p.angles, response.angles), q)
    error = np.abs(response.strain - strain).max() / np.abs(strain).max()
    assert error < 1e-6, error


def test_a_speed_whose_free_motion_grows_has_no_steady_state():
    # at 60 Hz the centrifugal softening -Omega^2 (1.4e5 (rad/s)^2) exceeds the first mode's
    # stiffness at its weakest pose (0.7 (2 pi 50 Hz)^2 = 6.9e4): the free motion grows
    # (|mu| ~ 31 per turn), harmonic balance would still return a periodic answer, and the
    # study must refuse it; at 10 Hz it is stable. A sweep marks the speed, not refuses it.
    model = synthetic()
    with pytest.raises(UnstableError, match="no steady state"):
        steady_response(model, 2 * np.pi * 60.0, samples=12)
    sweep = response_sweep(model, 2 * np.pi * np.array([10.0, 60.0]), samples=12)
    assert list(sweep.unstable) == [False, True]
    assert sweep.largest_modulus[0] < 1.0 and np.isfinite(sweep.peak_strain[0]).all()


def _hermite_curvature(u, link, position):
    """d2v/dx2 of the cubic through the element's end values (Euler-Bernoulli), written out."""
    h = link.length / link.elements
    e = min(int(position / h), link.elements - 1)
    x = position / h - e
    c, s = math.cos(link.angle), math.sin(link.angle)
    n1, n2 = link.nodes[e], link.nodes[e + 1]
    v1, v2 = (-s * u[3 * n] + c * u[3 * n + 1] for n in (n1, n2))
    r1, r2 = u[3 * n1 + 2], u[3 * n2 + 2]
    return ((12 * x - 6) * (v1 - v2) / h**2 + (6 * x - 4) * r1 / h + (6 * x - 2) * r2 / h)


def test_forcing_and_strain_rows_match_the_full_static_solution(case1, full):
    # with every elastic mode in the basis, the modal static answer to the d'Alembert loads at
    # a pose is the full FE one; each pose is sampled exactly (no interpolation between them)
    topology = case1.topology(1)
    for p, angle in enumerate(full.periodic.angles):
        state = case1.rigid_state(angle)
        model = pose_model(topology, state.points)
        K, _ = assemble_reduced_dense(model, rigid_elimination(model))
        _, alpha, acc = link_motion(case1, model, topology,
                                    rigid_motion(case1.linkage, state, 1.0, 0.0))
        u = static_displacement(np.asarray(K), rigid_elimination(model), inertia_loads(model, acc, alpha))
        expected = np.array([_hermite_curvature(u, next(link for link in model.links
                                                         if link.name == pt.link), pt.position)
                             for pt in full.points])
        q = la.solve(full.periodic.stiffness[p], full.periodic.inertia_forcing[p])
        # the modal solve and the full one differ by round-off of a well-conditioned K
        assert full.curvature[p] @ q == pytest.approx(expected, rel=1e-7)


def _static_curvatures(scene, model: ForcedModel, elements: int) -> np.ndarray:
    """(poses, points) [1/m per (rad/s)^2]: the full finite-element static answer to the
    d'Alembert loads at each sampled pose, read at the model's points."""
    topology = scene.topology(elements)
    out = []
    for angle in model.periodic.angles:
        state = scene.rigid_state(angle)
        frame = pose_model(topology, state.points)
        K, _ = assemble_reduced_dense(frame, rigid_elimination(frame))
        _, alpha, acc = link_motion(scene, frame, topology,
                                    rigid_motion(scene.linkage, state, 1.0, 0.0))
        u = static_displacement(np.asarray(K), rigid_elimination(frame),
                                inertia_loads(frame, acc, alpha))
        out.append([_hermite_curvature(u, next(link for link in frame.links
                                              if link.name == pt.link), pt.position)
                    for pt in model.points])
    return np.array(out)


@pytest.mark.parametrize("load_vectors", [True, False])
def test_the_static_answers_in_the_basis_make_the_slow_response_the_full_static_one(
        case1, load_vectors):
    # Two modes checked at 4 elements a link take a 9-vector modal basis, which holds the
    # midspan curvature of the d'Alembert loads' static answer at the sampled poses only to
    # 3.5e-2 of its largest value (the modes left out carry the rest). With the loads' static
    # answers of every pose added (analysis.load_vectors: 10 directions) the basis holds them,
    # so at a crank speed so slow that nothing is dynamic (0.01 rev/min: the damping's lag
    # 2 zeta Omega / omega_1 ~ 6e-8, the forcing's harmonics ~ (Omega / omega_1)^2 ~ 1e-11 of
    # the first mode) the periodic solution at each sampled pose is Omega^2 times the full
    # model's static answer there: measured 1.5e-6 of the largest, the directions dropped
    # under THRESHOLD. Allowed 1e-5.
    model = forced_model(case1, n_modes=2, poses=19, elements_per_link=MESH,
                         load_vectors=load_vectors)
    expected = _static_curvatures(case1, model, MESH)
    speed = 0.01 * RPM
    q = periodic_solution(model, speed).at(model.periodic.angles - model.periodic.angles[0])
    ours = np.einsum("pkn,pn->pk", model.curvature, q) / speed**2
    error = np.abs(ours - expected).max() / np.abs(expected).max()
    assert (model.periodic.load_vectors > 0) == load_vectors
    if load_vectors:
        assert error < 1e-5, error
    else:  # the modal basis alone misses it: what the added vectors are for
        assert error > 1e-2, error


def test_the_steady_states_verdict_is_the_stability_maps(case1):
    # the loads' static answers enlarge the response's basis, not the verdict's: the response
    # and the stability map must call the same speeds stable, so the multipliers come from
    # the map's own equations (the same arithmetic: 1e-12 is round-off of the projection)
    model = forced_model(case1, n_modes=2, poses=19, elements_per_link=MESH)
    stability_map = periodic_model(case1, 2, 19, elements_per_link=MESH)
    assert model.periodic.load_vectors > 0
    verdict = model.periodic.stability
    assert len(verdict.frequencies) == len(stability_map.frequencies) \
        < len(model.periodic.frequencies)
    for name in ("mass", "stiffness", "speed_stiffness", "coriolis", "damping"):
        np.testing.assert_allclose(getattr(verdict, name), getattr(stability_map, name),
                                   rtol=1e-12, atol=1e-12 * np.abs(getattr(stability_map,
                                                                           name)).max())
    speed = 1200 * RPM
    ours = steady_response(model, speed, samples=12).largest_modulus
    theirs = speed_multipliers(stability_map, speed).largest_modulus
    assert ours == pytest.approx(theirs, rel=1e-9)


def _reduced_size(scene, elements):
    model = pose_model(scene.topology(elements), scene.rigid_state(None).points)
    return reduced_columns(rigid_elimination(model), model.n_dofs)[1]


@pytest.mark.slow
def test_peak_strain_resonances_sit_on_the_campbell_lines(case1):
    # case 1 at 2 elements per link, 5 modes, zeta 0.05 (lighter damping lets the basis'
    # spurious parametric ranges in: docs/steady-response.md). The second harmonic of the inertia loads meets mode 1 where 2 Omega = f_1(theta): the
    # swept peak strain of every link peaks inside mode 1's frozen-pose band over two (the
    # speed's own stiffening Omega^2 K2 included), and the
    # stability map is stable there (a forced resonance, not a parametric one)
    full = forced_model(case1, n_modes=5, poses=19, damping_ratio=0.05, elements_per_link=2)
    p = full.periodic
    f1 = p.frequencies[0]
    speeds = 2 * np.pi * f1 * np.linspace(0.44, 0.68, 13)
    sweep = response_sweep(full, speeds, samples=72)
    step = speeds[1] - speeds[0]
    for k in range(len(full.points)):
        i = int(np.argmax(sweep.peak_strain[:, k]))
        peak = speeds[i]
        band = [np.sqrt(la.eigh(K + peak**2 * K2, M, eigvals_only=True)[0])
                for K, K2, M in zip(p.stiffness, p.speed_stiffness, p.mass)]
        assert min(band) / 2 - step <= peak <= max(band) / 2 + step, (k, peak, band)
    assert not sweep.unstable.any() and np.nanmax(sweep.largest_modulus) < 1.0


def test_a_point_outside_its_link_is_refused(case1):
    with pytest.raises(InputError, match="outside link 'coupler'"):
        forced_model(case1, n_modes=2, poses=3, elements_per_link=2,
                     points=(StrainPoint("coupler", 10.0),))
    with pytest.raises(InputError, match="no beam link named 'arm'"):
        forced_model(case1, n_modes=2, poses=3, elements_per_link=2,
                     points=(StrainPoint("arm", 0.0),))


def test_a_point_is_read_as_link_and_distance_or_refused_saying_what_is_expected():
    assert parse_point(" coupler : 60 mm") == StrainPoint("coupler", pytest.approx(0.06))
    for text in ("coupler", ":60 mm"):
        with pytest.raises(InputError, match="LINK:DISTANCE") as refused:
            parse_point(text, field="--point")
        assert (refused.value.source, refused.value.field) == ("command line", "--point")
        assert "coupler:60 mm" in refused.value.expected  # an example of the accepted form


def test_default_points_are_the_midspans(case1):
    points = midspans(case1)
    assert [p.link for p in points] == ["crank", "coupler", "rocker"]
    state = case1.rigid_state(None).points
    lengths = {"crank": ("O2", "A"), "coupler": ("A", "B"), "rocker": ("B", "O4")}
    for p in points:
        a, b = lengths[p.link]
        assert p.position == pytest.approx(
            np.hypot(*(np.asarray(state[b]) - np.asarray(state[a]))) / 2, rel=1e-12)
