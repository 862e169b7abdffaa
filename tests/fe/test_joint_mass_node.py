"""Which of a joint's coincident nodes carries its lumped mass, where the joint's finite springs
keep the nodes apart: the first attached link end's (the documented contract of
`JointSpec.mass`), checked against a two-mass spring chain.

Two steel bars along x: bar a from ground joint O (Kt = k1 in x and y, rotation held) to the
moving joint P (Kt = k, rotation rigid), bar b from P to a free end Q; a mass m on P. Along x
the bars move as rigid bodies on the springs (their own axial modes lie about 500 times
higher): ground -k1- M1 -k- M2, with M1 = bar a's mass and M2 = bar b's, the
joint mass added to the one whose node carries it. Its frequencies are the roots of
det([[k1 + k, -k], [-k, k]] - omega^2 diag(M1, M2)) = 0. The bars' axial flexibility lowers
them by about (beta L)^2 / 6 (beta L = omega L / c <= 6.3e-3: below 7e-6; measured 7.3e-6 at
most), so 2e-5 is the tolerance; the mass on the other node, or split, moves them by 10 % or
more.
"""

import math

import numpy as np
import pytest

from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model

from helpers import modes_of

STEEL = Section.rectangle(E=210e9, G=81e9, density=7850.0, width=0.02, thickness=0.02)
LENGTHS = {"a": 0.10, "b": 0.15}  # [m]
K1, K, MASS = 2e4, 1e4, 0.5  # [N/m], [N/m], [kg]
POINTS = {"O": (0.0, 0.0), "P": (LENGTHS["a"], 0.0), "Q": (LENGTHS["a"] + LENGTHS["b"], 0.0)}


def two_mass_chain(k1: float, k: float, m1: float, m2: float) -> np.ndarray:
    """Natural frequencies [Hz] of ground -k1- m1 -k- m2, in closed form: omega^2 solves
    m1 m2 w^4 - (m1 k + m2 (k1 + k)) w^2 + k1 k = 0."""
    b = m1 * k + m2 * (k1 + k)
    root = math.sqrt(b * b - 4 * m1 * m2 * k1 * k)
    return np.sqrt([(b - root) / (2 * m1 * m2), (b + root) / (2 * m1 * m2)]) / (2 * math.pi)


def axial_frequencies(order: tuple[str, str]) -> np.ndarray:
    """The two lowest axial (x) frequencies [Hz] of the two-bar model, its links listed in
    ``order``: the modes whose shapes have no y or rotation part."""
    links = {"a": LinkSpec("a", "O", "P", STEEL, 4), "b": LinkSpec("b", "P", "Q", STEEL, 4)}
    joints = (JointSpec("O", ground=True, Kt=K1, Kr=math.inf),
              JointSpec("P", ground=False, Kt=K, Kr=math.inf, mass=MASS),
              JointSpec("Q", ground=False, Kt=0.0, Kr=0.0))
    model = build_model(Topology(links=tuple(links[name] for name in order), joints=joints),
                        POINTS)
    result = modes_of(model, 12)
    shapes = result.shapes.reshape(-1, 3, result.shapes.shape[1])
    # bars along x: axial and transverse motion decouple exactly, so a mode is one or the other
    axial = [i for i in result.elastic
             if np.abs(shapes[:, 1:, i]).max() < 1e-9 * np.abs(shapes[:, 0, i]).max()]
    return result.frequencies[axial[:2]]


def bar_mass(name: str) -> float:
    return STEEL.mass_per_length * LENGTHS[name]


@pytest.mark.parametrize("order", [("a", "b"), ("b", "a")], ids=["a first", "b first"])
def test_the_first_attached_link_end_carries_the_joint_mass(order):
    first = order[0]
    m1 = bar_mass("a") + (MASS if first == "a" else 0.0)
    m2 = bar_mass("b") + (MASS if first == "b" else 0.0)
    expected = two_mass_chain(K1, K, m1, m2)
    np.testing.assert_allclose(axial_frequencies(order), expected, rtol=2e-5)
    # the other placement is far outside that tolerance: the test tells them apart
    other = two_mass_chain(K1, K, bar_mass("a") + MASS - (m1 - bar_mass("a")),
                           bar_mass("b") + MASS - (m2 - bar_mass("b")))
    assert np.abs(other / expected - 1).max() > 0.1
