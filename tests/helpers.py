"""Small model builders shared by the tests: single beams with chosen supports."""

import math

import numpy as np

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.fe.model_at_pose import in_plane_eigen_scale
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model
from flexlink.analysis.solve import solve_modes

INF = math.inf
# A slender steel-like strip: L/h = 100, so axial modes lie far above the first bending modes.
LENGTH, WIDTH, THICK = 1.0, 0.01, 0.005
SECTION = Section.rectangle(E=210e9, G=81e9, density=7850.0, width=WIDTH, thickness=THICK)


def beam_scale(section=SECTION, length=LENGTH):
    """sqrt(EI / (rhoA L^4)) [rad/s]: omega_n = (beta_n L)^2 times this."""
    return math.sqrt(section.EI / (section.mass_per_length * length**4))


SUPPORTS = {
    # (start joint Kt, Kr), (end joint Kt, Kr); None = free end (no joint springs)
    "cantilever": ((INF, INF), None),
    "pinned-pinned": ((INF, 0.0), (INF, 0.0)),
    "free-free": (None, None),
}


def single_beam(support, elements, angle=0.0, section=SECTION, length=LENGTH):
    ends = SUPPORTS[support]
    joints = tuple(JointSpec(name, ground=spec is not None, Kt=spec[0] if spec else 0.0,
                             Kr=spec[1] if spec else 0.0)
                   for name, spec in zip(("S", "E"), ends))
    topo = Topology(links=(LinkSpec("beam", "S", "E", section, elements),), joints=joints)
    c, s = math.cos(angle), math.sin(angle)
    return build_model(topo, {"S": (0.0, 0.0), "E": (length * c, length * s)})


def modes_of(model, n, method="dense"):
    K, M = assemble(model)
    return solve_modes(K, M, n, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model), solver=EigenSolver(method))


def bending_frequencies(result, n):
    """Elastic frequencies [rad/s] of the bending modes: modes whose shape is mostly transverse."""
    omegas = 2 * np.pi * result.frequencies
    return omegas[np.array([k == "elastic" for k in result.kinds])][:n]
