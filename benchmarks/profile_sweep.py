"""Where a sweep's time goes: pyinstrument over 360 poses of case 2 (8 elements/link, 6 modes).

Run: bash benchmarks/run.sh sets up pyinstrument; then
    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/profile_sweep.py [elements] [craig-bampton]
(``craig-bampton``: the reduced sweep, ``modal_sweep(..., reduction="craig-bampton")``).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from pyinstrument import Profiler  # noqa: E402

from flexlink.scene import load_scene  # noqa: E402
from flexlink.analysis.sweep import Reduction, modal_sweep  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def main():
    elements = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    reduction = sys.argv[2] if len(sys.argv) > 2 else None
    if reduction is not None and reduction not in tuple(Reduction):
        sys.exit(f"reduction: one of {', '.join(Reduction)} or nothing")
    scene = load_scene(ROOT / "cases" / "case2.toml")
    topology = scene.topology(elements)
    poses = [scene.rigid_pose(t).joints for t in np.radians(np.arange(360) + 0.5)]
    modal_sweep(topology, poses[:2], 6, reduction=reduction)  # imports, caches out of the picture
    profiler = Profiler(interval=0.0002)
    profiler.start()
    modal_sweep(topology, poses, 6, reduction=reduction)
    profiler.stop()
    print(profiler.output_text(unicode=False, color=False, show_all=False))


if __name__ == "__main__":
    main()
