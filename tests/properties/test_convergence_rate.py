"""Mesh convergence at the rate theory gives, for scenes built as a user builds them.

- Euler-Bernoulli links (cubic Hermite bending, consistent mass): the energy-norm error of the
  interpolant is O(h^2), so eigenvalue errors are O(h^4); a cantilever's frequencies converge
  at order 4 to the closed form (beta_n L = 1.8751, 4.6941), from above (Rayleigh-Ritz).
- Lumped (HRZ) mass spoils the consistent mass's accuracy: order 2.
- Timoshenko links (the interdependent interpolation element): the element's shear strain is
  constant along it (its shapes solve the static equations, where k G A gamma is constant), so
  the shear strain is approximated to O(h), its energy to O(h^2): eigenvalue errors O(h^2),
  visible once shear carries a fair share of the energy (a stubby cantilever).
- A frame of Euler-Bernoulli links: bisecting every element nests the trial spaces (cubic
  Hermite and linear axial both), so by the min-max principle no frequency can rise when the
  mesh is refined; the rate lies between the axial elements' 2 and the bending elements' 4.
"""

import itertools
import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from helpers import BETA_L
from strategies import cantilever_toml, fewer, linkages, load, log_uniform, write_scene

from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene



def orders(f: dict) -> np.ndarray:
    """Observed orders log2(|f_e - f_2e| / |f_2e - f_4e|) from three meshes e, 2e, 4e."""
    e = sorted(f)
    return np.log2(np.abs(f[e[0]] - f[e[1]]) / np.abs(f[e[1]] - f[e[2]]))


@st.composite
def cantilevers(draw, beam, slenderness):
    length = draw(log_uniform(0.05, 2.0))
    E = draw(log_uniform(1e9, 4e11))
    return cantilever_toml(length, draw(st.floats(-math.pi, math.pi)), E,
                           E / draw(st.floats(2.2, 30.0)), draw(st.floats(1000.0, 20000.0)),
                           length / draw(slenderness), length / draw(st.floats(5.0, 200.0)),
                           beam)


@given(cantilevers("euler-bernoulli", st.floats(20.0, 200.0)))
def test_euler_bernoulli_cantilever_converges_at_order_four_from_above(text):
    scene = load_scene(write_scene(text))
    s = scene.links[0].section
    length = scene.linkage.bodies[0].length
    exact = (np.array(BETA_L["cantilever"][:2]) ** 2 * math.sqrt(s.EI / (s.mass_per_length * length**4))
             / (2 * math.pi))
    f = {e: analyze(scene, 2, e).elastic_frequencies(2) for e in (4, 8, 16)}
    errors = {e: (fe - exact) / exact for e, fe in f.items()}
    for e, err in errors.items():
        # from above; the axial modes of a slender link lie far above modes 1 and 2
        assert np.all(err > 0), (e, err)
    observed = np.log2(errors[4] / errors[8]), np.log2(errors[8] / errors[16])
    # measured 3.97 and 3.99 (mode 1), 3.9 and 3.98 (mode 2): order 4 reached from below as
    # the mesh resolves the mode; 3.8 leaves room for the pre-asymptotic part at 4 elements
    assert np.all((np.array(observed) > 3.8) & (np.array(observed) < 4.1)), observed


@fewer
@given(cantilevers("euler-bernoulli", st.floats(20.0, 200.0)))
def test_lumped_mass_converges_at_order_two(text):
    scene = load_scene(write_scene(text))
    f = {e: analyze(scene, 1, e, mass="lumped").elastic_frequencies(1) for e in (8, 16, 32)}
    assert 1.9 < orders(f)[0] < 2.2, orders(f)


@fewer
@given(cantilevers("timoshenko", st.floats(4.0, 8.0)))
def test_timoshenko_cantilever_converges_at_order_two(text):
    scene = load_scene(write_scene(text))
    f = {e: analyze(scene, 2, e).elastic_frequencies(2) for e in (16, 32, 64)}
    # measured 2.01 to 2.06 for L/h 5 to 10 at these meshes (the h^4 part of the bending
    # energy still adds a little); an O(h^4) element would give about 4
    assert np.all((orders(f) > 1.9) & (orders(f) < 2.2)), orders(f)


@fewer
@given(linkages(beam="euler-bernoulli", elements=st.just(2)))
def test_refining_an_euler_bernoulli_frame_never_raises_a_frequency(spec):
    scene = load(spec)
    f = {e: analyze(scene, 3, e).elastic_frequencies(3) for e in (2, 4, 8, 16)}
    e = sorted(f)
    for coarse, fine in itertools.pairwise(e):
        # min-max on nested spaces: exact; 1e-12 only absorbs the eigen solve's round-off
        assert np.all(f[fine] <= f[coarse] * (1 + 1e-12)), (coarse, f[coarse], f[fine])
    rates = orders({k: f[k] for k in (4, 8, 16)})
    # between the axial elements' 2 and the bending elements' 4; at 4 elements the
    # pre-asymptotic part can still push a rate a little above 4 (measured up to 4.8 at 2)
    assert np.all((rates > 1.9) & (rates < 4.5)), rates
