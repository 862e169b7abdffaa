"""The fatigue chain (``materials.fatigue``, ``analysis.fatigue``): a worked example with its
Marin factors written out by hand, Goodman at zero mean, Basquin scaling of the life, the
rainflow count of one turn, and refusals of missing data."""

import math

import numpy as np
import pytest

from flexlink.analysis.fatigue import (MeanStress, equivalent_amplitude, history_fatigue,
                                       safety_factor, turn_cycles)
from flexlink.errors import InputError
from flexlink.materials.fatigue import (LoadType, PartCurve, Surface, marin_factors,
                                        rectangle_diameter, reliability_factor,
                                        specimen_curve)
from flexlink.materials.strength import load_strength

MPA = 1e6
TURN = 2 * np.pi * np.arange(360) / 360


def _sine(amplitude, mean, phase=0.3):
    return mean + amplitude * np.sin(TURN + phase)


def _part(reliability=0.99):
    specimen = specimen_curve(load_strength("aisi_1080"))
    marin = marin_factors(specimen.Sut, Surface.MACHINED, rectangle_diameter(0.030, 0.001),
                          LoadType.BENDING, 20.0, reliability)
    return PartCurve(specimen, marin)


def test_worked_example_by_hand():
    """The compliant wiper's strip steel, AISI 1080 Q&T 315 C, from its material file's data:
    Sut = 1300 MPa, Sy = 980 MPa, Se' = 650 MPa, sigma_f' = 1645 MPa; a machined 30 x 1 mm
    strip in bending at 20 C, 99 % reliability, cycled at sigma_a = 300 MPa about
    sigma_m = 200 MPa. Each step by hand (Shigley, 9th ed., ch. 6), independent of the code:"""
    Sut, Se_prime, sf = 1300.0, 650.0, 1645.0  # MPa
    # Basquin exponent of the specimen through (2e6 reversals, Se'): b = log(Se'/sf) / log(2e6)
    b = math.log(Se_prime / sf) / math.log(2e6)  # = -0.06400
    assert b == pytest.approx(-0.06400, abs=1e-5)
    f = sf * 2000.0**b / Sut  # fraction of Sut at 1e3 cycles = 0.7780
    assert f == pytest.approx(0.7780, abs=1e-4)
    ka = 4.51 * Sut**-0.265  # machined: 0.6745
    de = 0.808 * math.sqrt(30.0 * 1.0)  # equivalent diameter of the 30 x 1 mm rectangle: 4.426 mm
    kb = 1.24 * de**-0.107  # 2.79 <= de <= 51 mm: 1.0576
    kc, kd = 1.0, 1.0  # bending; room temperature
    ke = 1 - 0.08 * 2.32635  # 99 % reliability, z = 2.32635 (normal table): 0.8139
    Se = ka * kb * kc * kd * ke * Se_prime  # = 377.4 MPa
    assert Se == pytest.approx(377.4, abs=0.1)
    a = (f * Sut) ** 2 / Se
    B = -math.log10(f * Sut / Se) / 3
    sa, sm = 300.0, 200.0
    sar = sa / (1 - sm / Sut)  # Goodman: 354.5 MPa, below Se: infinite life
    assert sar < Se
    n = 1 / (sa / Se + sm / Sut)  # Goodman safety factor, proportional loading: 1.0540
    part = _part()
    marin = part.marin
    for computed, hand in ((marin.ka, ka), (marin.kb, kb), (marin.kc, kc), (marin.kd, kd)):
        assert computed == pytest.approx(hand, rel=1e-12)
    assert marin.ke == pytest.approx(ke, rel=1e-6)  # z to 5 decimals by hand
    assert part.endurance / MPA == pytest.approx(Se, rel=1e-6)
    result = history_fatigue(_sine(sa * MPA, sm * MPA, phase=0.0), part)
    assert result.cycles == 1
    assert result.safety == pytest.approx(n, rel=1e-6)  # the samples hold the sine's peaks
    assert math.isinf(result.life)
    # a larger cycle lives finitely: sigma_a = 450 MPa, sigma_ar = 531.8 MPa, a = 2710 MPa,
    # B = -0.1427 -> N = (sar / a)^(1/B) = 9.04e4 cycles
    sar2 = 450.0 / (1 - sm / Sut)
    N = (sar2 / a) ** (1 / B)
    assert 1e3 < N < 1e6
    finite = history_fatigue(_sine(450 * MPA, sm * MPA, phase=0.0), part)
    assert finite.life == pytest.approx(N, rel=1e-5)
    assert finite.yield_safety == pytest.approx(980.0 / 650.0, rel=1e-12)


