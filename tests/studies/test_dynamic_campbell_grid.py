"""The dynamic Campbell diagram's speed grid: refused unless finite, >= 0 and ascending, and
the divergence record independent of where the grid starts."""

import math

import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.errors import InputError
from flexlink.scene import load_scene
from flexlink.studies.running.dynamic_campbell import dynamic_campbell

RPM = 2 * math.pi / 60


@pytest.fixture(scope="module")
def case1():
    return load_scene(CASES_DIR / "case1.toml")


@pytest.mark.parametrize("speeds", [[0.0, 10.0, math.inf], [0.0, math.nan, 10.0],
                                    [-1.0, 10.0], [10.0, 5.0], [[0.0, 10.0]]])
def test_a_grid_not_finite_non_negative_and_ascending_is_refused(case1, speeds):
    with pytest.raises(InputError, match="finite, >= 0 and ascending"):
        dynamic_campbell(case1, np.array(speeds), n_poses=4, n_modes=2, elements_per_link=4)


def test_a_grid_starting_past_divergence_still_records_it(case1):
    """Case 1's lowest mode diverges near crank 210 deg between 2700 and 2900 rev/min (the
    speed where the stiffness at speed turns singular, test_dynamic_campbell.py): a grid that
    starts above it has no stable speed, and the record is the same singular speed, which
    depends on the sampled poses only, never on the grid (1e-12: the same eigenproblems)."""
    kept = dynamic_campbell(case1, np.array([0.0, 2900.0]) * RPM, n_poses=12, n_modes=3,
                            elements_per_link=8).divergence
    past = dynamic_campbell(case1, np.array([2900.0, 3000.0]) * RPM, n_poses=12, n_modes=3,
                            elements_per_link=8)
    assert past.stable_speeds == 0 and np.isnan(past.frequencies).all()
    d = past.divergence
    assert d is not None and d.grid_speed == 2900.0 * RPM and d.line is None
    assert d.q == kept.q and d.speed == pytest.approx(kept.speed, rel=1e-12)
    assert 2700 * RPM < d.speed < 2900 * RPM
