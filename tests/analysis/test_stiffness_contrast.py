"""The eigen solve on links whose stiffness differs 100 times: the solver's scales (the
eigenvalue scale of the softest link, the shift, the rigid-spring threshold of the stiffest
element, the energy-refined quotients) must give the frequencies of the physics, whichever link
is the soft one.

Two references written here without flexlink's solver: the exact frequency equation of a
stepped cantilever (transfer matrices of the Euler-Bernoulli segments), and scipy's dense
generalized eigensolver on the assembled, constraint-eliminated matrices of a four-bar scene.
"""

import math

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.optimize import brentq

from flexlink.analysis.modal import analyze
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model
from flexlink.scene import load_scene

from conftest import CASES_DIR
from helpers import modes_of

CONTRAST = 100.0
STIFF = Section.rectangle(E=210e9, G=81e9, density=7850.0, width=0.01, thickness=0.005)
SOFT = Section.rectangle(E=210e9 / CONTRAST, G=81e9 / CONTRAST, density=7850.0, width=0.01,
                         thickness=0.005)
LENGTH = 0.5  # [m] each segment
ELEMENTS = 16


def segment_transfer(section: Section, length: float, omega: float) -> np.ndarray:
    """The transfer matrix of (w, w', EI w'', EI w''') along one uniform segment at omega."""
    beta = (section.mass_per_length * omega**2 / section.EI) ** 0.25

    def basis(x):
        b = beta * x
        c, s, ch, sh = math.cos(b), math.sin(b), math.cosh(b), math.sinh(b)
        ei = section.EI
        return np.array([[c, s, ch, sh],
                         [-beta * s, beta * c, beta * sh, beta * ch],
                         [-ei * beta**2 * c, -ei * beta**2 * s, ei * beta**2 * ch, ei * beta**2 * sh],
                         [ei * beta**3 * s, -ei * beta**3 * c, ei * beta**3 * sh, ei * beta**3 * ch]])
    return basis(length) @ np.linalg.inv(basis(0.0))


def stepped_cantilever(sections, lengths, count: int) -> np.ndarray:
    """The lowest ``count`` bending frequencies [Hz] of a cantilever of welded uniform segments
    (root first): clamped root (w = w' = 0), free tip (moment = shear = 0), by bracketing the
    roots of the 2 x 2 determinant on a fine grid and bisecting."""
    def det(omega):
        T = np.eye(4)
        for section, length in zip(sections, lengths):
            T = segment_transfer(section, length, omega) @ T
        return np.linalg.det(T[2:, 2:])
    # the first root is above the soft whole beam's and below the stiff one's: scan past both
    soft = min(s.EI / s.mass_per_length for s in sections)
    lowest = 3.5 * math.sqrt(soft / sum(lengths) ** 4)
    grid = np.geomspace(0.2 * lowest, 400 * lowest, 20000)
    values = np.array([det(w) for w in grid])
    roots = [brentq(det, a, b, xtol=1e-13 * b)
             for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:]) if fa * fb < 0]
    return np.array(roots[:count]) / (2 * math.pi)


def fe_bending(sections) -> np.ndarray:
    """flexlink's lowest bending frequencies [Hz] of the stepped cantilever along x (bending
    and axial motion decouple there: a bending mode has no x part)."""
    topology = Topology(
        links=(LinkSpec("root", "O", "P", sections[0], ELEMENTS),
               LinkSpec("tip", "P", "Q", sections[1], ELEMENTS)),
        joints=(JointSpec("O", ground=True, Kt=math.inf, Kr=math.inf),
                JointSpec("P", ground=False, Kt=math.inf, Kr=math.inf),
                JointSpec("Q", ground=False, Kt=0.0, Kr=0.0)))
    model = build_model(topology, {"O": (0.0, 0.0), "P": (LENGTH, 0.0), "Q": (2 * LENGTH, 0.0)})
    result = modes_of(model, 6)
    shapes = result.shapes.reshape(-1, 3, result.shapes.shape[1])
    bending = [i for i in result.elastic
               if np.abs(shapes[:, 0, i]).max() < 1e-9 * np.abs(shapes[:, 1, i]).max()]
    return result.frequencies[bending]


@pytest.mark.parametrize("order", [(STIFF, SOFT), (SOFT, STIFF)], ids=["soft tip", "soft root"])
def test_a_stepped_cantilever_matches_its_exact_frequencies(order):
    # cubic elements converge at h^4 in the eigenvalue, from above (Rayleigh-Ritz): at 16
    # elements a segment the third mode is 8.0e-6 above the exact one with the soft tip and
    # 6.8e-6 with the soft root (measured; 1.2e-4 and 1.1e-4 at 8, 16 times less at 32), so
    # 0 <= error < 1.5e-5 (less 1e-9 for round-off); a solve that lost the soft segment's
    # share (its stiffness or mass scaled by the stiff one's) is off by percents
    exact = stepped_cantilever(order, (LENGTH, LENGTH), 3)
    error = fe_bending(order)[:3] / exact - 1
    assert np.all(error > -1e-9) and np.all(error < 1.5e-5), error
    assert exact[0] > 0 and np.all(np.diff(exact) > 0)


@pytest.mark.parametrize("soft", ["crank", "coupler", "rocker"])
def test_a_scene_with_one_link_100_times_softer_matches_a_dense_solve(soft):
    # case 1 with one link's material 100 times softer (E and G; the same density): flexlink's
    # frequencies against scipy.linalg.eigh on T^T K T, T^T M T of the same model. Both are
    # round-off accurate: eps lambda_max / lambda_1 (computed below, times 10 for the norms)
    # bounds their gap; the soft link moves the first frequency by tens of percent
    plain = load_scene(CASES_DIR / "case1.toml")
    section = plain.topology(8).links[0].section
    material = {"E": f"{section.E / CONTRAST!r} Pa", "G": f"{section.G / CONTRAST!r} Pa",
                "density": f"{section.density!r} kg/m^3"}
    scene = load_scene(CASES_DIR / "case1.toml",
                       overrides={f"links.{soft}.material": material})
    stiffness = {l.name: l.section.EI for l in scene.topology(8).links}
    others = [v for name, v in stiffness.items() if name != soft]
    np.testing.assert_allclose(np.array(others) / stiffness[soft], CONTRAST, rtol=1e-12)
    result = analyze(scene, 4, 8)
    K, M = assemble(result.model)
    T = rigid_elimination(result.model)
    Kr, Mr = ((K, M) if T is None else (T.T @ K @ T, T.T @ M @ T))
    Kr, Mr = (np.asarray(A.todense()) for A in (Kr, Mr))
    values = sla.eigh(Kr, Mr, eigvals_only=True)  # the drive holds the crank: all elastic
    reference = np.sqrt(values[:4]) / (2 * math.pi)
    bound = 10 * np.finfo(float).eps * (np.diag(Kr) / np.diag(Mr)).max() / values[0]
    assert values[0] > 0 and bound < 1e-5
    np.testing.assert_allclose(result.elastic_frequencies(4), reference, rtol=bound)
    assert abs(analyze(plain, 1, 8).elastic_frequencies(1)[0] / reference[0] - 1) > 0.1
