"""Many independent evaluations on all cores (joblib), with an optional tqdm progress bar.

Results come back in task order whatever the scheduling, so a run seeded once in the parent
process is reproducible whatever the number of workers. The tasks' warnings, in this process
or in a worker, are not shown one by one: they come back with the results and are summarised
once (``logbook.report``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from flexlink import logbook


def _collecting_call(function: Callable, task: tuple):
    # module level, so joblib can send it to a worker process
    with logbook.collecting() as records:
        result = function(*task)
    return result, list(records)


def run_tasks(function: Callable, tasks: Sequence[tuple], *, n_jobs: int = -1,
              progress: bool = False, label: str = "tasks") -> list:
    """[function(*task) for task in tasks], on ``n_jobs`` workers (-1 = all cores; 1 = in this
    process, no pool), showing a tqdm bar on stderr when ``progress``. ``label`` names the
    tasks (plural) in the bar and in the warnings' summary."""
    from joblib import Parallel, delayed
    from tqdm import tqdm

    bar = tqdm(total=len(tasks), desc=label, disable=not progress, leave=False)
    if n_jobs == 1:
        calls = (_collecting_call(function, task) for task in tasks)
    else:
        calls = Parallel(n_jobs=n_jobs, return_as="generator")(
            delayed(_collecting_call)(function, task) for task in tasks)
    out, records = [], []
    for result, warned in calls:
        out.append(result)
        records += warned
        bar.update()
    bar.close()
    logbook.report(records, f"{len(tasks)} {label}")
    return out