@pytest.mark.parametrize("method", list(MeanStress))
def test_zero_mean_is_fully_reversed(method):
    """At zero mean every correction but SWT leaves the amplitude alone; SWT's
    sqrt(sigma_max sigma_a) is the amplitude too. So the life equals the fully reversed one."""
    specimen = _part().specimen
    sa = np.array([100.0, 400.0, 700.0]) * MPA
    np.testing.assert_allclose(equivalent_amplitude(sa, 0.0, specimen, method), sa, rtol=1e-12)
    np.testing.assert_allclose(safety_factor(sa, 0.0, 368e6, specimen, method), 368e6 / sa,
                               rtol=1e-12)


def test_goodman_mean_lowers_the_strength():
    """A tensile mean raises the equivalent amplitude by 1 / (1 - sigma_m / Sut); a
    compressive one is given no credit."""
    specimen = _part().specimen
    sa, sm = 300e6, 650e6
    assert equivalent_amplitude(sa, sm, specimen)[()] == pytest.approx(600e6, rel=1e-12)
    assert equivalent_amplitude(sa, -sm, specimen)[()] == pytest.approx(sa, rel=1e-12)


def test_life_scales_as_basquin_says():
    """On the finite-life line N = (sigma_ar / a)^(1/B): scaling the whole stress history by
    s scales the life by s^(1/B) (Goodman's ratio 1 - sigma_m / Sut changes with s, so at
    zero mean)."""
    part = _part()
    base = history_fatigue(_sine(500e6, 0.0), part)
    scaled = history_fatigue(_sine(1.15 * 500e6, 0.0), part)
    assert 1e3 < scaled.life < base.life < 1e6
    assert scaled.life / base.life == pytest.approx(1.15 ** (1 / part.exponent), rel=1e-9)


def test_rainflow_of_one_turn():
    """A sine is one cycle of its range about its mean; adding a third harmonic puts two
    small cycles inside a large one."""
    one = turn_cycles(_sine(2.0, 3.0))
    assert len(one.amplitude) == 1
    assert one.amplitude[0] == pytest.approx(2.0, rel=1e-4)
    assert one.mean[0] == pytest.approx(3.0, rel=1e-4)
    y = 1 + np.sin(TURN) + 0.5 * np.sin(3 * TURN)
    three = turn_cycles(y)
    assert len(three.amplitude) == 3
    assert three.amplitude.max() == pytest.approx((y.max() - y.min()) / 2, rel=1e-12)


def test_missing_strength_names_file_and_key(tmp_path):
    """A material file without an endurance datum is refused with its path and key."""
    path = tmp_path / "bare.toml"
    path.write_text('name = "bare"\nE = { mean = "200 GPa" }\nG = { mean = "80 GPa" }\n'
                    'density = { mean = "7800 kg/m^3" }\npoisson = { mean = 0.3 }\n'
                    '[strength]\nSut = { mean = "600 MPa" }\nSy = { mean = "400 MPa" }\n')
    with pytest.raises(InputError, match=r"bare\.toml: strength\.fatigue_coefficient"):
        specimen_curve(load_strength(str(path)))
    path.write_text(path.read_text().replace('Sy = { mean = "400 MPa" }\n', ""))
    with pytest.raises(InputError, match=r"bare\.toml: strength\.Sy"):
        specimen_curve(load_strength(str(path)))


@pytest.mark.parametrize("bad", [0.0, 1.0, -0.5, 1.2, float("nan")])
def test_reliability_outside_0_1_is_refused(bad):
    with pytest.raises(InputError, match="--reliability"):
        reliability_factor(bad)
