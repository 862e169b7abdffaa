"""Out-of-plane family: element matrices, closed-form bending and torsion frequencies of single
strips, rigid-body modes, spring limits, and the scene's family switch."""

import math

import numpy as np
import pytest

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.errors import InputError
from flexlink.analysis.families import elastic_modes
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology
from flexlink.analysis.outofplane import out_of_plane_modes
from flexlink.fe.strip import (StripProperties, strip_chain_matrices, strip_element_matrices,
                               strip_node_rotation)
from flexlink.scene import load_scene

from conftest import CASES_DIR as CASES
from helpers import BETA_L

INF = math.inf
LENGTH = 0.5
# a flat strip 20 x 2 mm: torsion and weak-axis bending frequencies interleave but never coincide
STRIP = Section.rectangle(E=70e9, G=26e9, density=2700.0, width=0.02, thickness=0.002)
P = StripProperties.of(STRIP)


def strip_modes(start, end, elements, n, angle=0.0):
    """One strip from S to E; ``start``/``end`` = (Kt, Ktilt) of a ground bearing, None = free."""
    joints = (JointSpec("S", start is not None, start[0] if start else 0.0, 0.0),
              JointSpec("E", end is not None, end[0] if end else 0.0, 0.0))
    tilt = {"S": start[1] if start else 0.0, "E": end[1] if end else 0.0}
    topo = Topology(links=(LinkSpec("strip", "S", "E", STRIP, elements),), joints=joints)
    points = {"S": (0.0, 0.0), "E": (LENGTH * math.cos(angle), LENGTH * math.sin(angle))}
    return out_of_plane_modes(topo, points, tilt, n, EigenSolver("dense"))


def bending(beta_l):
    return np.array(beta_l) ** 2 * math.sqrt(P.EI / (P.rhoA * LENGTH**4)) / (2 * math.pi)


def torsion(waves):
    """Torsion of a uniform shaft: f = waves * pi / L sqrt(GJ / rho Ip) / 2 pi."""
    return np.array(waves) * math.pi / LENGTH * math.sqrt(P.GJ / P.rhoIp) / (2 * math.pi)


def test_strip_properties_closed_forms():
    b, t = 0.02, 0.002
    assert P.EI == pytest.approx(70e9 * b * t**3 / 12, rel=1e-14)
    assert P.GJ == pytest.approx(26e9 * b * t**3 / 3 * (1 - 0.63 * t / b), rel=1e-14)
    assert P.rhoIp == pytest.approx(2700 * b * t * (b * b + t * t) / 12, rel=1e-14)


def test_element_symmetric_and_rigid_motions_strain_free():
    l = 0.07
    k, m = strip_element_matrices(l, P)
    assert np.abs(k - k.T).max() <= 1e-15 * np.abs(k).max()
    assert np.linalg.eigvalsh(m).min() > 0
    # rigid motions: translation w; rotation ty about y (w = -ty x); twist tx
    rigid = np.array([[1, 0, 0, 1, 0, 0], [0, 0, 1, -l, 0, 1], [0, 1, 0, 0, 1, 0]], float).T
    assert np.abs(k @ rigid).max() <= 1e-12 * np.abs(k).max()
    # and nothing else is strain-free
    assert np.sum(np.linalg.eigvalsh(k) > 1e-9 * np.abs(k).max()) == 3


def test_rotated_chain_keeps_three_rigid_body_modes():
    K, M = strip_chain_matrices(LENGTH, 5, P)
    T = np.kron(np.eye(6), strip_node_rotation(0.83))
    Kg = T.T @ K @ T
    x = np.linspace(0, LENGTH, 6) * np.array([[math.cos(0.83)], [math.sin(0.83)]])
    # global rigid motions: w = 1; rotation rx (w = y rx); rotation ry (w = -x ry)
    R = np.zeros((18, 3))
    R[0::3, 0] = 1
    R[0::3, 1], R[1::3, 1] = x[1], 1
    R[0::3, 2], R[2::3, 2] = -x[0], 1
    assert np.abs(Kg @ R).max() <= 1e-10 * np.abs(Kg).max()
    assert np.allclose(T @ T.T, np.eye(18))


@pytest.mark.parametrize("angle", [0.0, 1.1])
def test_cantilever_bending_and_torsion_match_closed_forms(angle):
    result = strip_modes((INF, INF), None, 40, 6, angle)
    exact = np.sort(np.concatenate([bending(BETA_L["cantilever"]), torsion([0.5, 1.5])]))
    # Hermite bending converges as h^4, linear torsion as h^2: (pi/2/40)^2/12 ~ 1e-4 at 40 elements
    np.testing.assert_allclose(result.elastic_frequencies[:5], exact[:5], rtol=3e-4)


def test_spring_limits_simply_supported_and_free_twist():
    """Ktilt = 0 at both ends with rigid Kt: simply supported bending, and the free twist of the
    whole strip is a zero (mechanism) mode, found and labelled as such."""
    result = strip_modes((INF, 0.0), (INF, 0.0), 40, 4)
    assert sum(k != "elastic" for k in result.kinds) == 1
    exact = np.sort(np.concatenate([bending([math.pi * k for k in (1, 2, 3, 4)]),
                                    torsion([1.0, 2.0])]))
    np.testing.assert_allclose(result.elastic_frequencies[:3], exact[:3], rtol=3e-4)
    # very stiff springs approach the rigid (exact constraint) answer from below
    stiff = strip_modes((1e7, 1e5), None, 40, 4).elastic_frequencies[:3]  # 1e5 x EI/L^3, EI/L
    rigid = strip_modes((INF, INF), None, 40, 4).elastic_frequencies[:3]
    assert np.all(stiff <= rigid * (1 + 1e-12))
    np.testing.assert_allclose(stiff, rigid, rtol=1e-3)


def test_scene_chooses_family_and_3d_is_the_union():
    n = 4
    planar = elastic_modes(load_scene(CASES / "case1.toml"), n, 4)
    out = elastic_modes(load_scene(CASES / "case1.toml", {"model.family": "out-of-plane"}), n, 4)
    both = elastic_modes(load_scene(CASES / "case1.toml", {"model.family": "3d"}), n, 4)
    assert set(planar[1]) == {"in-plane"} and set(out[1]) == {"out-of-plane"}
    np.testing.assert_allclose(both[0], np.sort(np.concatenate([planar[0], out[0]]))[:n], rtol=1e-12)
    with pytest.raises(InputError, match="model.family"):
        elastic_modes(load_scene(CASES / "case1.toml", {"model.family": "spatial"}), n, 4)
