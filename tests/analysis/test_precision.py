"""The round-off estimate made before assembly, against the assembled model itself: its
lambda_max is the largest diagonal ratio K_ii / M_ii of the assembled matrices and its lambda_1
the first free-free bending eigenvalue of the link, so the ratio must match one recomputed from
them; it grows as n^2 (axial term) then n^4 (rotation term), ``finest_supported`` is the last mesh under a limit, and the refusal
names the mesh, the limit and the DOFs it spared."""

import numpy as np
import pytest

from flexlink.analysis.precision import finest_supported, refuse_too_fine, roundoff_ratio
from flexlink.errors import NumericalError
from flexlink.fe.assembly import assemble
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model

from helpers import SECTION, modes_of

EPS = np.finfo(float).eps
POINTS = {"S": (0.0, 0.0), "E": (0.6, 0.8)}  # a 1 m link at an angle


def free_beam(elements, section=SECTION):
    joints = (JointSpec("S", ground=False, Kt=0.0, Kr=0.0),
              JointSpec("E", ground=False, Kt=0.0, Kr=0.0))
    return Topology(links=(LinkSpec("beam", "S", "E", section, elements),), joints=joints)


BAR = Section.rectangle(E=70e9, G=26e9, density=2700.0, width=0.02, thickness=0.02)


@pytest.mark.parametrize(("section", "n"), [(SECTION, 8), (SECTION, 64), (BAR, 8)],
                         ids=["strip, axial term", "strip, rotation term", "square bar"])
def test_the_estimate_is_the_assembled_models_own_ratio(section, n):
    # along x, so each node's (ux, uy, rz) are the element's own axial, transverse and
    # rotation DOFs (an inclined link mixes axial and transverse in its diagonal). The strip
    # bends in its plane across its 10 mm width: 3 EA / h^2 exceeds 420 EI / h^4 up to
    # h = sqrt(140 / 12) 10 mm, n ~ 29
    along_x = {"S": (0.0, 0.0), "E": (1.0, 0.0)}
    topology = free_beam(n, section)
    model = build_model(topology, along_x)
    K, M = assemble(model)
    ratio = K.diagonal() / M.diagonal()
    lam_max = ratio[3:-3].max()  # inner nodes: what the estimate takes
    result = modes_of(model, 4)
    lam_1 = result.eigenvalues[result.elastic[0]]
    # the FE lambda_1 lies above the exact beam's by its discretisation error, O(h^4):
    # 1.6e-4 relative at 8 elements (measured), 2^-12 of that at 64
    assert roundoff_ratio(topology, along_x) == pytest.approx(EPS * lam_max / lam_1, rel=3e-4, abs=0)
    # frame-free: the link lengths from other coordinates agree to an ulp, their powers to 1e-13
    assert roundoff_ratio(topology, POINTS) == pytest.approx(roundoff_ratio(topology, along_x),
                                                             rel=1e-13)


def test_ratio_grows_as_n2_then_n4_and_finest_supported_is_the_last_mesh_under_the_limit():
    # the strip's axial term dominates below n ~ 29, the rotation term above: n^2, then n^4
    r8, r16 = roundoff_ratio(free_beam(8), POINTS), roundoff_ratio(free_beam(16), POINTS)
    assert r16 / r8 == pytest.approx(4.0, rel=1e-12)
    r100, r200 = roundoff_ratio(free_beam(100), POINTS), roundoff_ratio(free_beam(200), POINTS)
    assert r200 / r100 == pytest.approx(16.0, rel=1e-12)
    for limit in (1e-11, 1e-6, 10.0):  # n = 7 (set by the axial term), 270 and 15220
        n = finest_supported(free_beam(1), POINTS, limit)
        assert roundoff_ratio(free_beam(n), POINTS) <= limit < roundoff_ratio(free_beam(n + 1),
                                                                             POINTS)


def test_a_mesh_past_the_limit_is_refused_before_assembly():
    limit = 1e-6
    n = finest_supported(free_beam(1), POINTS, limit)
    refuse_too_fine(free_beam(n), POINTS, limit)  # at the limit: accepted
    topology = free_beam(4 * n)
    with pytest.raises(NumericalError) as err:
        refuse_too_fine(topology, POINTS, limit)
    text = str(err.value)
    assert text.startswith(f"{4 * n} elements per link is too fine for double precision")
    assert f"exceeds {limit:g}" in text
    assert f"before assembling {3 * (4 * n + 1)} DOFs" in text
    assert f"Use fewer than {n} elements per link" in text
    # the estimate of the ratio in the message: 4^4 times the accepted mesh's, to 2 digits
    quoted = float(text.split("eps lambda_max / lambda_1 = ")[1].split()[0])
    assert quoted == pytest.approx(roundoff_ratio(topology, POINTS), rel=0.05, abs=0)


def test_the_softest_link_sets_lambda_1_and_the_finest_element_lambda_max():
    # two links: a long soft one (2 m, 4 elements) and a short one finely meshed (0.5 m, 16)
    joints = tuple(JointSpec(name, ground=False, Kt=0.0, Kr=0.0) for name in "ABC")
    links = (LinkSpec("long", "A", "B", SECTION, 4), LinkSpec("short", "B", "C", SECTION, 16))
    points = {"A": (0.0, 0.0), "B": (2.0, 0.0), "C": (2.0, 0.5)}
    both = roundoff_ratio(Topology(links=links, joints=joints), points)
    long_alone = roundoff_ratio(free_beam(4), {"S": (0.0, 0.0), "E": (2.0, 0.0)})
    short_alone = roundoff_ratio(free_beam(16), {"S": (0.0, 0.0), "E": (0.5, 0.0)})
    # h: 0.5 m and 1/32 m, so lambda_max is the short link's (both terms); lambda_1 ~ L^-4 is
    # the long one's
    assert both == pytest.approx(short_alone * (2.0 / 0.5) ** 4, rel=1e-12, abs=0)
    assert both > long_alone
