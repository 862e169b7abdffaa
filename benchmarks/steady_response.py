"""One steady-response speed (target: under 50 ms): Table II case 3, 6 modes, 37 poses,
180 crank angles, at 600 and 2000 rev/min.

    PYTHONPATH=. python benchmarks/steady_response.py [--repeats N]

CPU time of this process with BLAS on one thread, per speed, the model (built once per scene)
apart, split into the solution (harmonic balance, ``steady_response.periodic_solution``) and
the verdict (the stability map's multipliers, ``stability_map.speed_multipliers``). The
figure judged is the slower speed's best of the repeats of the whole ``steady_response``.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from flexlink.scene import load_scene  # noqa: E402
from flexlink.analysis.periodic import speed_multipliers  # noqa: E402
from flexlink.studies.running.steady_response import (  # noqa: E402
    forced_model,
    periodic_solution,
    steady_response,
)
from flexlink.units import RPM  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
GOAL = 0.050  # s
SPEEDS = (600.0, 2000.0)  # rev/min


def _best(repeats, work):
    """(the best CPU time [s] of ``repeats`` calls of work(), its last result)."""
    times = []
    for _ in range(repeats):
        t = time.process_time()
        result = work()
        times.append(time.process_time() - t)
    return min(times), result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=3)
    repeats = parser.parse_args().repeats
    t0 = time.process_time()
    model = forced_model(load_scene(ROOT / "cases/case3.toml"), n_modes=6)
    _ = model.periodic.adiabatic  # the verdict's adiabatic basis: built once per model, like it
    print(f"case 3, 6 modes: model and adiabatic basis {time.process_time() - t0:.2f} s CPU "
          "(once per scene)")
    worst = 0.0
    for rpm in SPEEDS:
        speed = rpm * RPM
        solve, solution = _best(repeats, lambda w=speed: periodic_solution(model, w))
        verdict, _ = _best(repeats, lambda w=speed: speed_multipliers(model.periodic, w))
        whole, result = _best(repeats, lambda w=speed: steady_response(model, w))
        worst = max(worst, whole)
        print(f"{rpm:g} rev/min: {whole * 1e3:.1f} ms (best of {repeats}): solution "
              f"{solve * 1e3:.1f} ms ({solution.harmonics} harmonics, estimated error "
              f"{solution.error:.1e}), verdict {verdict * 1e3:.1f} ms (largest |mu| "
              f"{result.largest_modulus:.3f}); coupler peak strain "
              f"{result.peak_strain[1] * 1e6:.4g} microstrain")
    print(f"one steady-response speed: under {GOAL * 1e3:g} ms: "
          f"{'MET' if worst < GOAL else 'NOT MET'} ({worst * 1e3:.1f} ms)")


if __name__ == "__main__":
    main()
