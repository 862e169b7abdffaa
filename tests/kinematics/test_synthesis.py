"""Synthesis: targets checked with the four-bar's own kinematics, and Table II recovered."""

import math

import pytest

from flexlink.kinematics.linkage import crank_angles, four_bar_linkage
from flexlink.kinematics.synthesis import brodell_soni, extended_rocker, minimax

deg = math.radians


def toggle_crank_angles(fb):
    """Crank angles [rad] of the extended and folded toggles (crank and coupler collinear),
    from the triangle O2 O4 B with |O2 B| = L3 +- L2 (B above the ground line)."""
    L1, L2, L3, L4 = fb.lengths

    def angle_of_B(d):
        return math.acos((L1**2 + d**2 - L4**2) / (2 * L1 * d))

    return angle_of_B(L3 + L2), angle_of_B(L3 - L2) + math.pi


@pytest.mark.parametrize("theta4i, delta, printed", [
    (100.0, 20.0, (0.141, 0.900, 0.457)),  # Table II case 3: mu = 90 +- 20
    (90.0, 30.0, (0.209, 0.914, 0.457)),   # Table II case 4: mu = 90 +- 30
])
def test_minimax_recovers_table2(theta4i, delta, printed):
    fb = minimax(deg(theta4i), deg(delta))
    # as printed: within half a unit of the third decimal
    assert list(fb.ratios) == pytest.approx(printed, rel=0, abs=5e-4)
    R2, R3, R4 = fb.ratios
    assert R3**2 + R4**2 - R2**2 == pytest.approx(1.0, abs=1e-12)
    mu_min, mu_max = fb.transmission_limits()
    assert mu_min == pytest.approx(deg(90 - delta), abs=1e-12)
    assert mu_max == pytest.approx(deg(90 + delta), abs=1e-12)
    assert fb.pose(0.0).theta4 == pytest.approx(deg(theta4i), abs=1e-12)


@pytest.mark.parametrize("gamma_min, swing", [(60.0, 30.0), (50.0, 60.0), (40.0, 80.0)])
def test_brodell_soni_identities(gamma_min, swing):
    fb = brodell_soni(deg(gamma_min), deg(swing), ground=0.4)
    assert fb.grashof_class() == "crank-rocker"
    assert fb.rocker_swing() == pytest.approx(deg(swing), abs=1e-12)
    mu_min, mu_max = fb.transmission_limits()
    assert mu_min == pytest.approx(deg(gamma_min), abs=1e-12)
    assert mu_min + mu_max == pytest.approx(math.pi, abs=1e-12)
    extended, folded = toggle_crank_angles(fb)
    assert folded - extended == pytest.approx(math.pi, abs=1e-12)  # unit time ratio


@pytest.mark.parametrize("ratio", [2.0, 3.5, 9.0])
def test_extended_rocker_design_has_unit_time_ratio_and_its_swing(ratio):
    fb = extended_rocker(0.1, deg(30.0), ratio)
    assert fb.rocker_swing() == pytest.approx(deg(30.0), abs=1e-12)
    extended, folded = toggle_crank_angles(fb)
    assert folded - extended == pytest.approx(math.pi, abs=1e-12)
    # a rocker built longer than designed (k = 1.2) loses both properties
    other = extended_rocker(0.1, deg(30.0), ratio, k=1.2)
    extended, folded = toggle_crank_angles(other)
    assert abs(folded - extended - math.pi) > 1e-3


def test_extended_rocker_tends_to_simple_harmonic_motion_for_a_long_coupler():
    # with L3 >> L2 the pin B follows the crank's projection on the chord B1B2:
    # sin(phi - phi_mid) = sin(Theta/2) cos(q - q0), so max |K| = sin(Theta/2) and, at the
    # limit positions, |L| = tan(Theta/2); the errors shrink like L2/L3 (here 1e-3)
    fb = extended_rocker(0.1, deg(30.0), 1000.0)
    cycle = four_bar_linkage(*fb.lengths).cycle(crank_angles(720), fb.pose(0.0).joints)
    assert abs(cycle.K[:, 2]).max() == pytest.approx(math.sin(deg(15.0)), rel=1e-4)
    assert abs(cycle.L[:, 2]).max() == pytest.approx(math.tan(deg(15.0)), rel=3e-3)
