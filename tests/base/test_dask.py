"""Monte Carlo on a dask.distributed LocalCluster of worker processes gives exactly the serial
result (samples are drawn in the parent; results come back in task order).

``use_scheduler("local")`` is given the tests' shared cluster (conftest) in place of a new one:
the stand-in records what was asked for and whether the block closed it."""

import os
from pathlib import Path

import numpy as np

from flexlink.parallel import run_tasks, use_scheduler
from flexlink.studies.calibration.uncertainty import monte_carlo, scene_inputs

# distributed: imported by the dask_cluster fixture (which skips without it), not at collection

CASE = str(Path(__file__).resolve().parents[2] / "cases" / "case2.toml")


def _worker_and(value):
    """(address of the dask worker running this task, or None outside dask; value)."""
    from distributed import get_worker

    try:
        return get_worker().address, value
    except ValueError:
        return None, value


class SessionCluster:
    """Stands in for ``distributed.LocalCluster``: hands out the shared cluster, records the
    keyword arguments it was asked with, and takes ``close`` as a note (conftest closes the
    real one)."""

    def __init__(self, cluster):
        self.cluster, self.asked, self.closed = cluster, None, False

    def __call__(self, **kwargs):
        self.asked = kwargs
        return self

    def __getattr__(self, name):
        return getattr(self.cluster, name)

    def close(self):
        self.closed = True


def test_local_cluster_same_as_serial(dask_cluster, monkeypatch):
    import distributed

    stand_in = SessionCluster(dask_cluster)
    monkeypatch.setattr(distributed, "LocalCluster", stand_in)
    inputs = scene_inputs(CASE, {}, 0.05, 0.15e-3)
    run = dict(paths=(CASE,), base_overrides={}, inputs=inputs, samples=4, seed=3, n_modes=2,
               elements=2)
    serial = monte_carlo(**run, n_jobs=1)
    with use_scheduler("local") as client:
        assert client is not None
        distributed_run = monte_carlo(**run)
        ran = run_tasks(_worker_and, [(k,) for k in range(4)])
        cluster = set(client.nthreads())
        assert not stand_in.closed
    # one single-threaded worker process per core, closed with the block
    asked = {k: stand_in.asked.get(k) for k in ("n_workers", "threads_per_worker", "processes")}
    assert asked == dict(n_workers=os.cpu_count(), threads_per_worker=1, processes=True)
    assert stand_in.closed
    assert np.array_equal(serial.samples, distributed_run.samples, equal_nan=True)
    assert [v for _, v in ran] == [0, 1, 2, 3]  # task order
    assert all(address in cluster for address, _ in ran)  # on the cluster's workers
