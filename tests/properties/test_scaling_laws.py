"""Exact scaling laws of the linkage's natural frequencies, from the form of K and M.

- Modulus: E (and G) times s, with every finite joint and drive spring times s: K -> s K,
  M unchanged, so f -> sqrt(s) f. Rigid joints stay rigid, free ones free.
- Density: rho times s with the joint masses times s: M -> s M, so f -> f / sqrt(s).
- Size (complete geometric similarity): every length, the link lengths and the section's
  dimensions alike, times s. Per element EA / h and 12 EI / h^3 scale as s, rho A h as s^3,
  rho I h as s^5 and 4 EI / h as s^3, so the law f -> f / s is exact only when the joints scale
  the same way: Kt times s (a force per length, like EA / h), Kr and the drive times s^3 (a
  moment per radian, like EI / h) and joint masses times s^3. With the sections kept fixed
  there is no exact law (axial and bending terms scale differently, see test_energy_identities
  for the exact first-order law that the strain fractions give); a bound still holds: for
  s >= 1, rigid Kt, Kr zero or rigid, and joint masses times s, every eigenvalue lies
  between lambda / s^4 (all bending) and lambda / s^2 (all axial), i.e. f / s^2 <= f' <= f / s.
- In-plane depth of the sections times s (A times s, I times s^3), Euler-Bernoulli links,
  rigid Kt, Kr zero or rigid, no joint masses: K' = s K_axial + s^3 K_bending, M' = s M, so
  for s >= 1 every frequency lies between f (all axial) and s f (all bending).
- Out-of-plane size: an edgewise bar's thickness (or A and I together) times s, with springs
  and joint masses times s: K -> s K and M -> s M, so f does not change.
"""

import dataclasses
import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from strategies import RIGID, JointValues, linkages, load, scaled

from flexlink.analysis.modal import analyze

N_MODES = 3
# Each law is exact; the two models differ only by round-off in their inputs (the scene file
# writes 17 significant digits) and in the eigen solve (backward error ~1e-15 amplified by
# the eigenvalue condition, small for these coarse meshes): 1e-9 leaves a wide margin.
RTOL = 1e-9

factors = st.floats(0.25, 4.0).filter(lambda s: abs(s - 1) > 0.05)


def frequencies(spec, n=N_MODES):
    result = analyze(load(spec), n)
    return result.modes.frequencies, result.modes.kinds


def assert_law(before, after, factor):
    f0, kinds0 = before
    f1, kinds1 = after
    assert kinds0 == kinds1
    np.testing.assert_allclose(f1, factor * f0, rtol=RTOL, atol=RTOL * factor * f0.max())


@given(linkages(), factors)
def test_frequencies_scale_with_the_square_root_of_the_modulus(spec, s):
    assert_law(frequencies(spec), frequencies(scaled(spec, E=s, Kt=s, Kr=s)), math.sqrt(s))


@given(linkages(), factors)
def test_frequencies_scale_with_one_over_the_square_root_of_density(spec, s):
    assert_law(frequencies(spec), frequencies(scaled(spec, density=s, mass=s)), 1 / math.sqrt(s))


@given(linkages(), factors)
def test_a_geometrically_similar_linkage_has_frequencies_one_over_its_size(spec, s):
    similar = scaled(spec, length=s, section=s, across=s, Kt=s, Kr=s**3, mass=s**3)
    assert_law(frequencies(spec), frequencies(similar), 1 / s)


@given(linkages(beam="euler-bernoulli"), st.floats(1.1, 4.0), st.sampled_from((0.0, RIGID)))
def test_longer_links_on_the_same_sections_lie_between_the_axial_and_bending_laws(spec, s, kr):
    """f / s^2 <= f' <= f / s for s >= 1 (Courant-Fischer with u' = s u on translations):
    K' = s K_axial + K_bending / s and M' = s^3 M when Kt is rigid, Kr is 0 or rigid and
    joint masses scale as s (a joint mass m moving s u has s^2 m u^2: times s, it is s^3)."""
    joints = {n: JointValues(RIGID, kr, j.mass) for n, j in spec.joints.items()}
    drive = None if spec.drive is None else RIGID
    spec = dataclasses.replace(spec, joints=joints, drive=drive)
    f0, kinds0 = frequencies(spec)
    f1, kinds1 = frequencies(scaled(spec, length=s, mass=s))
    assert kinds0 == kinds1
    elastic = np.array([k == "elastic" for k in kinds0])
    f0, f1 = f0[elastic], f1[elastic]
    # the bounds are exact; RTOL only absorbs round-off where a mode sits on one of them
    assert np.all(f1 >= f0 / s**2 * (1 - RTOL))
    assert np.all(f1 <= f0 / s * (1 + RTOL))


@given(linkages(), factors)
def test_the_out_of_plane_size_does_not_change_in_plane_frequencies(spec, s):
    assert_law(frequencies(spec), frequencies(scaled(spec, across=s, Kt=s, Kr=s, mass=s)), 1.0)


@given(linkages(beam="euler-bernoulli", masses=False), st.floats(1.1, 4.0),
       st.sampled_from((0.0, RIGID)))
def test_deeper_sections_lie_between_the_axial_and_bending_laws(spec, s, kr):
    """f <= f' <= s f for s >= 1 (Courant-Fischer on K' = s K_axial + s^3 K_bending,
    M' = s M; the exact first-order law is in test_energy_identities)."""
    joints = {n: JointValues(RIGID, kr, 0.0) for n in spec.joints}
    spec = dataclasses.replace(spec, joints=joints,
                               drive=None if spec.drive is None else RIGID)
    f0, kinds0 = frequencies(spec)
    f1, kinds1 = frequencies(scaled(spec, section=s))
    assert kinds0 == kinds1
    elastic = np.array([k == "elastic" for k in kinds0])
    f0, f1 = f0[elastic], f1[elastic]
    assert np.all(f1 >= f0 * (1 - RTOL))  # exact bounds; RTOL absorbs round-off
    assert np.all(f1 <= s * f0 * (1 + RTOL))
