"""The batched Taylor exponential (``analysis.floquet.exponentials``) against
``scipy.linalg.expm`` on the same stacks: the step exponentials the stability map forms on
Table II case 1 (6 modes, 37 poses), by its adiabatic steps and by its Magnus steps.

    PYTHONPATH=. python benchmarks/exponentials.py [--repeats N]

The stacks are recorded as the verdict at each speed passes them (a copy of each, contiguous),
then each is exponentiated by both, best CPU time of the repeats with BLAS on one thread
(scipy.linalg.expm takes the stack whole, (m, n, n); it is also timed called once per matrix,
as a loop over the steps would). Printed per stack: its shape, the times, the ratios, and the
largest difference per matrix relative to scipy's 1-norm. The hand-written kernel is kept only
while it wins: the last lines say by how much, per integrator.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import time  # noqa: E402
import timeit  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import scipy.linalg as sla  # noqa: E402

from flexlink.analysis import adiabatic, floquet  # noqa: E402
from flexlink.scene import load_scene  # noqa: E402
from flexlink.analysis.periodic import (  # noqa: E402
    Integrator,
    periodic_model,
    speed_multipliers,
)
from flexlink.units import RPM  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SPEEDS = (300.0, 1500.0, 3000.0)  # rev/min
AGREEMENT = 1e-12  # of each exponential's 1-norm


def _recorded_stacks(model) -> list[tuple[str, np.ndarray]]:
    """(label, stack) of every call of the exponential while the verdict runs at SPEEDS by
    both integrators."""
    stacks = []
    kernel = floquet.exponentials

    def recording(label):
        def exponentials(omega):
            stacks.append((label, np.array(omega)))
            return kernel(omega)
        return exponentials

    try:
        for integrator, module in ((Integrator.ADIABATIC, adiabatic), (Integrator.MAGNUS, floquet)):
            for rpm in SPEEDS:
                module.exponentials = recording(f"{integrator.value} {rpm:g} rev/min")
                speed_multipliers(model, rpm * RPM, integrator=integrator)
    finally:
        adiabatic.exponentials = floquet.exponentials = kernel
    return stacks


def _best(repeats, work) -> float:
    """The best CPU time [s] of ``repeats`` calls of work()."""
    return min(timeit.repeat(work, timer=time.process_time, repeat=repeats, number=1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=5)
    repeats = parser.parse_args().repeats
    model = periodic_model(load_scene(ROOT / "cases/case1.toml"), n_modes=6)
    stacks = _recorded_stacks(model)
    # the largest stack of each label: the others are the same sizes or the remainder chunk
    largest = {}
    for label, stack in stacks:
        if label not in largest or stack.shape[0] > largest[label].shape[0]:
            largest[label] = stack
    ratios, worst = {}, 0.0
    for label, stack in largest.items():
        mine, reference = floquet.exponentials(stack), sla.expm(stack)
        ours = _best(repeats, lambda s=stack: floquet.exponentials(s))
        theirs = _best(repeats, lambda s=stack: sla.expm(s))
        looped = _best(repeats, lambda s=stack: [sla.expm(a) for a in s])
        size = np.abs(reference).sum(axis=-2).max(axis=-1)  # 1-norm per matrix
        difference = (np.abs(mine - reference).sum(axis=-2).max(axis=-1) / size).max()
        worst = max(worst, difference)
        ratios.setdefault(label.split()[0], []).append((theirs / ours, looped / ours))
        print(f"{label}: stack {stack.shape[0]} x {stack.shape[1]} x {stack.shape[2]} "
              f"({sum(1 for lb, _ in stacks if lb == label)} calls): Taylor {ours * 1e3:.2f} ms; "
              f"scipy.linalg.expm on the stack {theirs * 1e3:.2f} ms ({theirs / ours:.1f}x), "
              f"per matrix {looped * 1e3:.2f} ms ({looped / ours:.1f}x); largest difference "
              f"{difference:.1e} of the 1-norm")
    for kind, pairs in ratios.items():
        whole, single = np.array(pairs).T
        print(f"{kind} steps: the batched Taylor exponential {whole.min():.1f}x to "
              f"{whole.max():.1f}x as fast as scipy.linalg.expm on the stack, {single.min():.1f}x "
              f"to {single.max():.1f}x as fast as expm per matrix")
    print(f"agreement with scipy.linalg.expm to {AGREEMENT:g} of the 1-norm: "
          f"{'MET' if worst <= AGREEMENT else 'NOT MET'} ({worst:.1e})")

if __name__ == "__main__":
    main()
