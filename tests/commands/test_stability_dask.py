"""`stability-map --scheduler`: on a LocalCluster of worker processes the JSON document is the
serial run's to round-off (`contents.mismatches`, as test_dask_cli says why), and the speeds did
run on the cluster (helpers and the cluster from test_dask_cli)."""

import time

# distributed: imported by the dask_cluster fixture (which skips without it), not at collection

from conftest import ROOT
from contents import mismatches
from test_dask_cli import cluster, cluster_tasks, serial_and_distributed, untimed  # noqa: F401


def test_stability_map_on_cluster_same_as_serial(cluster, tmp_path):  # noqa: F811
    address, client = cluster
    # high speeds: few Magnus steps a revolution, so the test stays cheap
    run = ("stability-map", ROOT / "cases" / "case1.toml", "--speeds", "2600:3000 rev/min",
           "--count", "5", "-n", "2", "--poses", "13")
    since = time.time()
    serial, distributed = serial_and_distributed(run, address, tmp_path)
    assert not mismatches(untimed(distributed), untimed(serial))
    # two workers, four chunks each, capped at one speed a chunk
    assert cluster_tasks(client, since) == 5
