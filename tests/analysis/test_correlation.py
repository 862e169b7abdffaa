"""Test-analysis correlation (analysis/correlation.py) and Effective Independence
(analysis/effective_independence.py), on shapes whose answers are known in closed form."""

from __future__ import annotations

import numpy as np
import pytest

from flexlink.analysis.correlation import (ALIAS_MAC, DOUBTFUL_MAC, GOOD_MAC, PairQuality,
                                           comac, correlate, modal_scale_factor, pair_by_order)
from flexlink.analysis.effective_independence import (effective_independence,
                                                      fisher_determinant, independence)
from flexlink.errors import InputError


def _sines(x, modes):
    """Pinned-pinned beam modes sin(n pi x / L) at x / L, as columns."""
    return np.sin(np.pi * np.outer(x, np.arange(1, modes + 1)))


def test_pairing_is_by_shape_and_finds_a_swapped_pair():
    """Model modes are the test modes with modes 2 and 3 swapped, scaled and sign-flipped:
    the pairing puts test 2 with model 3 and test 3 with model 2, every MAC 1 (within
    round-off), and each modal scale factor undoes the scaling. Pairing by order would take
    (2, 2) and (3, 3), whose MAC is 0 (the sines are orthogonal on this grid)."""
    x = (np.arange(1, 13) - 0.5) / 12
    test = _sines(x, 4)
    model = test[:, [0, 2, 1, 3]] * np.array([2.0, -0.5, 3.0, 1.0])
    c = correlate(test, model)
    assert c.pairs == ((0, 0), (1, 2), (2, 1), (3, 3))
    np.testing.assert_allclose(c.pair_mac, 1.0, atol=1e-12)
    assert c.pair_quality == (PairQuality.GOOD,) * 4
    np.testing.assert_allclose(c.scale, [0.5, 1 / 3, -2.0, 1.0], rtol=1e-12)
    assert c.unpaired_test == () and c.unpaired_model == ()
    by_order = [c.mac[i, j] for i, j in pair_by_order(4, 4)]
    assert by_order[1] < 1e-12 and by_order[2] < 1e-12


def test_thresholds_sort_pairs_into_good_doubtful_and_unpaired():
    """Model shapes built at a chosen MAC with their test partners: cos^2 of the angle
    between them. MAC 0.95 is good, 0.8 doubtful, 0.5 no pair (both modes unpaired)."""
    x = (np.arange(1, 21) - 0.5) / 20
    test = _sines(x, 6)[:, :3]
    spare = _sines(x, 6)[:, 3:]  # orthogonal to every test shape on this grid
    macs = [0.95, 0.8, 0.5]
    model = np.column_stack([np.sqrt(m) * test[:, i] / np.linalg.norm(test[:, i])
                             + np.sqrt(1 - m) * spare[:, i] / np.linalg.norm(spare[:, i])
                             for i, m in enumerate(macs)])
    c = correlate(test, model)
    np.testing.assert_allclose(np.diag(c.mac), macs, atol=1e-12)
    assert GOOD_MAC == 0.9 and DOUBTFUL_MAC == 0.7
    assert c.pairs == ((0, 0), (1, 1))
    assert c.pair_quality == (PairQuality.GOOD, PairQuality.DOUBTFUL)
    assert c.unpaired_test == (2,) and c.unpaired_model == (2,)


def test_comac_points_at_the_channel_that_disagrees():
    """Every model shape equals its test partner except at channel 5, which reads the three
    modes with gains 1, 4 and 0.1 (a model region wrong in a different way per mode). The MSF
    shrinks each model shape a little (the wrong channel pulls it), so no channel is exactly
    1, but channel 5 alone falls far below the others."""
    x = (np.arange(1, 11) - 0.5) / 10
    test = _sines(x, 3)
    model = test.copy()
    model[5] = test[5] * [1.0, 4.0, 0.1]
    c = comac(test, model)
    others = np.delete(np.arange(10), 5)
    assert np.min(c[others]) > 0.9
    assert c[5] < np.min(c[others]) - 0.2
    assert correlate(test, model).comac.shape == (10,)


def test_automac_warns_where_the_sensors_alias_two_modes():
    """Sensors at x/L = 1/3 and 2/3 of a pinned-pinned beam read modes 2 and 4 as the same
    pattern up to sign (sin(2 pi / 3) = -sin(4 pi / 3)): autoMAC 1, flagged; modes 1 and 2
    are orthogonal there."""
    test = _sines(np.array([1 / 3, 2 / 3]), 4)[:, [0, 1, 3]]
    c = correlate(test, test)
    assert c.auto_mac[1, 2] == pytest.approx(1.0, abs=1e-12)
    assert c.aliased == ((1, 2),)
    assert c.auto_mac[0, 1] < ALIAS_MAC


def test_modal_scale_factor_is_the_least_squares_factor():
    rng = np.random.default_rng(0)
    m = rng.normal(size=(8, 2))
    t = m * [3.0, -0.25]
    np.testing.assert_allclose(modal_scale_factor(t, m), [3.0, -0.25], rtol=1e-12)


def test_independence_sums_to_the_mode_count_and_is_zero_on_a_node():
    """E_D is the diagonal of a rank-k projector: between 0 and 1, summing to k; a candidate
    on a node of every target mode (x = 0 or L for a pinned beam) has E_D = 0."""
    x = np.linspace(0.0, 1.0, 41)
    E = independence(_sines(x, 4))
    assert E.sum() == pytest.approx(4.0, rel=1e-12)
    assert np.all(E >= -1e-12) and np.all(E <= 1 + 1e-12)
    assert E[0] < 1e-12 and E[-1] < 1e-12


def test_effective_independence_keeps_off_the_nodes_and_beats_a_uniform_layout():
    """Pinned-pinned beam, 4 target modes, 4 sensors out of 99 interior candidates. The nodes
    of modes 1-4 are at x/L = 1/4, 1/3, 1/2, 2/3, 3/4 (and the supports): Effective
    Independence keeps every sensor at least 2 % of L from them. A uniform layout of 4
    sensors spread from end to end (x/L = 0, 1/3, 2/3, 1) reads mode 3 as zero and modes 2
    and 4 as one pattern (autoMAC 1); the chosen layout's largest off-diagonal autoMAC is
    lower and its Fisher information larger."""
    x = np.linspace(0.0, 1.0, 101)[1:-1]
    Phi = _sines(x, 4)
    kept = effective_independence(Phi, 4)
    nodes = np.array([0.0, 1 / 4, 1 / 3, 1 / 2, 2 / 3, 3 / 4, 1.0])
    assert np.min(np.abs(x[kept][:, None] - nodes[None, :])) >= 0.02
    chosen = correlate(Phi[kept], Phi[kept]).auto_mac
    uniform_x = np.linspace(0.0, 1.0, 4)
    uniform = _sines(uniform_x, 4)
    with np.errstate(invalid="ignore", divide="ignore"):
        auto_uniform = correlate(uniform[:, [0, 1, 3]], uniform[:, [0, 1, 3]]).auto_mac
    off = ~np.eye(4, dtype=bool)
    assert np.max(chosen[off]) < np.max(auto_uniform[~np.eye(3, dtype=bool)]) - 0.5
    assert fisher_determinant(Phi[kept]) > fisher_determinant(uniform) + 1e-3
    assert abs(fisher_determinant(uniform)) < 1e-12  # mode 3 unseen: singular


def test_effective_independence_refuses_fewer_sensors_than_modes():
    with pytest.raises(InputError, match="--count"):
        effective_independence(_sines(np.linspace(0.1, 0.9, 9), 4), 3)
