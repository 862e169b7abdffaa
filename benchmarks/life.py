"""Stress field and life of Table II case 3 at one speed against the steady response alone
(target: at most 2x), each with its own default basis (the response's 6 static modes per pose,
the stress's 14), 37 poses, 180 crank angles, 1200 rev/min.

    PYTHONPATH=. python benchmarks/life.py [--repeats N] [--speed RPM]

CPU time of this process with BLAS on one thread, best of the repeats, each from the scene
file read once: the steady response alone is ``forced_model`` + ``steady_response`` (its
verdict included); the stress and life are ``stress_model`` + ``stress_field`` (the same
verdict) + ``life_study``. The peak stress's error estimate (one refined mesh and one enlarged
basis, ``studies.life.convergence``) is timed apart: it is two more stress fields by design.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from flexlink.scene import load_scene  # noqa: E402
from flexlink.studies.life.convergence import peak_error  # noqa: E402
from flexlink.studies.life.life import Conditions, life_study  # noqa: E402
from flexlink.studies.life.stress_field import stress_field, stress_model  # noqa: E402
from flexlink.studies.running.steady_response import forced_model, steady_response  # noqa: E402
from flexlink.units import RPM  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
RATIO = 2.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--speed", type=float, default=1200.0, help="rev/min")
    args = parser.parse_args()
    scene = load_scene(ROOT / "cases/case3.toml")
    speed = args.speed * RPM

    result_basis = []

    def response():
        model = forced_model(scene, n_modes=6)
        result_basis[:] = model.periodic.frequencies
        return steady_response(model, speed)

    def life():
        model = stress_model(scene)
        field = stress_field(model, speed)
        return model, field, life_study(scene, model, field, Conditions(reliability=0.99))

    alone, both = [], []  # interleaved, so a busy moment of the machine falls on both
    for _ in range(args.repeats):
        t = time.process_time()
        result = response()
        alone.append(time.process_time() - t)
        t = time.process_time()
        model, field, study = life()
        both.append(time.process_time() - t)
    alone, both = min(alone), min(both)
    t = time.process_time()
    error = peak_error(scene, field, model.elements[0])
    estimate = time.process_time() - t
    print(f"case 3 at {args.speed:g} rev/min, {len(model.forced.periodic.frequencies)} basis "
          f"vectors (response: {len(result_basis)}), {len(model.points.link)} stress points, 180 angles")
    print(f"steady response alone: {alone:.2f} s CPU (best of {args.repeats}; coupler midspan "
          f"peak strain {result.peak_strain[1] * 1e6:.4g} microstrain)")
    worst = study.links[0]
    print(f"stress field and life: {both:.2f} s CPU (best of {args.repeats}; worst link "
          f"{worst.link}, peak {worst.peak.value / 1e6:.4g} MPa, margin {worst.margin:.4g})")
    print(f"peak stress error estimate (apart): {estimate:.2f} s CPU, largest "
          f"{error.estimate.max() * 100:.2g} % ({'within' if error.met else 'NOT within'} "
          f"{error.tolerance * 100:g} %)")
    ratio = both / alone
    print(f"stress field and life at most {RATIO:g}x the steady response alone: "
          f"{'MET' if ratio <= RATIO else 'NOT MET'} ({ratio:.2f}x)")


if __name__ == "__main__":
    main()
