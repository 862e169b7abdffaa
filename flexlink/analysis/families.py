"""Model families a scene can choose (``[model] family = ...``), behind one function.

- "planar": the paper's model, in-plane frame elements (``analysis.analyze``); the default.
- "out-of-plane": weak-axis bending and St Venant torsion of the strips (``outofplane``).
- "3d": both; for a linkage lying in one plane with doubly symmetric sections the two sets of
  motions decouple to first order, so the 3D spectrum is the union of the two, sorted.
Measured frequencies are paired with the lowest elastic modes of the chosen family by mode
order only.
"""

from __future__ import annotations

import numpy as np

from flexlink.analysis.modal import analyze
from flexlink.analysis.outofplane import analyze_out_of_plane
from flexlink.scene import Scene

FAMILIES = ("planar", "out-of-plane", "3d")
IN_PLANE, OUT_OF_PLANE = "in-plane", "out-of-plane"


def scene_family(scene: Scene) -> str:
    return scene.options.family  # one of FAMILIES, checked by the scene schema


def elastic_modes(scene: Scene, n_modes: int, elements: int | None = None,
                  method: str = "auto") -> tuple[np.ndarray, tuple[str, ...]]:
    """The lowest ``n_modes`` elastic frequencies [Hz] of the scene's family (NaN where fewer
    were found) and, per mode, whether it is an in-plane or out-of-plane mode."""
    family = scene_family(scene)
    found: list[tuple[float, str]] = []
    if family in ("planar", "3d"):
        found += [(f, IN_PLANE) for f in analyze(scene, n_modes, elements, method)
                  .elastic_frequencies(n_modes)]
    if family in ("out-of-plane", "3d"):
        found += [(f, OUT_OF_PLANE) for f in
                  analyze_out_of_plane(scene, n_modes, elements, method).elastic_frequencies[:n_modes]]
    found.sort()
    freqs = np.full(n_modes, np.nan)
    kinds = [f for _, f in found[:n_modes]]
    freqs[:len(kinds)] = [f for f, _ in found[:n_modes]]
    return freqs, tuple(kinds)
