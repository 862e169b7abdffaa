"""A sensor plan (``studies.correlation.sensor_plan``) as JSON, text, a CSV and a UFF file of the
layout in the scene's [test] frame (with the target modes the model predicts there, so test
software and ``flexlink correlate`` read it as a pre-test), and a picture on the linkage."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from flexlink.output.figures import figure_png
from flexlink.studies.correlation.correlation import ModesAtPoints
from flexlink.studies.correlation.sensor_plan import Layout, SensorPlan, displacements
from flexlink.units import UNITS


def _number(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def _layout_json(layout: Layout, links) -> dict:
    return {"max_off_diagonal_auto_mac": _number(layout.max_auto_mac),
            "fisher_determinant": float(layout.fisher),
            "unseen_modes": [k + 1 for k in layout.unseen],
            "auto_mac": [[_number(v) for v in row] for row in layout.auto_mac],
            "sensors": [{"sensor": f"s{i + 1}", "link": links[int(k)], "fraction": float(f),
                         "x_mm": float(p[0] * 1e3), "y_mm": float(p[1] * 1e3),
                         "direction": d.tolist(), "kind": kind}
                        for i, (k, f, p, d, kind) in enumerate(zip(
                            layout.link, layout.fraction, layout.points, layout.directions,
                            layout.kinds))]}


def plan_json(plan: SensorPlan) -> dict:
    links = [l.name for l in plan.modes.solved[0].model.links]
    ratio = plan.chosen.fisher / plan.uniform.fisher if plan.uniform.fisher > 0 else None
    return {"scene": plan.scene.name, "file": plan.scene.path, "count": plan.count,
            "candidates": plan.candidates,
            "family": str(plan.scene.options.family),
            "elements_per_link": plan.modes.elements_per_link,
            "target_modes": [{"mode": k + 1, "Hz": float(f), "part": str(p), "label": label}
                             for k, (f, p, label) in enumerate(zip(
                                 plan.modes.frequencies, plan.modes.parts, plan.modes.labels))],
            "effective_independence": _layout_json(plan.chosen, links),
            "uniform": _layout_json(plan.uniform, links),
            "fisher_ratio": ratio}


def plan_text(document: dict) -> str:
    d = document
    modes = ", ".join(f"{m['mode']}) {m['Hz']:.1f} Hz {m['label']}" for m in d["target_modes"])
    lines = [f"{d['scene']} ({d['file']}): {d['count']} sensors for {len(d['target_modes'])} "
             f"modes ({modes}), Effective Independence over {d['candidates']} candidates",
             "sensor  link        at L   x mm     y mm     measures"]
    for s in d["effective_independence"]["sensors"]:
        lines.append(f"{s['sensor']:<7} {s['link']:<10} {s['fraction']:5.2f} {s['x_mm']:8.2f} "
                     f"{s['y_mm']:8.2f}  {s['kind']}")
    lines.append("layout                 max off-diagonal autoMAC   det Fisher information")
    for name, key in (("Effective Independence", "effective_independence"),
                      ("uniform", "uniform")):
        layout = d[key]
        auto_text = f"{layout['max_off_diagonal_auto_mac']:.3f}" + (
            " (mode " + ", ".join(map(str, layout["unseen_modes"])) + " unseen)"
            if layout["unseen_modes"] else "")
        lines.append(f"{name:<22} {auto_text:>26}   {layout['fisher_determinant']:.4g}")
    if d["fisher_ratio"] is not None:
        lines.append(f"Fisher information: Effective Independence / uniform = "
                     f"{d['fisher_ratio']:.4g}")
    return "\n".join(lines)


def _in_test_frame(plan: SensorPlan):
    """(unit, coordinates (N, 3) in it, directions (N, 3)) of the chosen channels in the
    frame of the scene's [test] table (its unit, else mm), so a test laid out by them reads
    back through that table."""
    frame = plan.scene.options.test
    unit = frame.unit or "mm"
    xy = frame.to_test(plan.chosen.points, UNITS["length"][unit])
    return (unit, np.column_stack([xy, np.zeros(len(xy))]),
            frame.direction_to_test(plan.chosen.directions))


def layout_shapes(plan: SensorPlan) -> ModesAtPoints:
    """The chosen channels' points 1..N in the test frame, each with the target modes' whole
    displacement there (X, Y, Z of the test frame): a UFF 55 dataset holds three directions
    per point, not one skewed one, so the UFF layout predicts what a triaxial sensor at each
    chosen point reads (the CSV keeps the chosen direction)."""
    unit, coordinates, _ = _in_test_frame(plan)
    whole = displacements(plan.modes, plan.chosen)  # (N, 3, M), scene frame
    frame = plan.scene.options.test
    values = np.stack([frame.direction_to_test(whole[:, :, k]) for k in range(whole.shape[2])],
                      axis=2)
    return ModesAtPoints(np.arange(1, plan.count + 1), coordinates, values,
                         plan.modes.frequencies, unit)


def layout_csv(plan: SensorPlan) -> str:
    """One row per chosen channel: sensor, position, direction (test frame), predicted mode
    shapes; the frequency row first (``studies.correlation.measured.read_csv`` reads it)."""
    unit, coordinates, directions = _in_test_frame(plan)
    k = len(plan.modes.frequencies)
    lines = [f"sensor,x [{unit}],y [{unit}],z [{unit}],dx,dy,dz,"
             + ",".join(f"mode {j + 1}" for j in range(k)),
             "frequency [Hz],,,,,,," + ",".join(f"{f:.9g}" for f in plan.modes.frequencies)]
    for i, (p, d, r) in enumerate(zip(coordinates, directions, plan.chosen.readings)):
        lines.append(f"s{i + 1}," + ",".join(f"{c:.9g}" for c in p) + ","
                     + ",".join(f"{c:.9g}" for c in d) + "," + ",".join(f"{v:.9g}" for v in r))
    return "\n".join(lines) + "\n"


def plan_picture(plan: SensorPlan) -> bytes:
    """PNG: the linkage, the chosen channels (arrows along their directions; a ring for z) and
    the uniform layout (hollow squares)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    model = plan.modes.solved[0].model
    size = float(np.ptp(model.nodes, axis=0).max())
    fig, ax = plt.subplots(figsize=(8, 5))
    for l in model.links:
        a, b = model.nodes[l.first_node], model.nodes[l.first_node + l.elements]
        ax.plot([a[0], b[0]], [a[1], b[1]], color="0.6", lw=2)
    u = plan.uniform.points
    ax.plot(u[:, 0], u[:, 1], "s", mfc="none", mec="tab:orange", ms=8, label="uniform")
    c, d = plan.chosen.points, plan.chosen.directions
    in_plane = np.hypot(d[:, 0], d[:, 1]) > 0
    ax.quiver(c[in_plane, 0], c[in_plane, 1], d[in_plane, 0], d[in_plane, 1], color="tab:blue",
              angles="xy", scale_units="xy", scale=1 / (0.06 * size), width=0.004,
              label="Effective Independence")
    ax.plot(c[~in_plane, 0], c[~in_plane, 1], "o", mfc="none", mec="tab:blue", ms=9)
    for i, p in enumerate(c):
        ax.annotate(f"s{i + 1}", p, textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_aspect("equal")
    ax.legend(fontsize=8)
    ax.set_title(f"{plan.scene.name}: {plan.count} sensors for {len(plan.modes.frequencies)} "
                 f"modes\n(rings: out-of-plane z)", fontsize=9)
    return figure_png(fig, 110)


def write_plan_files(folder: Path, plan: SensorPlan, geometry: int, pictures: bool
                     ) -> list[Path]:
    """sensors.csv, sensors.uff (datasets 164, 15 or 2411, 55 per target mode; both in the
    scene's [test] frame) and with ``pictures`` sensors.png, into ``folder``, atomically."""
    from flexlink.fileio import write_atomic
    from flexlink.output.correlation.measured import write_uff

    files = [write_atomic(folder / "sensors.csv", layout_csv(plan)),
             write_uff(folder / "sensors.uff", layout_shapes(plan),
                       f"flexlink sensor layout (predicted modes): {plan.scene.name}",
                       geometry=geometry)]
    if pictures:
        files.append(write_atomic(folder / "sensors.png", plan_picture(plan)))
    return files
