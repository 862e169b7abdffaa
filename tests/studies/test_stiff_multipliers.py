"""Floquet multipliers where the reduced basis is stiff: Table II case 3 with Rayleigh damping
(beta 1.1423e-4 s: zeta 0.02 at mode 1), whose stiff vectors (3-8 kHz here) are overdamped.
The adiabatic steps refuse their real eigenvalues, and the fourth-order Magnus steps' count
follows the fastest decay rate (h max|eig A| <= 2): ``response -n 14`` at 1200 rev/min ran
more than 20 CPU-minutes. The midpoint steps (``periodic.midpoint_multipliers``) take a count
set by the coefficients' variation over the turn."""

import numpy as np
import pytest

from conftest import CASES_DIR, SCENES_DIR
from flexlink.analysis.periodic import (Integrator, midpoint_multipliers, multipliers_by,
                                        periodic_model)
from flexlink.scene import load_scene
from flexlink.studies.running.stability_map import stability_map
from flexlink.studies.running.steady_response import (forced_model, response_sweep,
                                                       steady_response)
from flexlink.units import RPM


@pytest.fixture(scope="module")
def stiff():
    """8 vectors on 4 elements a link: 56 Hz to 8.1 kHz, zeta 0.02 to 2.9."""
    return periodic_model(load_scene(CASES_DIR / "case3.toml",
                                     {"damping.rayleigh_beta": 1.1423e-4}),
                          n_modes=3, elements_per_link=4, basis_size=8)


@pytest.mark.parametrize("rpm", [600.0, 1200.0])
def test_midpoint_steps_agree_with_the_fourth_order_steps(stiff, rpm):
    """ln |mu| per turn within 1e-4 (the midpoint steps' settling tolerance) of the
    fourth-order steps at h omega_max <= 2; measured 6.4e-6 at 600, 8e-8 at 1200 rev/min."""
    midpoint = midpoint_multipliers(stiff, rpm * RPM)
    magnus, used = multipliers_by(stiff, rpm * RPM, integrator=Integrator.MAGNUS)
    assert used is Integrator.MAGNUS
    assert midpoint.growth_per_period == pytest.approx(magnus.growth_per_period, abs=1e-4)


def test_slow_stiff_speed_takes_few_steps_and_reports_them(stiff):
    """At 60 rev/min the fourth-order steps need some 50 000 a turn (5 s here, and growing
    with the stiffest vector); the fallback takes the midpoint steps, reports each batch, and
    settles within 4096 steps in all (1792 measured)."""
    done = []
    result, used = multipliers_by(stiff, 60 * RPM, on_steps=done.append)
    assert used is Integrator.MIDPOINT
    assert 0 < sum(done) <= 4096
    # a decay per turn of about zeta_1 omega_1 T (Liouville's bound for the slowest mode)
    assert np.isfinite(result.growth_per_period) and result.largest_modulus < 1e-2


def test_response_and_map_report_steps_within_a_speed():
    """The progress within one speed reaches the studies' callers (the commands' step bars)."""
    scene = load_scene(CASES_DIR / "case3.toml", {"damping.rayleigh_beta": 1.1423e-4})
    model = forced_model(scene, n_modes=3, elements_per_link=4, basis_size=8)
    done = []
    steady_response(model, 60 * RPM, samples=36, on_steps=done.append)
    assert sum(done) > 0
    done.clear()
    response_sweep(model, np.array([60.0]) * RPM, samples=36, on_steps=done.append)
    assert sum(done) > 0
    done.clear()
    stability_map(model.periodic, np.array([60.0, 61.0]) * RPM, on_steps=done.append)
    assert sum(done) > 0


def test_uneven_convergence_is_not_taken_for_settled():
    """The aluminium four-bar at 100 rev/min: its stiff vectors are neither overdamped nor
    many periods a step, and the midpoint steps converge unevenly (ln |mu| moves 5.9e-5 from
    2048 to 4096 steps a turn, then 6.8e-4 to 8192). One doubling within 1e-4 stopped at
    4096, 6.9e-4 from the fourth-order steps; two running settle at 32768, 1.2e-6 from them
    (within 1e-4, the settling tolerance)."""
    model = periodic_model(load_scene(SCENES_DIR / "kineto_aluminium.toml"), n_modes=6)
    midpoint = midpoint_multipliers(model, 100 * RPM)
    magnus, _ = multipliers_by(model, 100 * RPM, integrator=Integrator.MAGNUS)
    assert midpoint.growth_per_period == pytest.approx(magnus.growth_per_period, abs=1e-4)
