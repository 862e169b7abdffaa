"""Test-analysis correlation of mode shapes read at the same channels (sensor, direction).

- MAC (``mac.mac_matrix``, unweighted: a test has no mass matrix) of every test mode against
  every model mode, and the one-to-one pairing with the largest total MAC (the Hungarian
  algorithm, ``mac.pair_modes`` on scipy's ``linear_sum_assignment``), not pairing by order.
- Each pair is judged by its MAC: >= ``GOOD_MAC`` good, >= ``DOUBTFUL_MAC`` doubtful, below
  that the two modes are not a pair and both count as unpaired.
- The modal scale factor MSF = (phi_t . phi_m) / (phi_m . phi_m) scales a model shape onto its
  test partner (least squares), so the two can be drawn and compared point by point.
- CoMAC per channel (after Lieven and Ewins 1988) over the accepted pairs, each test shape
  scaled to unit length and its model partner onto it by the MSF:
      CoMAC_c = (sum_p |t_cp m_cp|)^2 / (sum_p t_cp^2 sum_p m_cp^2)
  1 where the channel's readings are proportional across the pairs; low values point at a
  sensor (or a model region) that disagrees across the modes. Like a MAC over the modes at
  one channel it ignores a scale common to all modes, so a sensor read with one wrong gain
  or sign in every mode does not show.
- autoMAC of the test set: MAC of the test modes with themselves. An off-diagonal entry at or
  above ``ALIAS_MAC`` means the sensors cannot tell those two modes apart (spatial aliasing):
  any model mode pairing one would pair the other about as well.
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np

from flexlink.analysis.mac import mac_matrix, pair_modes

GOOD_MAC = 0.9
DOUBTFUL_MAC = 0.7
ALIAS_MAC = DOUBTFUL_MAC  # two test modes this alike would both pair one model mode


class PairQuality(enum.StrEnum):
    GOOD = "good"
    DOUBTFUL = "doubtful"


def quality(mac: float) -> PairQuality | None:
    """The verdict on a pair of MAC ``mac``; None: not a pair."""
    if mac >= GOOD_MAC:
        return PairQuality.GOOD
    if mac >= DOUBTFUL_MAC:
        return PairQuality.DOUBTFUL
    return None


@dataclasses.dataclass(frozen=True)
class Correlation:
    """Test modes (columns of the test shapes) against model modes at the same channels.

    mac (k_test, k_model); pairs: (test index, model index) of the accepted pairs, in test
    order; pair_mac, pair_quality and scale (MSF, model -> test) per pair; unpaired_test and
    unpaired_model: indices left out; comac (channels,) over the accepted pairs (NaN at a
    channel where every paired shape reads zero); auto_mac (k_test, k_test); aliased: test
    index pairs (i < j) with auto_mac >= ALIAS_MAC."""

    mac: np.ndarray
    pairs: tuple[tuple[int, int], ...]
    pair_mac: np.ndarray
    pair_quality: tuple[PairQuality, ...]
    scale: np.ndarray
    unpaired_test: tuple[int, ...]
    unpaired_model: tuple[int, ...]
    comac: np.ndarray
    auto_mac: np.ndarray
    aliased: tuple[tuple[int, int], ...]

    def __post_init__(self):
        k_test, k_model = self.mac.shape
        n = len(self.pairs)
        for name in ("pair_mac", "scale"):
            if np.shape(getattr(self, name)) != (n,):
                raise ValueError(f"Correlation.{name} has shape "
                                 f"{np.shape(getattr(self, name))}, expected ({n},)")
        if len(self.pair_quality) != n:
            raise ValueError(f"Correlation.pair_quality has {len(self.pair_quality)} entries, "
                             f"expected {n}")
        if self.auto_mac.shape != (k_test, k_test):
            raise ValueError(f"Correlation.auto_mac has shape {self.auto_mac.shape}, expected "
                             f"({k_test}, {k_test})")
        if len(self.unpaired_test) + n != k_test or len(self.unpaired_model) + n != k_model:
            raise ValueError("Correlation: paired and unpaired modes do not add up")


def modal_scale_factor(test: np.ndarray, model: np.ndarray) -> np.ndarray:
    """Per column: the factor s minimising |test - s model|, (t . m) / (m . m)."""
    return np.einsum("ij,ij->j", test, model) / np.einsum("ij,ij->j", model, model)


def comac(test: np.ndarray, model: np.ndarray) -> np.ndarray:
    """CoMAC (channels,) of paired columns of ``test`` and ``model`` (same shape), each test
    column scaled to unit length and its model partner scaled onto it by the MSF."""
    t = test / np.linalg.norm(test, axis=0)
    m = model * modal_scale_factor(t, model)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.sum(np.abs(t * m), axis=1) ** 2 / (np.sum(t**2, axis=1) * np.sum(m**2, axis=1))


def correlate(test: np.ndarray, model: np.ndarray) -> Correlation:
    """The correlation of ``test`` (channels, k_test) with ``model`` (channels, k_model)
    shapes, both real and read at the same channels."""
    test, model = np.asarray(test, dtype=float), np.asarray(model, dtype=float)
    if test.ndim != 2 or model.ndim != 2 or test.shape[0] != model.shape[0]:
        raise ValueError(f"test shapes {test.shape} and model shapes {model.shape} must be "
                         "(channels, modes) with the same channels")
    mac = mac_matrix(test, model)
    assignment = pair_modes(mac)
    kept = [(int(i), int(j), float(v)) for i, j, v in zip(assignment.a, assignment.b,
                                                          assignment.mac) if quality(v)]
    pairs = tuple((i, j) for i, j, _ in kept)
    t_idx = [i for i, _ in pairs]
    m_idx = [j for _, j in pairs]
    auto = mac_matrix(test, test)
    upper = np.triu(auto, 1)
    aliased = tuple((int(i), int(j)) for i, j in zip(*np.nonzero(upper >= ALIAS_MAC)))
    return Correlation(
        mac=mac, pairs=pairs, pair_mac=np.array([v for *_, v in kept]),
        pair_quality=tuple(quality(v) for *_, v in kept),
        scale=modal_scale_factor(test[:, t_idx], model[:, m_idx]),
        unpaired_test=tuple(i for i in range(test.shape[1]) if i not in t_idx),
        unpaired_model=tuple(j for j in range(model.shape[1]) if j not in m_idx),
        comac=comac(test[:, t_idx], model[:, m_idx]) if pairs else np.full(len(test), np.nan),
        auto_mac=auto, aliased=aliased)


def pair_by_order(k_test: int, k_model: int) -> tuple[tuple[int, int], ...]:
    """The pairing a frequency table by mode order implies: the i-th test mode with the i-th
    model mode."""
    return tuple((i, i) for i in range(min(k_test, k_model)))
