"""Helpers of scripts/mutation.sh, run inside the scratch copy (reads mutmut's mutants/*.meta).

    python mutation_table.py pick TARGET N SEED   N mutant names of TARGET drawn at random
    python mutation_table.py table TARGET [N SEED]  per-module counts of the mutants run so
                                                  far (of those N drawn, if given)
    python mutation_table.py run JOBS NAME...     `mutmut run` without its clean test run

TARGET is a package folder (flexlink/fe) or a module (flexlink/units.py). A random sample
estimates the kill rate without mutmut's fastest-first order, which would favour mutants
that die early; the table gives a 95 % Wilson interval for each rate.
"""

import json
import math
import random
import sys
from pathlib import Path

from mutmut.stats import status_by_exit_code

COLUMNS = ("mutants", "checked", "killed", "survived", "no tests", "other")


def metas(target: str) -> list[Path]:
    path = Path("mutants") / target
    if path.suffix == ".py":
        return [path.with_name(path.name + ".meta")]
    return sorted(path.rglob("*.py.meta"))


def exit_codes(meta: Path) -> dict:
    return json.loads(meta.read_text())["exit_code_by_key"]


def drawn(target: str, n: int, seed: int) -> list[str]:
    """N mutant names of TARGET in the order drawn: the first k of N are the draw of k (the
    same seed), so a sample cut short is still a random sample of its completed prefix."""
    names = sorted(name for meta in metas(target) for name in exit_codes(meta))
    return random.Random(seed).sample(names, min(n, len(names)))


def pick(target: str, n: int, seed: int) -> None:
    print("\n".join(sorted(drawn(target, n, seed))))


def wilson(k: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """95 % Wilson score interval of a binomial proportion k / n."""
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return centre - half, centre + half


def row(name: str, counts: dict, wall: float | None) -> str:
    cells = " ".join(f"{counts[c]:>8}" for c in COLUMNS)
    if counts["checked"]:
        lo, hi = wilson(counts["killed"], counts["checked"])
        rate = (f"{100 * counts['killed'] / counts['checked']:5.1f} % "
                f"[{100 * lo:3.0f}, {100 * hi:3.0f}]")
    else:
        rate = "    -             "
    time = f"{wall:7.0f} s" if wall is not None else ""
    return f"{name:40} {cells}  {rate} {time}"


def table(target: str, only: set[str] | None = None) -> None:
    """Killed includes timeouts (as in mutmut's own score); "other" is suspicious, segfault,
    interrupted. The rate is killed over checked, so "no tests" counts against it. Wall: the
    sum of the module's mutant run times (the wall time spent on it when JOBS=1)."""
    print(f"{'module':40} " + " ".join(f"{c:>8}" for c in COLUMNS)
          + "  kill rate [95 % CI]     wall")
    total = dict.fromkeys(COLUMNS, 0)
    total_wall = 0.0
    for meta in metas(target):
        data = json.loads(meta.read_text())
        counts = dict.fromkeys(COLUMNS, 0)
        for name, code in data["exit_code_by_key"].items():
            counts["mutants"] += 1
            if code is None or (only is not None and name not in only):
                continue
            counts["checked"] += 1
            status = status_by_exit_code[code]
            status = "killed" if status == "timeout" else status
            counts[status if status in COLUMNS else "other"] += 1
        if not counts["mutants"]:
            continue
        wall = sum(t for name, t in data.get("durations_by_key", {}).items()
                   if only is None or name in only)
        total_wall += wall
        for c in COLUMNS:
            total[c] += counts[c]
        print(row(str(meta.relative_to("mutants"))[: -len(".meta")], counts, wall))
    print(row(f"total {target}", total, total_wall))


def run_without_clean_run(jobs: int, names: list[str]) -> None:
    """`mutmut run --max-children JOBS NAME...` minus its first step, which runs every test
    the named mutants select on the unmutated code. That step repeats the stats phase, which
    itself fails unless the whole suite passes (mutmut runs it with -x), so right after a stats
    phase on the same sources it costs a suite's time for nothing."""
    import mutmut.__main__ as mutmut_main

    make_runner = mutmut_main.get_mutant_runner

    def runner_without_clean_run(*args, **kwargs):
        runner = make_runner(*args, **kwargs)
        runner.run_clean_tests = lambda tests: 0
        return runner

    mutmut_main.get_mutant_runner = runner_without_clean_run
    mutmut_main.cli(["run", "--max-children", str(jobs), *names])


if __name__ == "__main__":
    command, target, *rest = sys.argv[1:]
    if command == "run":
        run_without_clean_run(int(target), rest)
    elif command == "pick":
        pick(target, int(rest[0]), int(rest[1]))
    else:
        table(target, set(drawn(target, int(rest[0]), int(rest[1]))) if rest else None)
