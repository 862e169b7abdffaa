"""The MAC comparison of two scenes' modes (``studies.pose.mac_comparison``) as JSON, CSV and text."""

from __future__ import annotations

from flexlink.studies.pose.mac_comparison import ShapeComparison
from flexlink.units import percent_error


def comparison_json(c: ShapeComparison, n_modes: int) -> dict:
    """JSON-ready: the part compared, each side's frequencies [Hz] and labels, the MAC matrix and the
    pairs (1-based modes) with their frequency difference [%] (b vs a)."""
    sides = {}
    for name, s in (("a", c.a), ("b", c.b)):
        sides[name] = {"scene": s.scene.name, "file": s.scene.path,
                       "elements_per_link": s.elements_per_link,
                       "modes": [{"mode": i + 1, "Hz": float(f), "label": l}
                                 for i, (f, l) in enumerate(zip(s.frequencies, s.labels))]}
    fa, fb = c.a.frequencies, c.b.frequencies
    return {"part": c.part, **sides, "mac": c.mac.tolist(),
            "pairs": [{"a": i + 1, "b": j + 1, "mac": m,
                       "difference_pct": percent_error(fb[j], fa[i])}
                      for i, j, m in c.pairs]}


def mac_csv(c: ShapeComparison) -> str:
    """The MAC matrix: rows the modes of a, columns those of b."""
    n_b = c.mac.shape[1]
    lines = ["mode_a," + ",".join(f"b{j + 1}" for j in range(n_b))]
    lines += [f"{i + 1}," + ",".join(f"{v:.6f}" for v in row) for i, row in enumerate(c.mac)]
    return "\n".join(lines) + "\n"


def mac_text(document: dict, mac) -> str:
    """The human-readable report: each side's modes, the MAC matrix (rows: A, columns: B) and
    the pairs with their frequency difference."""
    lines = [f"{document['part']} modes"]
    for side in ("a", "b"):
        s = document[side]
        lines.append(f"{side.upper()}: {s['scene']} ({s['file']}), {s['elements_per_link']} "
                     "elements/link: " + ", ".join(f"{m['mode']}) {m['Hz']:.2f} Hz {m['label']}"
                                                  for m in s["modes"]))
    lines.append("MAC  " + "".join(f"{'B' + str(j + 1):>7}" for j in range(mac.shape[1])))
    for i, row in enumerate(mac):
        lines.append(f"A{i + 1:<4}" + "".join(f"{v:>7.3f}" for v in row))
    lines.append("pairs:")
    for p in document["pairs"]:
        lines.append(f"  A{p['a']} - B{p['b']}: MAC {p['mac']:.3f}, frequency "
                     f"{p['difference_pct']:+.2f} %")
    return "\n".join(lines)
