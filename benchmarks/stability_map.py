"""Stability map of Table II case 1: 300 speeds over 0:3000 rev/min, 6 modes (target: under
10 s on one core).

    PYTHONPATH=. python benchmarks/stability_map.py [--speeds N] [--integrator magnus]

CPU time of this process with BLAS on one thread: the periodic model (37 poses) and the Floquet
map over the speeds, reported apart and together. The default adiabatic steps
(``analysis.adiabatic``) count their basis, built once per model, in the map's time;
``--integrator magnus``: the Magnus steps instead (docs/critical-speeds.md, "Speed").
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import math  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from flexlink.scene import load_scene  # noqa: E402
from flexlink.analysis.periodic import Integrator, periodic_model  # noqa: E402
from flexlink.studies.running.stability_map import stability_map  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
GOAL = 10.0  # s


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--speeds", type=int, default=300)
    parser.add_argument("--integrator", choices=[i.value for i in Integrator],
                        default=Integrator.ADIABATIC.value)
    args = parser.parse_args()
    count, integrator = args.speeds, Integrator(args.integrator)
    t0 = time.process_time()
    model = periodic_model(load_scene(ROOT / "cases/case1.toml"), n_modes=6)
    t1 = time.process_time()
    result = stability_map(model, np.linspace(0.0, 3000.0, count) * 2 * math.pi / 60,
                           integrator=integrator)
    t2 = time.process_time()
    total = t2 - t0
    print(f"case 1, {count} speeds, 6 modes, {integrator.value} steps (basis {model.basis.size} vectors, check "
          f"{100 * model.basis.error:.3g} %): model {t1 - t0:.2f} s, map {t2 - t1:.2f} s, "
          f"total {total:.2f} s CPU; {len(result.ranges)} unstable ranges")
    print(f"stability map under {GOAL:g} s: {'MET' if total < GOAL else 'NOT MET'}")


if __name__ == "__main__":
    main()
