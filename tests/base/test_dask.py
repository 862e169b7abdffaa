"""Monte Carlo on a dask.distributed LocalCluster of worker processes gives exactly the serial
result (samples are drawn in the parent; results come back in task order)."""

from pathlib import Path

import numpy as np
import pytest

from flexlink.parallel import run_tasks, use_scheduler
from flexlink.studies.uncertainty import monte_carlo, scene_inputs

pytest.importorskip("distributed")

CASE = str(Path(__file__).resolve().parents[2] / "cases" / "case2.toml")


def _worker_and(value):
    """(address of the dask worker running this task, or None outside dask; value)."""
    from distributed import get_worker

    try:
        return get_worker().address, value
    except ValueError:
        return None, value


def test_local_cluster_same_as_serial():
    inputs = scene_inputs(CASE, {}, 0.05, 0.15e-3)
    run = dict(paths=(CASE,), base_overrides={}, inputs=inputs, samples=4, seed=3, n_modes=2,
               elements=2)
    serial = monte_carlo(**run, n_jobs=1)
    with use_scheduler("local") as client:
        assert client is not None
        distributed = monte_carlo(**run)
        ran = run_tasks(_worker_and, [(k,) for k in range(4)])
        cluster = set(client.nthreads())
    assert np.array_equal(serial.samples, distributed.samples, equal_nan=True)
    assert [v for _, v in ran] == [0, 1, 2, 3]  # task order
    assert all(address in cluster for address, _ in ran)  # on the cluster's workers
