"""The exponential-midpoint steps (``analysis.periodic.midpoint_multipliers``) on equations with
a closed form: two Mathieu oscillators, q_i'' + 2 zeta_i w_i q_i' + w_i^2 (1 + eps cos t) q_i = 0,
the first undamped on either side of its first tongue's edges (Hill's determinant,
tests/mathieu.py), the second 10^4 times stiffer and overdamped (zeta 2), as Rayleigh's beta K
makes a reduced basis' stiff vectors. The adiabatic steps refuse the overdamped vector's real
eigenvalue and the fourth-order Magnus steps would need h max|eig A| <= 2, some 6e4 steps a
turn: the midpoint steps take under two thousand in all."""

import numpy as np
import pytest

from flexlink.analysis.periodic import Integrator, PeriodicModel, multipliers_by
from mathieu import hill_edges

EPSILON = 0.2
STIFF = 1e4  # the second oscillator's frequency over the first's


def two_oscillators(delta: float, poses: int = 5) -> PeriodicModel:
    """Unit masses, K(theta) = (1 + EPSILON cos theta) diag(delta, STIFF^2 delta): at crank
    speed 1 rad/s the first is Mathieu's multiplicative form of parameter delta (exact from
    3 poses: a first harmonic)."""
    angles = 2.0 * np.pi * np.arange(poses) / poses
    k = np.array([delta, STIFF**2 * delta])
    zeros = np.zeros((poses, 2, 2))
    return PeriodicModel(angles=angles, mass=zeros + np.eye(2), coriolis=zeros,
                         stiffness=(1.0 + EPSILON * np.cos(angles))[:, None, None] * np.diag(k),
                         speed_stiffness=zeros, frequencies=np.sqrt(k) / (2.0 * np.pi),
                         damping_ratio=np.array([0.0, 2.0]))


@pytest.mark.parametrize("edge", [0, 1])
def test_stiff_overdamped_vector_leaves_the_tongue_edges_to_hill(edge, caplog):
    """Just outside either edge (0.1 % of delta) the undamped oscillator's multipliers stay on
    the unit circle: the midpoint step is the exact exponential of a Hamiltonian block, so
    |mu| = 1 to round-off (1e-9 allows it with room; measured 2e-12); just inside, the tongue's
    growth (measured |mu| - 1 = 0.022 at 0.1 % inside) is above 1e-3. The 0.1 % margin is far
    above the midpoint steps' shift of the edges (second order, at 1024 steps or more)."""
    delta = hill_edges(EPSILON, 1, multiplicative=True)[edge]
    side = -1.0 if edge == 0 else 1.0
    steps = []
    for where, factor in (("outside", 1.0 + side * 1e-3), ("inside", 1.0 - side * 1e-3)):
        result, used = multipliers_by(two_oscillators(delta * factor), 1.0,
                                      on_steps=steps.append)
        assert used is Integrator.MIDPOINT
        growth = result.largest_modulus - 1.0
        if where == "outside":
            assert abs(growth) < 1e-9
        else:
            assert growth > 1e-3
    # doubled from 256 until it settles (1792 steps a call, measured): far below the
    # fourth-order steps' 6e4
    assert sum(steps) <= 2 * 4096
