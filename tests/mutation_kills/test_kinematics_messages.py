"""The kinematics refusals read as whole sentences: what was refused, the value, the field and
the expected unit or range (the user sees these lines as they are, prefixed by the file)."""

import math

import pytest

from flexlink.errors import InputError
from flexlink.kinematics.fourbar import FourBar
from flexlink.kinematics.linkage import Body, Linkage
from flexlink.kinematics.synthesis import brodell_soni, minimax


def test_a_link_length_names_the_link_and_the_unit():
    with pytest.raises(InputError) as err:
        FourBar(ground=1.0, crank=0.2, coupler=-0.5, rocker=0.6)
    assert (err.value.field, err.value.expected) == ("coupler", "length > 0 m")
    assert str(err.value) == ("coupler: link length must be a positive finite number, got -0.5 "
                              "(expected length > 0 m)")


def test_the_driver_and_the_mobility_refusals():
    with pytest.raises(InputError) as err:
        Linkage(ground={"O": (0.0, 0.0)}, bodies=(Body.bar("crank", "A", "O", 1.0),),
                driver="crank")
    assert str(err.value) == ("linkage.driver: driver 'crank' must turn about a ground pivot "
                              "(its first joint)")
    with pytest.raises(InputError) as err:
        Linkage(ground={"O": (0.0, 0.0)}, bodies=(Body.bar("crank", "O", "A", 1.0),
                                                  Body.bar("free", "A", "B", 1.0)), driver="crank")
    assert str(err.value) == ("bodies: 3 loop equations for 4 unknown coordinates: the linkage "
                              "must have exactly one degree of freedom")


def test_the_synthesis_refusals_name_the_inputs_in_degrees():
    theta4i, delta = math.radians(10.0), math.radians(30.0)
    mu_min = math.pi / 2 - delta  # M^2 + N^2 of the mini-max construction, here below 1
    s = (math.sin(theta4i) ** 2 + math.sin(theta4i - mu_min) ** 2) / math.sin(mu_min) ** 2
    with pytest.raises(InputError) as err:
        minimax(theta4i, delta)
    assert str(err.value) == (f"theta4i: theta4i = 10 deg and delta = 30 deg give M^2 + N^2 = "
                              f"{s:.4g} <= 1: no crank-rocker")
    with pytest.raises(InputError) as err:
        brodell_soni(math.radians(95.0), math.radians(40.0))
    assert str(err.value) == ("gamma_min/swing: need 0 < gamma_min < 90 deg and 0 < swing < 180 "
                              "deg")
    with pytest.raises(InputError) as err:  # the rocker-to-ground ratio would exceed 1
        brodell_soni(math.radians(80.0), math.radians(170.0))
    assert str(err.value) == ("gamma_min: gamma_min = 80 deg with swing 170 deg has no "
                              "crank-rocker")
