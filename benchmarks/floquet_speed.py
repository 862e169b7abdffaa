"""Floquet multipliers where the adiabatic steps are refused: the fourth-order Magnus steps at
h max|eig A| <= 2 (the fallback before, ``Integrator.MAGNUS``) against the fallback's
midpoint steps (``periodic.midpoint_multipliers``), CPU time and ln |mu| per turn of each.

    PYTHONPATH=. python benchmarks/floquet_speed.py [--quick]

Cases (Table II case 3, 37 poses, BLAS on one thread):
  1. Rayleigh damping (beta 1.1423e-4 s), 6 modes, 1200 rev/min: overdamped stiff vectors
     (real eigenvalues: the adiabatic basis is refused at every speed);
  2. the same with 14 modes (``response -n 14``), whose fourth-order count is only estimated
     (the CPU time of FOURTH_ORDER_SAMPLE steps times the count: tens of CPU-minutes);
  3. the scene's damping (0.01), 6 modes, 11.5 rev/min: the adiabatic steps' grid is too
     coarse for the damping spread and the modes keep too much energy for the quasi-static
     bound (the speeds between about 10.4 and 12.9 rev/min);
  4. ``stability-map --speeds "11:12.5 rev/min" --count 3`` and ``"13:20 rev/min"``, the map
     through its default path (adiabatic, then the fallback), before as the fallback was;
     ``"13:20 rev/min" -n 14``, where the adiabatic basis loses a mode: its fourth-order
     count estimated as in case 2.
``--quick``: the fourth-order runs of cases 3 and 4 (about a minute each) are skipped.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import logging  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from flexlink.analysis import periodic  # noqa: E402
from flexlink.analysis.floquet import monodromy  # noqa: E402
from flexlink.analysis.periodic import Integrator, multipliers_by, periodic_model  # noqa: E402
from flexlink.errors import NumericalError  # noqa: E402
from flexlink.scene import load_scene  # noqa: E402
from flexlink.studies.running.stability_map import stability_map  # noqa: E402
from flexlink.units import RPM  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CASE3 = ROOT / "cases/case3.toml"
RAYLEIGH = {"damping.rayleigh_beta": 1.1423e-4}
FOURTH_ORDER_SAMPLE = 4096  # steps timed to estimate a count too long to run


def _cpu(call):
    start = time.process_time()
    out = call()
    return out, time.process_time() - start


def _fourth_order_count(model, speed: float) -> int:
    """The fourth-order steps a turn the fallback took before (h max|eig A| <= STEP_PHASE)."""
    system = model.system(speed, energy_coordinates=True)
    size = np.abs(np.linalg.eigvals(system((model.angles - model.angles[0]) / speed))).max()
    return max(200, int(np.ceil(2.0 * np.pi / speed * size / periodic.STEP_PHASE)))


def _built(model):
    """The model with its adiabatic basis (or its refusal) built: a cost of every speed's
    path, before as after, kept out of the timings."""
    try:
        _ = model.adiabatic
    except NumericalError:
        pass
    return model


def _compare(label: str, model, rpm: float, run_fourth: bool) -> None:
    speed = rpm * RPM
    steps = []
    (after, used), t_after = _cpu(lambda: multipliers_by(model, speed, on_steps=steps.append))
    count = _fourth_order_count(model, speed)
    line = (f"{label}: after {used.value} {sum(steps)} steps {t_after:.2f} s, ln|mu| "
            f"{after.growth_per_period:.7f}; before {count} fourth-order steps")
    if run_fourth:
        (before, _), t_before = _cpu(lambda: multipliers_by(model, speed,
                                                            integrator=Integrator.MAGNUS))
        line += (f" {t_before:.2f} s, ln|mu| {before.growth_per_period:.7f} (difference "
                 f"{abs(after.growth_per_period - before.growth_per_period):.2g})")
    else:
        system = model.system(speed, energy_coordinates=True)
        _, t_sample = _cpu(lambda: monodromy(system, 2.0 * np.pi / speed, FOURTH_ORDER_SAMPLE))
        line += f" estimated {t_sample * count / FOURTH_ORDER_SAMPLE:.0f} s"
    print(line, flush=True)


def _map(label: str, model, low: float, high: float, run_fourth: bool) -> None:
    speeds = np.linspace(low, high, 3) * RPM
    result, t_after = _cpu(lambda: stability_map(model, speeds))
    line = (f"{label}: after {t_after:.2f} s (fallback at {int(result.magnus_fallback.sum())}, "
            f"quasi-static at {int(result.quasi_static.sum())} of 3 speeds), largest |mu| "
            f"{result.largest_modulus.max():.4g}")
    if run_fourth:
        most = periodic.FOURTH_ORDER_MOST
        periodic.FOURTH_ORDER_MOST = periodic.MAGNUS_BUDGET  # the fallback as it was
        try:
            before, t_before = _cpu(lambda: stability_map(model, speeds))
        finally:
            periodic.FOURTH_ORDER_MOST = most
        line += (f"; before {t_before:.2f} s, largest ln|mu| difference "
                 f"{np.abs(np.log(before.largest_modulus) - np.log(result.largest_modulus)).max():.2g}")
    print(line, flush=True)


def _map_estimated(label: str, model, low: float, high: float) -> None:
    """A map whose fourth-order fallback is too long to run: after measured, before
    estimated from FOURTH_ORDER_SAMPLE timed steps at the first speed."""
    speeds = np.linspace(low, high, 3) * RPM
    result, t_after = _cpu(lambda: stability_map(model, speeds))
    counts = [_fourth_order_count(model, w) for w in speeds]
    system = model.system(speeds[0], energy_coordinates=True)
    _, t_sample = _cpu(lambda: monodromy(system, 2.0 * np.pi / speeds[0], FOURTH_ORDER_SAMPLE))
    print(f"{label}: after {t_after:.2f} s (fallback at {int(result.magnus_fallback.sum())} "
          f"of 3 speeds); before {sum(counts)} fourth-order steps, estimated "
          f"{t_sample * sum(counts) / FOURTH_ORDER_SAMPLE:.0f} s", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    logging.basicConfig(level=logging.ERROR)
    rayleigh6 = _built(periodic_model(load_scene(CASE3, RAYLEIGH), n_modes=6))
    _compare("1. Rayleigh, 6 modes, 1200 rev/min", rayleigh6, 1200.0, True)
    rayleigh14 = _built(periodic_model(load_scene(CASE3, RAYLEIGH), n_modes=14))
    _compare("2. Rayleigh, 14 modes, 1200 rev/min", rayleigh14, 1200.0, False)
    scene = _built(periodic_model(load_scene(CASE3), n_modes=6))
    _compare("3. zeta 0.01, 6 modes, 11.5 rev/min", scene, 11.5, not args.quick)
    _map("4a. map 11:12.5 rev/min, 3 speeds", scene, 11.0, 12.5, not args.quick)
    _map("4b. map 13:20 rev/min, 3 speeds", scene, 13.0, 20.0, not args.quick)
    scene14 = _built(periodic_model(load_scene(CASE3), n_modes=14))
    _map_estimated("4c. map 13:20 rev/min, 3 speeds, 14 modes", scene14, 13.0, 20.0)


if __name__ == "__main__":
    main()
