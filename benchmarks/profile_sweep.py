"""Where a sweep's time goes: pyinstrument over 360 poses of case 2 (8 elements/link, 6 modes).

Run: bash benchmarks/run.sh sets up pyinstrument; then
    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/profile_sweep.py [elements]
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from pyinstrument import Profiler  # noqa: E402

from flexlink.scene import load_scene  # noqa: E402
from flexlink.analysis.sweep import modal_sweep  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def main():
    elements = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    scene = load_scene(ROOT / "cases" / "case2.toml")
    topology = scene.topology(elements)
    poses = [scene.linkage.pose(t, "open").joints for t in np.radians(np.arange(360) + 0.5)]
    modal_sweep(topology, poses[:2], 6)  # imports and caches out of the picture
    profiler = Profiler(interval=0.0002)
    profiler.start()
    modal_sweep(topology, poses, 6)
    profiler.stop()
    print(profiler.output_text(unicode=False, color=False, show_all=False))


if __name__ == "__main__":
    main()
