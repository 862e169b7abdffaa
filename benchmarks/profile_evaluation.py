"""What one calibration evaluation costs: 200 loads of the Table II cases with varying overrides,
each followed by ``families.elastic_modes(scene, 4, 6)`` (what ``calibration.predict`` does per
scene). Prints the CPU per evaluation split into loading and analysis (best of 3 rounds); with
``--profile``, cProfile's top entries by cumulative time.

Run: OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/profile_evaluation.py [--profile]
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import cProfile  # noqa: E402
import logging  # noqa: E402
import pstats  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from flexlink.analysis.families import elastic_modes  # noqa: E402
from flexlink.scene import load_scene  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CASES = [ROOT / "cases" / f"case{i}.toml" for i in (1, 2, 3, 4)]


def evaluations(n: int = 200) -> tuple[float, float]:
    """(load, analysis) CPU per evaluation [ms] over ``n`` evaluations."""
    load = analysis = 0.0
    for i in range(n):
        overrides = {"section.width": f"{20 + (i % 13) * 0.7} mm",
                     "joints.Kt": f"{1e6 * (1 + i % 7)} N/m"}
        t0 = time.process_time()
        scene = load_scene(CASES[i % 4], overrides=overrides)
        t1 = time.process_time()
        elastic_modes(scene, 4, 6)
        t2 = time.process_time()
        load, analysis = load + t1 - t0, analysis + t2 - t1
    return 1e3 * load / n, 1e3 * analysis / n


def main():
    logging.disable(logging.WARNING)  # the cases' slenderness warnings, once per evaluation
    evaluations(40)  # imports and caches out of the picture
    load, analysis = min((evaluations() for _ in range(3)), key=sum)
    print(f"per evaluation: load {load:.3f} ms, analysis {analysis:.3f} ms, "
          f"total {load + analysis:.3f} ms CPU")
    if "--profile" in sys.argv:
        profile = cProfile.Profile()
        profile.runcall(evaluations)
        pstats.Stats(profile).sort_stats("cumulative").print_stats(30)


if __name__ == "__main__":
    main()
