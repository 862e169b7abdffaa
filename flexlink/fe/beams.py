"""Beam theories of a link behind one dispatch: "euler-bernoulli" (``link.py``, the paper's
element) and "timoshenko" (``timoshenko.py``: shear strain and rotary inertia). Both give the
same local DOF order (u, v, rz) per node, so assembly, rotation and springs do not care which.

A section (``model.Section``) names its theory in ``section.beam``.
"""

from __future__ import annotations

import enum
import math

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from flexlink.errors import NumericalError

from flexlink.fe import link, timoshenko


def _euler_bernoulli(length, elements, s):
    return link.chain_entries(length, elements, s.EA, s.EI, s.mass_per_length)


def _timoshenko(length, elements, s):
    link.check_link_inputs(length, elements, s.EA, s.EI, s.mass_per_length)
    return timoshenko.timoshenko_entries(length, elements, s.EA, s.EI, s.kGA, s.mass_per_length,
                                    s.rotary_inertia)


class BeamTheory(enum.StrEnum):
    EULER_BERNOULLI = "euler-bernoulli"
    TIMOSHENKO = "timoshenko"


THEORIES = {BeamTheory.EULER_BERNOULLI: _euler_bernoulli, BeamTheory.TIMOSHENKO: _timoshenko}


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
    return 12.0 * section.EI / (section.kGA * h * h) if section.beam is BeamTheory.TIMOSHENKO else 0.0


def pinned_bending_frequencies(section, length: float, elements: int, n: int = 1) -> np.ndarray:
    """Lowest ``n`` bending frequencies [Hz] of a straight link pinned at both ends (v = 0 at
    both, u = 0 at the start), in the section's beam theory."""
    K, M = beam_matrices(length, elements, section)
    keep = np.setdiff1d(np.arange(K.shape[0]), [0, 1, 3 * elements + 1])
    K, M = K[keep][:, keep], M[keep][:, keep]
    if len(keep) <= 200:
        lam, vec = scipy.linalg.eigh(K.toarray(), M.toarray())
    else:  # shift below the first bending mode; ask for enough modes to pass the axial ones
        first = (math.pi / length) ** 4 * section.EI / section.mass_per_length  # EB, [rad^2/s^2]
        lam, vec = spla.eigsh(K.tocsc(), min(n + 8, len(keep) - 2), M.tocsc(),
                              sigma=-first / 4, which="LM")
        order = np.argsort(lam)
        lam, vec = lam[order], vec[:, order]
    # bending modes carry transverse motion; axial ones only u
    v_rows, u_rows = keep % 3 == 1, keep % 3 == 0
    bending = [k for k in range(len(lam))
               if np.linalg.norm(vec[v_rows, k]) > np.linalg.norm(vec[u_rows, k])]
    if len(bending) < n:
        raise NumericalError(f"found {len(bending)} bending modes of the {n} asked for")
    return np.sqrt(lam[bending[:n]]) / (2 * math.pi)


def timoshenko_pinned(section, length: float, n: int = 1) -> float:
    """Closed-form flexural frequency [Hz] of mode ``n`` of a pinned-pinned Timoshenko beam:
    with w = W sin(a x), psi = Psi cos(a x), a = n pi / L, the equations
    kGA (w'' - psi') = rhoA w_tt and EI psi'' + kGA (w' - psi) = rhoI psi_tt give
    det [[kGA a^2 - rhoA w^2, -kGA a], [-kGA a, EI a^2 + kGA - rhoI w^2]] = 0, a quadratic
    in w^2 whose lower root is the flexural mode."""
    a = n * math.pi / length
    s = section
    kGA, EI, rA, rI = s.kGA, s.EI, s.mass_per_length, s.rotary_inertia
    # (kGA a^2 - rA x)(EI a^2 + kGA - rI x) - (kGA a)^2 = 0, x = omega^2
    c2 = rA * rI
    c1 = -(rA * (EI * a * a + kGA) + rI * kGA * a * a)
    c0 = kGA * a * a * EI * a * a
    # the lower root written without cancellation (c2 c0 << c1^2 on slender beams)
    x = 2 * c0 / (-c1 + math.sqrt(c1 * c1 - 4 * c2 * c0))
    return math.sqrt(x) / (2 * math.pi)


def euler_bernoulli_pinned(section, length: float, n: int = 1) -> float:
    """Closed-form frequency [Hz] of mode ``n`` of a pinned-pinned Euler-Bernoulli beam."""
    return (n * math.pi / length) ** 2 * math.sqrt(section.EI / section.mass_per_length) / (2 * math.pi)
