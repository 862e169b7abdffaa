"""Shared test settings: repository paths, shipped scenes and the hypothesis profiles.

Property tests draw random linkages; the profile sets how many. ``ci`` (the default) is quick
and derandomised, so a CI run is reproducible; ``thorough`` is for a deliberate hunt:
``HYPOTHESIS_PROFILE=thorough python -m pytest tests/properties``.
"""

import logging
import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

# On a pytest-xdist worker (one per core: scripts/test.sh), BLAS threads of its own would only
# compete with the other workers for the same cores. Set before numpy is first imported (by a
# test module, after this file).
if os.environ.get("PYTEST_XDIST_WORKER"):
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

ROOT = Path(__file__).resolve().parent.parent
CASES_DIR = ROOT / "cases"
SCENES_DIR = ROOT / "scenes"
TABLE2_CASES = tuple(CASES_DIR / f"case{i}.toml" for i in (1, 2, 3, 4))

# Model builds take milliseconds to a second, so no per-example deadline; the too_slow check
# would only flag the eigen solves that every example needs.
settings.register_profile("ci", max_examples=20, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=400, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


@pytest.fixture
def root() -> Path:
    return ROOT


@pytest.fixture(params=TABLE2_CASES, ids=lambda p: p.stem)
def table2_case(request) -> Path:
    return request.param


# The dask tests share one LocalCluster: starting one, warming its workers' imports and closing it
# costs seconds. It is closed after the last of them, not at the end of the session, because
# its idle workers still take CPU from the tests that follow (their heartbeats: about 5 % of a
# core each, measured). Those tests run one after another (``pytest_collection_modifyitems``);
# a later one starts a new cluster.
_CLUSTER_USERS = "dask_cluster"
_cluster = None


@pytest.fixture
def dask_cluster():
    """The shared LocalCluster of two single-threaded worker processes, started by the first
    test that asks for it. Its scheduler's HTTP server takes a free port (":0"): without a
    dashboard address it still serves on 8787, or on another port with a warning when a second
    run on the machine holds 8787."""
    global _cluster
    distributed = pytest.importorskip("distributed")
    if _cluster is None:
        _cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                            dashboard_address=":0")
    return _cluster


def _close_cluster() -> None:
    """Close the cluster without its INFO lines: mid-run, they would land between the dots."""
    global _cluster
    if _cluster is not None:
        log = logging.getLogger("distributed")
        level = log.level
        log.setLevel(logging.ERROR)
        try:
            _cluster.close()
        finally:
            log.setLevel(level)
        _cluster = None


@pytest.hookimpl(wrapper=True)
def pytest_runtest_teardown(item, nextitem):
    yield  # the test's own fixtures (a client of the cluster) are torn down first
    if nextitem is None or _CLUSTER_USERS not in nextitem.fixturenames:
        _close_cluster()


def pytest_sessionfinish():
    _close_cluster()  # a run stopped early (-x) between two users of the cluster


def pytest_collection_modifyitems(items):
    """The cluster's users run one after another, at the place of the first, so one cluster
    serves them all in a serial run. A parallel run (scripts/test.sh) hands out whole files:
    a worker starts a cluster for each run of consecutive users it is given."""
    users = [item for item in items if _CLUSTER_USERS in item.fixturenames]
    if users:
        others = [item for item in items if _CLUSTER_USERS not in item.fixturenames]
        first = items.index(users[0])
        items[:] = others[:first] + users + others[first:]
