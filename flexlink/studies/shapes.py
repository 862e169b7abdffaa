"""Two scenes or meshes compared mode by mode: the MAC matrix of their lowest elastic modes
at their poses and the pairing it gives (``analysis.mac``)."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.identity import mode_identity
from flexlink.analysis.mac import STATIONS, compare_models, pair_modes
from flexlink.analysis.modal import CaseResult, analyze
from flexlink.scene import Scene


@dataclasses.dataclass(frozen=True)
class ShapeComparison:
    """mac[i, j]: MAC of mode i of ``a`` with mode j of ``b`` (elastic modes, lowest first);
    pairs: (i, j, MAC) of the best one-to-one pairing."""

    a: CaseResult
    b: CaseResult
    mac: np.ndarray
    pairs: tuple[tuple[int, int, float], ...]


def _elastic(result: CaseResult, n: int) -> np.ndarray:
    return result.modes.shapes[:, result.modes.elastic[:n]]


def compare_scenes(scene_a: Scene, scene_b: Scene, n_modes: int, elements_a: int | None,
                   elements_b: int | None, per_link: int = STATIONS) -> ShapeComparison:
    """The lowest ``n_modes`` in-plane elastic modes of both scenes at their poses, compared at
    ``per_link`` + 1 stations along each link (the scenes must name the same links)."""
    a = analyze(scene_a, n_modes, elements_a)
    b = analyze(scene_b, n_modes, elements_b)
    mac = compare_models(a.model, _elastic(a, n_modes), b.model, _elastic(b, n_modes), per_link)
    p = pair_modes(mac)
    return ShapeComparison(a, b, mac, tuple((int(i), int(j), float(m))
                                            for i, j, m in zip(p.a, p.b, p.mac)))


def comparison_json(c: ShapeComparison, n_modes: int) -> dict:
    """JSON-ready: each side's frequencies [Hz] and labels, the MAC matrix and the pairs
    (1-based modes) with their frequency difference [%] (b vs a)."""
    sides = {}
    for name, r in (("a", c.a), ("b", c.b)):
        freqs = r.elastic_frequencies(n_modes)
        labels = [d["label"] for d in mode_identity(r.model, _elastic(r, n_modes))]
        sides[name] = {"scene": r.scene.name, "file": r.scene.path,
                       "elements_per_link": r.elements_per_link,
                       "modes": [{"mode": i + 1, "Hz": float(f), "label": l}
                                 for i, (f, l) in enumerate(zip(freqs, labels))]}
    fa, fb = c.a.elastic_frequencies(n_modes), c.b.elastic_frequencies(n_modes)
    return {**sides, "mac": c.mac.tolist(),
            "pairs": [{"a": i + 1, "b": j + 1, "mac": m,
                       "difference_pct": 100.0 * (fb[j] - fa[i]) / fa[i]}
                      for i, j, m in c.pairs]}


def mac_csv(c: ShapeComparison) -> str:
    """The MAC matrix: rows the modes of a, columns those of b."""
    n_b = c.mac.shape[1]
    lines = ["mode_a," + ",".join(f"b{j + 1}" for j in range(n_b))]
    lines += [f"{i + 1}," + ",".join(f"{v:.6f}" for v in row) for i, row in enumerate(c.mac)]
    return "\n".join(lines) + "\n"
