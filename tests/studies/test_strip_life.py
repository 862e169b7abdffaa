"""The interim strip life against a hand calculation written out from stated data, Goodman at
zero mean, and Basquin's scaling."""

import math

import numpy as np
import pytest

from flexlink.errors import InputError
from flexlink.studies.life.strip_life import SteelStrength, marin, strip_life

STEEL = SteelStrength(1170e6, 880e6, "test data")
DEPTH, WIDTH = 1e-3, 30e-3  # [m]: the wiper's strip


def test_hand_calculation():
    """Shigley ch. 6 by hand for Sut = 1170 MPa, a 1 x 30 mm strip in bending, reliability 0.99,
    the history 400 MPa -> -300 MPa (sigma_a = 350, sigma_m = 50 MPa):
      Se' = 585 MPa; ka = 4.51 * 1170^-0.265 = 0.69360; d_e = 0.808 sqrt(30) = 4.4256 mm,
      kb = (4.4256 / 7.62)^-0.107 = 1.05986; ke = 1 - 0.08 * 2.32635 = 0.81389;
      Se = 585 * 0.69360 * 1.05986 * 0.81389 = 350.01 MPa;
      sigma_f' = 1515 MPa, b = log10(585/1515) / log10(2e6) = -0.065586,
      f = 1515 * 2000^b / 1170 = 0.78655 (f Sut = 920.26 MPa);
      a = 920.26^2 / 350.01 = 2419.6 MPa, b' = -log10(920.26/350.01)/3 = -0.139944;
      Goodman: sigma_ar = 350 / (1 - 50/1170) = 365.625 MPa;
      N = (365.625 / 2419.6)^(1 / -0.139944) = 7.32e5 cycles
      (log10: -0.82071 / -0.139944 = 5.8645)."""
    history = np.array([[400e6], [0.0], [-300e6], [0.0]])
    life = strip_life(history, STEEL, DEPTH, WIDTH, reliability=0.99)
    assert life.endurance == pytest.approx(350.01e6, rel=2e-5)
    assert life.equivalent == pytest.approx(365.62e6, rel=2e-5)
    assert math.log10(life.cycles) == pytest.approx(5.8645, abs=2e-4)
    assert life.yield_margin == pytest.approx(880 / 400)


def test_goodman_at_zero_mean_is_the_fully_reversed_case():
    s = 420e6 * np.sin(np.linspace(0, 2 * np.pi, 73))[:, None]
    life = strip_life(s, STEEL, DEPTH, WIDTH)
    assert abs(life.mean) < 1e-6 * 420e6
    assert life.equivalent == pytest.approx(life.amplitude, rel=1e-12)


def test_life_scales_as_basquin_says():
    """N ~ sigma^(1/b'): scaling the stress by k scales the life by k^(1/b')."""
    s = np.array([[500e6], [-500e6]])
    one, two = (strip_life(k * s, STEEL, DEPTH, WIDTH) for k in (1.0, 1.1))
    b = math.log10(two.equivalent / one.equivalent) / math.log10(two.cycles / one.cycles)
    f = 1515 * 2000 ** (math.log10(585 / 1515) / math.log10(2e6)) / 1170
    assert b == pytest.approx(-math.log10(f * 1170e6 / one.endurance) / 3, rel=1e-9)


def test_below_the_endurance_limit_the_life_is_infinite_and_bad_reliability_is_refused():
    assert math.isinf(strip_life(np.array([[1e8], [-1e8]]), STEEL, DEPTH, WIDTH).cycles)
    with pytest.raises(InputError, match="reliability"):
        marin(1170e6, DEPTH, WIDTH, 1.0)
