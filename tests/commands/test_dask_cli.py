"""`--scheduler` of `modes --sensitivity` and `cycle`: on a LocalCluster of worker processes the
JSON documents are the serial run's, and the work did run on the cluster.

The same documents to round-off (`contents.mismatches`: text and integers exactly, numbers to
`contents.RTOL` of their array's scale), not bit for bit: a dense eigen solve in another
process may sum in another order (with two BLAS threads the parent's first frequency of case 2
was measured 25.296377744065346 against ...36 Hz in a worker), and a CPU or BLAS of another
kind moves the last bits of every number. Both runs are subprocesses with one BLAS thread, as
every dask worker has (its nanny sets OPENBLAS_NUM_THREADS=1), so they share the machine's two
cores evenly."""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

# distributed: imported by the dask_cluster fixture (which skips without it), not at collection

from conftest import ROOT
from contents import mismatches
ONE_BLAS_THREAD = {name: "1" for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                          "MKL_NUM_THREADS")}


@pytest.fixture
def cluster(dask_cluster):
    """(scheduler address, a client of it) of the tests' shared LocalCluster of two worker
    processes (conftest)."""
    from distributed import Client

    with Client(dask_cluster) as client:
        client.get_task_stream()  # starts the scheduler's record of every task from here on
        yield dask_cluster.scheduler_address, client


def flexlink_started(*args) -> subprocess.Popen:
    """`flexlink ARGS --json` started in a fresh process with one BLAS thread."""
    env = {**os.environ, **ONE_BLAS_THREAD,
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    return subprocess.Popen([sys.executable, "-m", "flexlink.cli", *map(str, args), "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            cwd=ROOT)


def flexlink_json(child: subprocess.Popen, out: Path) -> dict:
    """The --json document of a run of ``flexlink_started`` into the folder ``out``, once it
    has ended, with ``out`` written as OUT in the file names it lists."""
    try:
        stdout, stderr = child.communicate(timeout=300)  # a guard against a hang only
    finally:
        child.kill()
    assert child.returncode == 0, stderr[-2000:]
    return json.loads(stdout.replace(str(out), "OUT"))


def serial_and_distributed(run: tuple, address: str, tmp_path: Path,
                           serial_options=()) -> tuple[dict, dict]:
    """The --json documents of ``run`` on this machine and on the cluster at ``address``, each
    into a folder of its own under ``tmp_path``. The two processes run side by side: the
    serial one sends no task to the cluster."""
    folders = tmp_path / "serial", tmp_path / "distributed"
    serial = flexlink_started(*run, *serial_options, "--out", folders[0])
    distributed = flexlink_started(*run, "--scheduler", address, "--out", folders[1])
    return flexlink_json(serial, folders[0]), flexlink_json(distributed, folders[1])


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
    run = ("modes", ROOT / "cases" / "case2.toml", "-n", "2", "--sensitivity", "--samples", "10")
    since = time.time()
    serial, distributed = serial_and_distributed(run, address, tmp_path, ("-j", "1"))
    assert not mismatches(untimed(distributed), untimed(serial))
    sensitivity = serial["cases"][0]["sensitivity"]
    # the nominal model, both ends of every ranged input, then the Monte Carlo samples
    assert cluster_tasks(client, since) == 1 + 2 * len(sensitivity["inputs"]) + 10


@pytest.mark.parametrize("order", ["--track", "--sorted"])
def test_cycle_on_cluster_same_as_serial(cluster, tmp_path, order):
    address, client = cluster
    run = ("cycle", ROOT / "cases" / "case1.toml", "--poses", "36", order)
    since = time.time()
    serial, distributed = serial_and_distributed(run, address, tmp_path)
    assert not mismatches(untimed(distributed), untimed(serial))
    # tracked: 4 chunks of poses per worker; sorted: the Craig-Bampton map as one task
    assert cluster_tasks(client, since) == (8 if order == "--track" else 1)
