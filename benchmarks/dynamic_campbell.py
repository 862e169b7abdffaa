"""Speed-dependent Campbell diagram: the cost of Table II case 1 at 72 poses x 50 speeds
(target: under 10 s on one core).

    PYTHONPATH=. python benchmarks/dynamic_campbell.py [--repeats N]

Times ``studies.running.dynamic_campbell.dynamic_campbell`` on the mesh `flexlink campbell` picks for
case 1 with 3 tracked modes (32 elements per link), 0 .. 2500 rev/min (below its divergence
near 2755 rev/min, so every pose and speed is solved): the static modes and the
reduced operating-point matrices at every pose, the small quadratic solve at every pose and
speed, and the tracking at every speed. CPU time of this process with BLAS on one thread;
the best and the median of the repeats.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import logging  # noqa: E402
import math  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

from flexlink.scene import load_scene  # noqa: E402
from flexlink.studies.running.dynamic_campbell import dynamic_campbell  # noqa: E402

GOAL = 10.0  # [s]
POSES, SPEEDS, ELEMENTS, TOP_RPM = 72, 50, 32, 2500.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    logging.disable(logging.WARNING)
    scene = load_scene(ROOT / "cases/case1.toml")
    speeds = np.linspace(0.0, TOP_RPM * 2 * math.pi / 60, SPEEDS)
    times = []
    for _ in range(args.repeats):
        start = time.process_time()
        result = dynamic_campbell(scene, speeds, POSES, 3, ELEMENTS)
        times.append(time.process_time() - start)
    best, median = min(times), statistics.median(times)
    print(f"dynamic Campbell: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
          f"average {os.getloadavg()[0]:.2f}; {args.repeats} runs")
    print(f"  Table II case 1, {POSES} poses x {SPEEDS} speeds (0-{TOP_RPM:g} rev/min, "
          f"{ELEMENTS} elements/link, {result.basis} static modes per pose): best {best:.2f} s, "
          f"median {median:.2f} s CPU")
    print(f"  target dynamic Campbell of case 1 (72 x 50) under {GOAL:g} s on one core: "
          f"{median:.2f} s {'MET' if median < GOAL else 'NOT MET'}")


if __name__ == "__main__":
    main()
