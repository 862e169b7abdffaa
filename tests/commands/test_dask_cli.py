"""`--scheduler` of `modes --sensitivity` and `cycle`: on a LocalCluster of worker processes the
JSON documents are the serial run's, bit for bit, and the work did run on the cluster.

Both runs are subprocesses with one BLAS thread, as every dask worker has (its nanny sets
OPENBLAS_NUM_THREADS=1): with two BLAS threads a dense eigen solve of the parent differs from a
worker's in the last bit (measured: 25.296377744065346 against ...36 Hz for case 2's first
mode), whoever schedules it."""

import json
import os
import subprocess
import sys
import time

import pytest

pytest.importorskip("distributed")

from conftest import ROOT
ONE_BLAS_THREAD = {name: "1" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                          "MKL_NUM_THREADS")}


@pytest.fixture(scope="module")
def cluster(dask_cluster):
    """(scheduler address, a client of it) of the session's LocalCluster of two worker
    processes (conftest)."""
    from distributed import Client

    with Client(dask_cluster) as client:
        client.get_task_stream()  # starts the scheduler's record of every task from here on
        yield dask_cluster.scheduler_address, client


def flexlink_json(*args) -> dict:
    """The --json document of `flexlink ARGS`, run in a fresh process with one BLAS thread."""
    env = {**os.environ, **ONE_BLAS_THREAD,
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-m", "flexlink.cli", *map(str, args), "--json"],
                          capture_output=True, text=True, env=env, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout)


def untimed(document):
    """``document`` without its wall-clock fields ("seconds"), which no two runs share."""
    if isinstance(document, dict):
        return {k: untimed(v) for k, v in document.items() if k != "seconds"}
    if isinstance(document, list):
        return [untimed(v) for v in document]
    return document


def cluster_tasks(client, since: float) -> int:
    """Tasks of ``parallel.run_tasks`` that the cluster finished after ``since`` (time.time)."""
    return sum(t["key"].startswith("_collecting_call")
               for t in client.get_task_stream(start=since))


def test_modes_sensitivity_on_cluster_same_as_serial(cluster, tmp_path):
    address, client = cluster
    run = ("modes", ROOT / "cases" / "case2.toml", "-n", "2", "--sensitivity", "--samples", "10",
           "--out", tmp_path)
    serial = flexlink_json(*run, "-j", "1")
    since = time.time()
    distributed = flexlink_json(*run, "--scheduler", address)
    assert untimed(distributed) == untimed(serial)
    sensitivity = serial["cases"][0]["sensitivity"]
    # the nominal model, both ends of every ranged input, then the Monte Carlo samples
    assert cluster_tasks(client, since) == 1 + 2 * len(sensitivity["inputs"]) + 10


@pytest.mark.parametrize("order", ["--track", "--sorted"])
def test_cycle_on_cluster_same_as_serial(cluster, tmp_path, order):
    address, client = cluster
    run = ("cycle", ROOT / "cases" / "case1.toml", "--poses", "36", order, "--out", tmp_path)
    serial = flexlink_json(*run)
    since = time.time()
    distributed = flexlink_json(*run, "--scheduler", address)
    assert untimed(distributed) == untimed(serial)
    # tracked: 4 chunks of poses per worker; sorted: the Craig-Bampton map as one task
    assert cluster_tasks(client, since) == (8 if order == "--track" else 1)
