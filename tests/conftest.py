"""Shared test settings: repository paths, shipped scenes and the hypothesis profiles.

Property tests draw random linkages; the profile sets how many. ``ci`` (the default) is quick
and derandomised, so a CI run is reproducible; ``thorough`` is for a deliberate hunt:
``HYPOTHESIS_PROFILE=thorough python -m pytest tests/properties``.
"""

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

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


@pytest.fixture(scope="session")
def dask_cluster():
    """One LocalCluster of two single-threaded worker processes for every dask test: starting
    one, warming its workers' imports and closing it costs seconds each time."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        yield cluster
