"""A linkage's natural frequencies and mode shapes do not depend on where it stands: moving,
turning or mirroring the whole linkage in its plane changes the numbers only by round-off,
and each mode shape is the old one carried along (its displacements turned, its rotations
turned with the orientation's sign). The four-bar scene kind and the same linkage written as
a general scene of bodies are one physical object and give the same answer."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from strategies import linkages, load, placements

from flexlink.analysis.modal import Mass, analyze

N_MODES = 3
# Frequencies: the placed scene differs from the original only by the round-off of placing
# its joints (cos, sin, the general scene's Newton solve to 1e-13 of the linkage size) and
# the eigen solver's backward error (~1e-15); 1e-9 leaves three orders of margin.
FREQ_RTOL = 1e-9
# Shapes: a mode's vector moves by about (perturbation / relative gap to its neighbours);
# modes at least GAP apart therefore keep MAC above 1 - 1e-8.
GAP, MAC_MIN = 1e-3, 1 - 1e-8


def carried(shapes: np.ndarray, R: np.ndarray) -> np.ndarray:
    """Full-DOF shapes (ux, uy, rz per node) turned by the 2x2 orthogonal R: displacements by
    R, rotations by det R (a mirror reverses the sense of rotation)."""
    out = np.array(shapes, dtype=float)
    ux, uy = shapes[0::3], shapes[1::3]
    out[0::3] = R[0, 0] * ux + R[0, 1] * uy
    out[1::3] = R[1, 0] * ux + R[1, 1] * uy
    out[2::3] = np.linalg.det(R) * shapes[2::3]
    return out


def mac(a: np.ndarray, b: np.ndarray) -> float:
    return float((a @ b) ** 2 / ((a @ a) * (b @ b)))


def separated(freqs: np.ndarray) -> np.ndarray:
    """Indices of modes whose frequency is at least GAP (relative) from every other one."""
    f = np.asarray(freqs)
    out = []
    for i, fi in enumerate(f):
        others = np.delete(f, i)
        if not others.size or np.min(np.abs(others - fi)) > GAP * max(fi, f.max() * 1e-6):
            out.append(i)
    return np.array(out, dtype=int)


@given(linkages(kind="four-bar"), placements(), st.sampled_from(tuple(Mass)))
def test_moving_turning_and_mirroring_the_linkage_changes_nothing(spec, placement, mass):
    here = analyze(load(spec), N_MODES, mass=mass)
    moved = spec.placed(*placement)
    there = analyze(load(moved), N_MODES, mass=mass)
    assert here.modes.kinds == there.modes.kinds
    np.testing.assert_allclose(there.modes.frequencies, here.modes.frequencies,
                               rtol=FREQ_RTOL, atol=FREQ_RTOL * here.modes.frequencies.max())
    expected = carried(here.modes.shapes, np.array(moved.rotation_matrix()))
    for i in separated(here.modes.frequencies):
        assert mac(expected[:, i], there.modes.shapes[:, i]) > MAC_MIN, i


@given(linkages(kind="four-bar"))
def test_the_four_bar_kind_and_the_same_linkage_as_bodies_agree(spec):
    fourbar = analyze(load(spec), N_MODES)
    general = analyze(load(spec.placed()), N_MODES)
    assert fourbar.modes.kinds == general.modes.kinds
    np.testing.assert_allclose(general.modes.frequencies, fourbar.modes.frequencies,
                               rtol=FREQ_RTOL, atol=FREQ_RTOL * fourbar.modes.frequencies.max())
