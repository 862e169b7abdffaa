"""Modes at an operating point: the cost of one solve at speed against the static solve of the
same model (target: at most 3x).

    PYTHONPATH=. python benchmarks/operating_point.py [--repeats N]

"Static" is ``analysis.modal.analyze`` (what ``flexlink modes`` solves per scene); "at speed" is
``studies.running.modes_at_speed.operating_modes``, which includes that static solve (its modes are the
ones each mode at speed is paired with), the preload, the geometric and rotating-frame matrices
and the quadratic eigen solve. CPU time of this process with BLAS on one thread, medians over
repeats, each run interleaved with its static twin so both see the same machine load.
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

ROOT = Path(__file__).resolve().parent.parent

from flexlink.analysis.modal import analyze  # noqa: E402
from flexlink.scene import load_scene  # noqa: E402
from flexlink.studies.running.modes_at_speed import operating_modes  # noqa: E402

GOAL = 3.0
RUNS = (  # scene, elements per link (the mesh `flexlink modes` picks or the scene pins), speed
    ("cases/case1.toml", 64, 2000.0),
    ("cases/case3.toml", 32, 2000.0),
    ("scenes/kineto_aluminium.toml", 16, 600.0),
    ("scenes/wiper.toml", 8, 60.0),
    ("scenes/rotor.toml", 32, 500.0),
)


def cpu(work) -> float:
    start = time.process_time()
    work()
    return time.process_time() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()
    logging.disable(logging.WARNING)  # the scenes' plausibility warnings, once per solve
    print(f"modes at an operating point vs static: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
          f"load average {os.getloadavg()[0]:.2f}; CPU ms, medians of {args.repeats}")
    worst = 0.0
    for path, elements, rpm in RUNS:
        scene = load_scene(ROOT / path)
        speed = rpm * 2 * math.pi / 60
        static, at_speed = [], []
        def plain(scene=scene, elements=elements):
            analyze(scene, 4, elements)

        def moving(scene=scene, elements=elements, speed=speed):
            operating_modes(scene, speed, 4, elements)

        for _ in range(args.repeats + 1):  # the first pair warms the caches, then is dropped
            static.append(cpu(plain))
            at_speed.append(cpu(moving))
        s, o = statistics.median(static[1:]), statistics.median(at_speed[1:])
        worst = max(worst, o / s)
        print(f"  {path} ({elements} elements/link, {rpm:g} rev/min): static {1e3 * s:.1f} ms, "
              f"at speed {1e3 * o:.1f} ms, ratio {o / s:.2f}")
    print(f"  target one operating-point modal solve <= {GOAL:g}x the static solve: worst "
          f"{worst:.2f}x (goal <= {GOAL:g}x) {'MET' if worst <= GOAL else 'NOT MET'}")


if __name__ == "__main__":
    main()
