"""How fine a mesh double precision supports, estimated before anything is assembled.

The eigen solver's own check (``solve.refined_eigenvalues``) refuses a model once
eps lambda_max / lambda_1 exceeds ``solve.LOST_LIMIT``: K as stored then perturbs its spectrum by
more than the lowest eigenvalue, and the lowest mode shapes are lost. Both eigenvalues can be
estimated from the topology and the link lengths alone, so a mesh far past that limit (e.g.
``-e 100000``: 9e5 DOFs, 3 GB and half a minute of assembly and factorisation) is refused at
once:
  - lambda_max: the largest diagonal ratio K_ii / M_ii of an inner node of the finest element
    h = L / n (what the solver's check uses too): rotation 420 EI / (rhoA h^4) (Hermite
    element, consistent mass), axial 3 EA / (rhoA h^2) (linear element);
  - lambda_1: BETA1_4 EI / (rhoA L^4) of the softest link, the first bending eigenvalue of a
    free-free (and of a clamped-clamped) beam. Fixing every joint node of the linkage only
    raises its eigenvalues, so this is an upper bound of the first elastic eigenvalue whenever
    the softest link's first mode lies among them; the estimate of the ratio is then a lower
    bound, and a refusal here is one the solver would make too.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from flexlink.errors import NumericalError
from flexlink.fe.model import Topology

BETA1_4 = 4.730040744862704**4  # (beta_1 L)^4 of a free-free beam: cos b cosh b = 1


def _ratio_terms(topology: Topology, points) -> tuple[float, float]:
    """The rotation and the axial term of the estimate of eps lambda_max / lambda_1: each
    link's largest diagonal ratio of that kind over the softest link's lambda_1."""
    rotation, axial, lam_1 = 0.0, 0.0, math.inf
    for spec in topology.links:
        s = spec.section
        length = math.dist(points[spec.start], points[spec.end])
        h = length / spec.elements
        rotation = max(rotation, 420 * s.EI / (s.mass_per_length * h**4))
        axial = max(axial, 3 * s.EA / (s.mass_per_length * h**2))
        lam_1 = min(lam_1, BETA1_4 * s.EI / (s.mass_per_length * length**4))
    eps = np.finfo(float).eps
    return float(eps * rotation / lam_1), float(eps * axial / lam_1)


def roundoff_ratio(topology: Topology, points: Mapping[str, tuple[float, float]]) -> float:
    """Estimate (a lower bound, see module docstring) of eps lambda_max / lambda_1 for
    ``topology`` meshed between the joint positions ``points`` [m]."""
    return max(_ratio_terms(topology, points))


def finest_supported(topology: Topology, points, limit: float) -> int:
    """The largest uniform elements per link n whose ``roundoff_ratio`` is at most ``limit``:
    the rotation term grows as n^4, the axial one as n^2 (which dominates coarse meshes of a
    slender link, up to n ~ L / (3.4 t) for a strip of thickness t)."""
    one = dataclasses.replace(topology, links=tuple(dataclasses.replace(l, elements=1)
                                                    for l in topology.links))
    rotation, axial = _ratio_terms(one, points)
    return max(1, int(min((limit / rotation) ** 0.25, (limit / axial) ** 0.5)))


def refuse_too_fine(topology: Topology, points, limit: float) -> None:
    """NumericalError, before assembly, when the mesh is past ``limit`` by the estimate."""
    ratio = roundoff_ratio(topology, points)
    if ratio > limit:
        n = max(l.elements for l in topology.links)
        raise NumericalError(
            f"{n} elements per link is too fine for double precision: the estimated "
            f"eps lambda_max / lambda_1 = {ratio:.2g} exceeds {limit:g}, so K's round-off would "
            f"swamp the lowest modes (refused before assembling {_dofs(topology)} DOFs). Use "
            f"fewer than {finest_supported(topology, points, limit)} elements per link (by this "
            "estimate; the solver's own check, with the actual lowest mode, may refuse "
            "somewhat coarser meshes too)")


def _dofs(topology: Topology) -> int:
    return 3 * sum(l.elements + 1 for l in topology.links)
