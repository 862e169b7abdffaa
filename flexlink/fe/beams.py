"""Beam theories of a link behind one dispatch: "euler-bernoulli" (``link.py``, the paper's
element) and "timoshenko" (``timoshenko.py``: shear strain and rotary inertia). Both give the
same local DOF order (u, v, rz) per node, so assembly, rotation and springs do not care which.

A section (``model.Section``) names its theory in ``section.beam``.
"""

from __future__ import annotations

import scipy.sparse as sp

from flexlink.fe import link, timoshenko


def _euler_bernoulli(length, elements, s):
    return link.chain_entries(length, elements, s.EA, s.EI, s.mass_per_length)


def _timoshenko(length, elements, s):
    link.check_link_inputs(length, elements, s.EA, s.EI, s.mass_per_length)
    return timoshenko.timoshenko_entries(length, elements, s.EA, s.EI, s.kGA, s.mass_per_length,
                                    s.rotary_inertia)


THEORIES = {"euler-bernoulli": _euler_bernoulli, "timoshenko": _timoshenko}


def link_entries(length: float, elements: int, section):
    """A link's local K and M entries (rows, cols, k, m) in its section's beam theory;
    length [m]."""
    return THEORIES[section.beam](length, elements, section)


def beam_matrices(length: float, elements: int, section):
    """(K, M) of a link as sparse CSR matrices of size 3 (elements + 1)."""
    rows, cols, k, m = link_entries(length, elements, section)
    n = 3 * (elements + 1)
    return (sp.coo_matrix((k, (rows, cols)), shape=(n, n)).tocsr(),
            sp.coo_matrix((m, (rows, cols)), shape=(n, n)).tocsr())


def shear_parameter(section, h: float) -> float:
    """Phi = 12 EI / (k G A h^2) of an element of length h [m]; 0 for Euler-Bernoulli."""
    return 12.0 * section.EI / (section.kGA * h * h) if section.beam == "timoshenko" else 0.0
