"""The tracked map's renderings (``studies.cycle.tracking.TrackedMap``): its events, re-seeded poses,
unsampled dead centres and periodicity as JSON-ready values, its CSV and its PNG."""

from __future__ import annotations

import math

import numpy as np

from flexlink.output.figures import cycle_axes, write_figure
from flexlink.studies.cycle.tracking import TrackedMap
from flexlink.units import rev_per_min


def events_json(result: TrackedMap) -> list[dict]:
    """JSON-ready events: kind, lines (1-based), crank angle [deg], relative gap."""
    return [{"kind": e.kind, "lines": list(e.lines),
             "crank_deg": round(math.degrees(result.q[e.pose]) % 360.0, 3), "gap": e.gap}
            for e in result.tracks.events]


def reseeds_json(result: TrackedMap) -> list[dict]:
    """JSON-ready re-seeded poses: crank angle [deg], lines (1-based), reason."""
    return [{"crank_deg": round(math.degrees(result.q[r.pose]) % 360.0, 3),
             "lines": list(r.lines), "to_zero_Hz": list(r.vanishing), "reason": r.reason}
            for r in result.tracks.reseeds]


def unsampled_json(result: TrackedMap) -> list[float]:
    """Dead centres between the sampled poses, crank angles [deg]."""
    return [round(math.degrees(a), 3) for a in result.unsampled]


def periodicity_json(result: TrackedMap) -> dict | None:
    """JSON-ready periodicity check: closes, the end-to-start line pairing (1-based), its MAC,
    each line's relative frequency step from the last pose to the first, and the note."""
    p = result.periodicity
    if p is None:
        return None
    return {"closes": p.closes, "end_pairs_with_start_line": [b + 1 for b in p.permutation],
            "mac": [float(v) for v in p.mac], "relative_step": [float(v) for v in p.step],
            "note": p.note}


def tracking_lines(reseeds: list[dict], unsampled: str | None, periodicity: dict | None
                   ) -> list[str]:
    """Text lines on the tracking of a map from its JSON-ready ``reseeds`` (``reseeds_json``),
    unsampled dead-centre note and ``periodicity`` (``periodicity_json``)."""
    out = [f"re-seeded line{'s' if len(r['lines']) > 1 else ''} "
           f"{', '.join(map(str, r['lines']))} at crank {r['crank_deg']:.1f} deg: {r['reason']}"
           for r in reseeds]
    if unsampled:
        out.append(f"warning: {unsampled}")
    if periodicity:
        out.append(f"periodicity: {periodicity['note']}")
    return out


def tracked_csv(result: TrackedMap) -> str:
    """One row per pose: input angle [deg], tracked f1 ... fN [Hz], each line's MAC with the
    pose it was paired with, and the events at that pose ("crossing 1-2; veering 2-3;
    re-seeded 1 2 3: singular pose ...")."""
    n = result.frequencies.shape[1]
    at: dict[int, list[str]] = {}
    for e in result.tracks.events:
        at.setdefault(e.pose, []).append(f"{e.kind} {e.lines[0]}-{e.lines[1]}")
    for r in result.tracks.reseeds:  # the reason has commas: quoted below
        at.setdefault(r.pose, []).append(f"re-seeded {' '.join(map(str, r.lines))}: {r.reason}")
    lines = ["crank_angle_deg," + ",".join(f"f{j + 1}_Hz" for j in range(n)) + ","
             + ",".join(f"mac{j + 1}" for j in range(n)) + ",events"]
    for i, (q, row) in enumerate(zip(result.q, result.frequencies)):
        lines.append(f"{math.degrees(q):.6g}," + ",".join(f"{v:.8g}" for v in row) + ","
                     + ",".join(f"{v:.6f}" for v in result.tracks.mac[i]) + ","
                     + _csv_field("; ".join(at.get(i, []))))
    return "\n".join(lines) + "\n"


def _csv_field(text: str) -> str:
    return f'"{text.replace(chr(34), chr(34) * 2)}"' if any(c in text for c in ',"') else text


def plot_tracked(result: TrackedMap, path, crank_speed: float | None = None, hits=()) -> None:
    """PNG of the tracked lines against crank angle (as ``cycle_report.plot_map``), with each
    line's label, crossings marked x and veerings o, the poses where mu = 90 deg and the
    resonating harmonics (``hits``: ``cycle.Resonance``) as dashes. Written to ``path``
    atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.8))
    deg = np.degrees(result.q)
    f = result.frequencies
    for j in range(f.shape[1]):
        label = f"mode {j + 1}" + (f": {result.labels[j]}" if j < len(result.labels) else "")
        ax.plot(deg, f[:, j], label=label)
    for kind, marker in (("crossing", "x"), ("veering", "o")):
        events = [e for e in result.tracks.events if e.kind == kind]
        if events:
            x = [deg[e.pose] for e in events]
            y = [f[e.pose, [e.lines[0] - 1, e.lines[1] - 1]].mean() for e in events]
            ax.scatter(x, y, marker=marker, s=60, color="k", facecolors="none" if marker == "o"
                       else None, zorder=3, label=kind)
    cycle_axes(ax, deg, result.mu90, hits, result.scene + " (modes tracked by MAC)" + (
        f", crank {rev_per_min(crank_speed):g} rev/min" if crank_speed else ""))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    write_figure(fig, path)
