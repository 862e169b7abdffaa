"""Many independent evaluations on all cores (joblib), with an optional tqdm progress bar.

Results come back in task order whatever the scheduling, so a run seeded once in the parent
process is reproducible whatever the number of workers.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence


def run_tasks(function: Callable, tasks: Sequence[tuple], *, n_jobs: int = -1,
              progress: bool = False, label: str = "") -> list:
    """[function(*task) for task in tasks], on ``n_jobs`` workers (-1 = all cores; 1 = in this
    process, no pool), showing a tqdm bar on stderr when ``progress``."""
    from joblib import Parallel, delayed
    from tqdm import tqdm

    bar = tqdm(total=len(tasks), desc=label, disable=not progress, leave=False)
    if n_jobs == 1:
        out = []
        for task in tasks:
            out.append(function(*task))
            bar.update()
        bar.close()
        return out
    results = Parallel(n_jobs=n_jobs, return_as="generator")(delayed(function)(*t) for t in tasks)
    out = []
    for result in results:
        out.append(result)
        bar.update()
    bar.close()
    return out
