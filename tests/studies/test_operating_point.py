"""Modes at an operating point against physics: the static modes at zero speed, Southwell's
rotating cantilever, the Coriolis coupling's slenderness law, and divergence where the
centrifugal softening overtakes the bar's stiffness."""

import dataclasses
import math

import numpy as np
import pytest

from conftest import CASES_DIR, SCENES_DIR
from flexlink.analysis.modal import analyze
from flexlink.fe.model import Section
from flexlink.scene import load_scene
from flexlink.studies.running.modes_at_speed import Terms, operating_modes

ROTOR = SCENES_DIR / "rotor.toml"
# In-plane (lead-lag) bending of a rotating cantilever without hub, Coriolis coupling left out:
# omega^2 = omega_flap^2 - Omega^2, omega_flap the flapping frequency with the centrifugal
# tension (Southwell); nondimensional by sqrt(EI / (rhoA L^4)), at lambda = Omega / that
# = 0 ... 5 (Hodges & Rutkowski 1981; Wright et al. 1982), printed to 5 digits.
SOUTHWELL = (3.5160, 3.6816, 4.1373, 4.7973, 5.5850, 6.4495)


def rotor(depth: float | None = None):
    scene = load_scene(ROTOR)
    if depth is None:
        return scene
    s = scene.links[0].section
    section = Section.rectangle(s.E, s.G, s.density, depth, s.area / s.depth)
    return dataclasses.replace(scene, links=(dataclasses.replace(scene.links[0],
                                                                  section=section),))


def bending_scale(scene) -> float:
    s, L = scene.links[0].section, 1.0
    return math.sqrt(s.EI / (s.mass_per_length * L**4))


@pytest.mark.parametrize("path, elements", [(CASES_DIR / "case1.toml", 8),
                                            (SCENES_DIR / "kineto_aluminium.toml", 8),
                                            (ROTOR, 16),
                                            # sparse path; plain eigenvalues 1.2e-9 off here
                                            (CASES_DIR / "case1.toml", 64)])
def test_zero_speed_gives_the_static_modes(path, elements):
    scene = load_scene(path)
    static = analyze(scene, 4, elements).elastic_frequencies(4)
    op = operating_modes(scene, 0.0, 4, elements)
    # both are Rayleigh quotients of round-off-accurate vectors: agreement to ~1e-13
    np.testing.assert_allclose(op.frequencies, static, rtol=1e-10)
    np.testing.assert_allclose(op.mac, 1.0, rtol=1e-10)
    assert np.all(op.modes.growth_rates == pytest.approx(0.0, abs=1e-9))
    assert op.largest_axial.value == 0.0


def test_rotating_cantilever_follows_southwell():
    """At 64 elements the lead-lag frequency (Coriolis off) gives omega_flap =
    sqrt(omega^2 + Omega^2) within 1e-4 of the published values at every lambda: the tension
    of the inertia preload (K_g) stiffens, the centrifugal term softens by exactly Omega^2.
    Measured: 2.0e-5 at 64 elements (K_g from constant N per element: order h^2)."""
    scene = rotor()
    scale = bending_scale(scene)
    computed = []
    for lam in range(len(SOUTHWELL)):
        op = operating_modes(scene, lam * scale, 1, 64, terms=Terms(coriolis=False))
        w = 2 * math.pi * op.frequencies[0] / scale
        computed.append(math.sqrt(w * w + lam * lam))
    np.testing.assert_allclose(computed, SOUTHWELL, rtol=1e-4)


def coriolis_shift(scene, lam=4.0, elements=32):
    """Relative change of the first lead-lag frequency when the Coriolis coupling is added."""
    speed = lam * bending_scale(scene)
    without = operating_modes(scene, speed, 1, elements, terms=Terms(coriolis=False))
    with_ = operating_modes(scene, speed, 1, elements)
    return with_.frequencies[0] / without.frequencies[0] - 1


def test_coriolis_shift_shrinks_as_the_bar_gets_slender():
    """The Coriolis term couples bending to the axial motion, whose frequencies stand
    (L / depth) times higher: at a fixed lambda the shift goes as (depth / L)^2. Measured
    -1.0e-4 at L/depth = 100 and a quarter of it at 200."""
    stubby, slender = coriolis_shift(rotor(0.01)), coriolis_shift(rotor(0.005))
    assert stubby < -5e-5  # it lowers the frequency, measurably
    # the law holds to the next order in (depth / L)^2 (measured ratio 4.0003)
    assert stubby / slender == pytest.approx(4.0, rel=1e-3)


def test_centrifugal_softening_diverges_past_the_first_frequency():
    """Without the preload and Coriolis, K - Omega^2 Mt loses definiteness exactly where
    Omega passes the first bending frequency: reported, never a frequency."""
    scene = rotor()
    static = analyze(scene, 1, 16).elastic_frequencies(1)[0] * 2 * math.pi
    terms = Terms(preload=False, coriolis=False)
    below = operating_modes(scene, 0.99 * static, 1, 16, terms=terms)
    assert below.modes.stable and below.modes.negative_stiffness == 0
    assert below.frequencies[0] == pytest.approx(static * math.sqrt(1 - 0.99**2) / (2 * math.pi),
                                                 rel=1e-9)
    above = operating_modes(scene, 1.01 * static, 1, 16, terms=terms)
    assert above.modes.negative_stiffness == 1 and not above.modes.stable
    s = above.modes.eigenvalues[0]
    assert abs(s.imag) < 1e-12 * abs(s)  # a real root: no oscillation, pure growth
    assert s.real == pytest.approx(static * math.sqrt(1.01**2 - 1), rel=1e-9)


def test_four_bar_at_speed_is_paired_and_reports_its_preload():
    scene = load_scene(CASES_DIR / "case1.toml")
    op = operating_modes(scene, 2000 * 2 * math.pi / 60, 4, 8)
    assert np.all(op.mac > 0.9) and list(op.static_index) == [0, 1, 2, 3]
    largest = max((abs(N).max(), name) for name, N in op.axial_forces.items())
    assert (abs(op.largest_axial.value), op.largest_axial.link) == largest
    # with the crank at constant speed the coupler and rocker still accelerate angularly
    assert op.link_alpha[0] == 0.0 and np.all(op.link_alpha[1:] != 0.0)


def test_an_external_load_joins_the_preload(tmp_path):
    """A tension F pulling the rotor's tip along the bar puts N = F in every element at rest,
    and the bending frequencies rise with it (a tensioned cantilever), where the static modes
    see nothing."""
    path = tmp_path / "pulled.toml"
    path.write_text(f'base = "{ROTOR.as_posix()}"\n[[loads]]\nkind = "force"\nlink = "rotor"\n'
                    'force = ["50 N", "0 N"]\nat = ["1 m", "0 m"]\nframe = "body"\n')
    scene = load_scene(path)
    op = operating_modes(scene, 0.0, 2, 8)
    for N in op.axial_forces.values():
        np.testing.assert_allclose(N, 50.0, rtol=1e-12)  # statically determinate: exact
    assert np.all(op.frequencies > op.static_frequencies)
    off = operating_modes(scene, 0.0, 2, 8, terms=Terms(preload=False))
    np.testing.assert_allclose(off.frequencies, off.static_frequencies, rtol=1e-10)
