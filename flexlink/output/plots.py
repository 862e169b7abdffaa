"""Frequency comparison plot with matplotlib: per case, computed vs the reference columns
(measured Ex, the paper's FE) as points on a log axis (a bar on a log axis has no
meaningful base), each computed bar annotated with
its % error against every reference. Returns PNG bytes; the caller writes them."""

from __future__ import annotations

import io
import math

import numpy as np

from flexlink.studies.pose.scene_summary import SceneSummary

COLOURS = {"computed": "#1f77b4", "FE": "#ff7f0e", "Ex": "#2ca02c"}
LABELS = {"computed": "computed (flexlink)", "FE": "paper FE", "Ex": "measured (Ex)"}


def frequency_plot(summary: SceneSummary, size: tuple[float, float] = (8.0, 5.0),
                   dpi: int = 120) -> bytes:
    """PNG of one scene's summary (``studies.pose.scene_summary``): a point per mode and series, log
    frequency axis.

    ``size`` [in] and ``dpi`` give the picture size in pixels (size * dpi)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    computed = summary.frequencies
    refs = [name for name, values in summary.reference.items() if len(values)]
    series = {"computed": computed}
    for name in refs:
        values = np.full(len(computed), np.nan)
        values[:len(summary.reference[name])] = summary.reference[name]
        series[name] = values
    modes = np.arange(1, len(computed) + 1)
    width = 0.8 / len(series)
    fig = Figure(figsize=size, dpi=dpi, layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    for j, (name, values) in enumerate(series.items()):
        ax.plot(modes + (j - (len(series) - 1) / 2) * width, values, ls="none",
                marker="os^Dv"[j % 5], markersize=7, color=COLOURS.get(name, f"C{j}"),
                label=LABELS.get(name, name))
    top = float(max(computed)) if len(computed) else 1.0
    for i, x in enumerate(modes - (len(series) - 1) / 2 * width):
        notes = [f"{summary.errors[ref][i]:+.0f} % vs {ref}" for ref in refs
                 if i < len(summary.errors[ref])]
        if notes:
            ax.annotate("\n".join(notes), (x, computed[i]), xytext=(0, 4),
                        textcoords="offset points", ha="center", va="bottom", fontsize=8)
    ax.set_yscale("log")
    lows = [v for values in series.values() for v in values if v > 0]
    ax.set_ylim(min(lows, default=1.0) / 2, top * 4)
    ax.set_xticks(modes, [f"mode {m}" for m in modes])
    ax.set_ylabel("natural frequency [Hz]")
    mu = summary.case.pose.mu
    angle = "" if mu is None else f"\u03bc = {math.degrees(mu):.1f} deg, "
    ax.set_title(f"{summary.case.scene.name}: {angle}{summary.case.elements_per_link} "
                 "elements/link")
    ax.grid(axis="y", which="both", alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()
