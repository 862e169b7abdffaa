"""One steady-response speed (target: under 50 ms): Table II case 3, 6 modes, 37 poses,
180 crank angles, at 600 and 2000 rev/min.

    PYTHONPATH=. python benchmarks/steady_response.py [--repeats N]

CPU time of this process with BLAS on one thread, per speed, the model (built once per scene)
apart. The figure judged is the slower speed's best of the repeats.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from flexlink.scene import load_scene  # noqa: E402
from flexlink.studies.steady_response import forced_model, steady_response  # noqa: E402
from flexlink.units import RPM  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
GOAL = 0.050  # s
SPEEDS = (600.0, 2000.0)  # rev/min


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=3)
    repeats = parser.parse_args().repeats
    t0 = time.process_time()
    model = forced_model(load_scene(ROOT / "cases/case3.toml"), n_modes=6)
    print(f"case 3, 6 modes: model {time.process_time() - t0:.2f} s CPU (once per scene)")
    worst = 0.0
    for rpm in SPEEDS:
        times = []
        for _ in range(repeats):
            t = time.process_time()
            result = steady_response(model, rpm * RPM)
            times.append(time.process_time() - t)
        worst = max(worst, min(times))
        print(f"{rpm:g} rev/min: {min(times) * 1e3:.1f} ms (best of {repeats}), largest |mu| "
              f"{result.largest_modulus:.3f}, coupler peak strain "
              f"{result.peak_strain[1] * 1e6:.4g} microstrain")
    print(f"one steady-response speed: under {GOAL * 1e3:g} ms: "
          f"{'MET' if worst < GOAL else 'NOT MET'} ({worst * 1e3:.1f} ms)")


if __name__ == "__main__":
    main()
