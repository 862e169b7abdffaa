"""Many independent evaluations on all cores (joblib) or on a dask.distributed cluster, with an
optional tqdm progress bar.

Results come back in task order whatever the scheduling, so a run seeded once in the parent
process is reproducible whatever the number of workers or machines. The tasks' warnings, in
this process or in a worker, are not shown one by one: they come back with the results and are
summarised once (``logbook.report``).

By default the work stays on this machine (joblib's process pool, or this process for
``n_jobs=1``). Inside ``use_scheduler(address)`` it goes to dask.distributed instead (the
optional ``dask`` extra): ``"local"`` starts a LocalCluster of worker processes on this machine
for the block, any other address (``tcp://host:8786``) joins a running scheduler whose workers
may sit on other machines (docs/performance.md says how to start them).
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterator, Sequence

from flexlink import logbook
from flexlink.errors import InputError

_client = None  # the dask.distributed Client of the innermost ``use_scheduler`` block


@contextlib.contextmanager
def use_scheduler(address: str | None) -> Iterator[object]:
    """Run every ``run_tasks`` of the block on dask.distributed: ``"local"`` (a LocalCluster of
    one single-threaded worker process per core, closed at the end of the block) or a
    scheduler address; None changes nothing. Yields the Client (or None)."""
    global _client
    if address is None:
        yield None
        return
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise InputError("dask.distributed is not installed", field="--scheduler",
                         expected="pip install 'flexlink[dask]'") from None
    cluster = None
    if address == "local":  # the status page on any free port: 8787 may be another cluster's
        cluster = LocalCluster(n_workers=os.cpu_count() or 1, threads_per_worker=1,
                               processes=True, dashboard_address=":0")
    try:
        client = Client(cluster if cluster is not None else address, timeout="30s")
    except OSError as exc:
        if cluster is not None:
            cluster.close()
        raise InputError(f"cannot reach the dask scheduler: {exc}", field="--scheduler",
                         expected="'local' or a running scheduler's address, e.g. "
                                  "tcp://host:8786") from None
    previous, _client = _client, client
    try:
        yield client
    finally:
        _client = previous
        client.close()
        if cluster is not None:
            cluster.close()


def on_cluster() -> bool:
    """Whether ``run_tasks`` goes to dask.distributed here (inside ``use_scheduler``)."""
    return _client is not None


def workers(n_jobs: int = -1) -> int:
    """How many tasks run at once: the cluster's worker threads inside ``use_scheduler``, else
    joblib's count for ``n_jobs`` (-1 = all cores)."""
    if _client is not None:
        return max(1, sum(_client.nthreads().values()))
    from joblib import effective_n_jobs

    return effective_n_jobs(n_jobs)



def _collecting_call(function: Callable, task: tuple):
    # module level, so joblib can send it to a worker process
    with logbook.collecting() as records:
        result = function(*task)
    return result, list(records)


def run_tasks(function: Callable, tasks: Sequence[tuple], *, n_jobs: int = -1,
              show_progress: bool = False, label: str = "tasks") -> list:
    """[function(*task) for task in tasks], on ``n_jobs`` workers (-1 = all cores; 1 = in this
    process, no pool) or on the dask cluster of ``use_scheduler``, showing a tqdm bar on stderr
    when ``show_progress``. ``label`` names the tasks (plural) in the bar and in the warnings'
    summary."""
    from joblib import Parallel, delayed
    from tqdm import tqdm

    bar = tqdm(total=len(tasks), desc=label, disable=not show_progress, leave=False)
    on_dask = _client is not None
    if on_dask:
        calls = _on_dask(function, tasks, bar)  # advances the bar as tasks finish
    elif n_jobs == 1:
        calls = (_collecting_call(function, task) for task in tasks)
    else:
        calls = Parallel(n_jobs=n_jobs, return_as="generator")(
            delayed(_collecting_call)(function, task) for task in tasks)
    out, records = [], []
    for result, warned in calls:
        out.append(result)
        records += warned
        if not on_dask:
            bar.update()
    bar.close()
    logbook.report(records, f"{len(tasks)} {label}")
    return out


def _on_dask(function: Callable, tasks: Sequence[tuple], bar) -> list:
    """(result, warnings) per task, in task order, from the cluster of ``use_scheduler``."""
    from distributed import as_completed

    # pure=False: equal arguments are still separate tasks (dask would otherwise merge them)
    futures = [_client.submit(_collecting_call, function, task, pure=False) for task in tasks]
    for _ in as_completed(futures):
        bar.update()
    return _client.gather(futures)  # in task order; re-raises a task's exception
