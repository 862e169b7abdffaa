"""The damping of the periodic equations acts on the rate of each pose's own elastic
deformation, not on the basis's own motion over the turn (``analysis.damping.
deformation_damping``).

Why it matters: the basis is fixed in co-rotating node coordinates, whose frames turn against
each other over the turn; the pins' translations carried with them read, in the scene pose's
terms, as stretches of the stiff pin springs. A damping fixed in the basis (the scene pose's
modal damping at every pose) resists that motion, and under Rayleigh damping, whose stiff
vectors carry ratios up to 4, it distorted the crank's quasi-static strain on Table II case 3
by 86 % of its peak at 600 rev/min."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as la

from conftest import CASES_DIR
from flexlink.analysis.periodic import periodic_model
from flexlink.scene import load_scene
from flexlink.studies.running.steady_response import forced_model, periodic_solution
from flexlink.units import RPM

BETA = 1.1423e-4  # [s]: zeta 0.02 at case 3's first mode, 2 pi 55.7 Hz


def scene(tmp_path, table: str, name: str = "damped"):
    path = tmp_path / f"{name}.toml"
    path.write_text(f'base = "{(CASES_DIR / "case3.toml").as_posix()}"\n[damping]\n{table}\n')
    return load_scene(path)


def test_rayleigh_damping_is_each_poses_own_alpha_m_plus_beta_k(tmp_path):
    # C(theta) = alpha M(theta) + beta K(theta) in the basis at every sampled pose (the pose's
    # modes span the basis, so the modal sum is exact): case 3 has no [[loads]], so the
    # stiffness at rest is the elastic K. 1e-9 of the largest entry: the round-off of the
    # generalised eigen decomposition of a K whose entries span 1e3 to 1e11
    alpha = 3.0
    model = periodic_model(scene(tmp_path, f"rayleigh_alpha = {alpha}\nrayleigh_beta = {BETA}"),
                           n_modes=4, poses=9, elements_per_link=4)
    expected = alpha * model.mass + BETA * model.stiffness
    assert np.abs(model.damping - expected).max() <= 1e-9 * np.abs(expected).max()
    # and it is not the scene pose's damping carried to every pose: the poses differ
    assert np.abs(model.damping - model.damping[0]).max() > 1e-3 * np.abs(expected).max()


def test_a_single_ratio_damps_each_poses_own_modes_at_that_ratio(tmp_path):
    # C Phi = M Phi diag(2 zeta omega) for the pose's own M-normalised modes at every pose
    model = periodic_model(scene(tmp_path, "ratio = 0.03"), n_modes=4, poses=9,
                           elements_per_link=4)
    for M, K, C in zip(model.mass, model.stiffness, model.damping):
        values, Phi = la.eigh(K, M)
        modal = Phi.T @ C @ Phi
        assert np.abs(modal - np.diag(2 * 0.03 * np.sqrt(values))).max() \
            <= 1e-9 * np.sqrt(values).max()


@pytest.mark.slow
def test_the_cranks_quasi_static_strain_scales_with_the_speed_squared_whatever_the_beta(
        tmp_path):
    # case 3's crank at 600 rev/min answers nearly quasi-statically (its load harmonics reach
    # about 60 Hz, its own mode 144 Hz): its peak strain is 100 times its peak at 60 rev/min
    # within 2 % (measured 1.3 %), the whole curve within 3.5 % of the peak (measured 2.6 %:
    # the harmonic balance departs from the quasi-static K(theta)^-1 f(theta) by 3.0 % there,
    # the crank's own dynamics, with a single ratio 0.02 as with Rayleigh; the time-domain
    # record departs by 1.25 % and 2.57 %, test_time_domain_record), and halving
    # Rayleigh's beta (the stiff vectors' ratios from up to 4.4 to 2.2) moves the curve by
    # less than 1 % of the peak (measured 0.82 %). With the scene pose's damping fixed in the
    # basis the curve was 86 % of the peak away and halving beta moved it by 28 %. The
    # periodic solution itself, without the Floquet check (Magnus steps over overdamped
    # vectors at 60 rev/min take minutes; the map's own tests check stability)
    turn = 2 * np.pi * np.arange(180) / 180
    crank = {}
    for beta in (BETA, BETA / 2):
        model = forced_model(scene(tmp_path, f"rayleigh_beta = {beta}", f"b{beta:.0e}"))
        k = [p.link for p in model.points].index("crank")
        rows = model.at(model.curvature, model.periodic.angles[0] + turn)[:, k]
        crank[beta] = [-model.half_depth[k] * np.einsum(
            "sn,sn->s", rows, periodic_solution(model, rpm * RPM).at(turn)) for rpm in (60, 600)]
    slow, fast = crank[BETA]
    peak = np.abs(fast).max()
    assert abs(peak / np.abs(100 * slow).max() - 1) <= 0.02
    assert np.abs(fast - 100 * slow).max() <= 0.035 * peak
    assert np.abs(crank[BETA / 2][1] - fast).max() <= 0.01 * peak
