"""What a root of (s^2 M + s G + K) x = 0 is, and why a mode grows, judged from the matrices.

A root s is real (|Im s| <= REAL_ROOT |s|) or a vibration. A real root has no frequency: with
Re s > 0 the mode diverges (it leaves the pose without oscillating), with Re s < 0 it decays
(the partner -sigma of a divergence, in a system without damping).

Why a mode grows. With G skew (gyroscopic) and K symmetric, the system is conservative: it is
stable while K is positive definite (Kelvin-Tait-Chetaev), and a growing mode needs a negative
stiffness. A skew part of K (circulatory: the links' angular acceleration, alpha S) does work
and can make modes grow with K's symmetric part positive definite (flutter). So:
  - the symmetric stiffness has negative eigenvalues: the cause is the part that makes it so,
    judged by adding each speed part alone to the elastic stiffness: the inertia preload
    (K + K_g: buckling under the compression it puts in the links), the centrifugal softening
    (K - Omega^2 Mt), or only the two together;
  - a vibrating mode grows while the symmetric stiffness is positive definite, or a skew part
    is present: the circulatory term.
"""

from __future__ import annotations

import enum

import numpy as np

from flexlink.analysis.quadratic import negative_eigenvalues

REAL_ROOT = 1e-8  # |Im s| / |s| at or below this: a real root (round-off of 0 is ~1e-16)


class RootKind(enum.StrEnum):
    VIBRATING = "vibrating"  # complex root: a frequency, a growth rate
    DIVERGING = "diverging"  # real root > 0: grows without oscillating
    DECAYING = "decaying"  # real root < 0: decays without oscillating


class Cause(enum.StrEnum):
    PRELOAD = "preload"  # K + K_g indefinite: buckling under the inertia preload
    CENTRIFUGAL = "centrifugal"  # K - Omega^2 Mt indefinite: centrifugal softening
    COMBINED = "preload and centrifugal"  # only the two together make K indefinite
    CIRCULATORY = "circulatory"  # the skew angular-acceleration term does work


def root_kinds(eigenvalues: np.ndarray) -> tuple[RootKind, ...]:
    """The kind of each root s [1/s]."""
    s = np.asarray(eigenvalues, dtype=complex)
    real = np.abs(s.imag) <= REAL_ROOT * np.abs(s)
    return tuple(RootKind.VIBRATING if not r else
                 RootKind.DIVERGING if v > 0 else RootKind.DECAYING
                 for r, v in zip(real, s.real))


def instability_causes(elastic, parts: dict[Cause, object], circulatory, negative: int,
                       growing: np.ndarray, kinds: tuple[RootKind, ...]) -> tuple[Cause, ...]:
    """The causes of an unstable operating point. ``elastic``: the elastic stiffness K
    (symmetric, dense or sparse); ``parts``: the symmetric speed parts that enter (Cause.PRELOAD
    -> K_g, Cause.CENTRIFUGAL -> -Omega^2 Mt), each None or absent when left out;
    ``circulatory``: the skew part (None when left out); ``negative``: the number of negative
    eigenvalues of the whole symmetric stiffness; ``growing`` and ``kinds``: per root. Empty
    when nothing grows and the stiffness is positive definite."""
    causes = []
    if negative:
        alone = [cause for cause in (Cause.PRELOAD, Cause.CENTRIFUGAL)
                 if parts.get(cause) is not None
                 and negative_eigenvalues(elastic + parts[cause]) > 0]
        causes += alone or [Cause.COMBINED]
    flutter = any(g and k is RootKind.VIBRATING for g, k in zip(growing, kinds))
    if flutter and _nonzero(circulatory):
        causes.append(Cause.CIRCULATORY)
    return tuple(causes)


def _nonzero(A) -> bool:
    if A is None:
        return False
    values = A.data if hasattr(A, "data") and not isinstance(A, np.ndarray) else np.asarray(A)
    return bool(np.any(values != 0))
