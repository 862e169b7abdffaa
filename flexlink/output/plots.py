"""Frequency comparison plot with matplotlib: per case, computed vs the reference columns
(measured Ex, the paper's FE) as points on a log axis (a bar on a log axis has no
meaningful base), each computed bar annotated with
its % error against every reference. Returns PNG bytes; the caller writes them."""

from __future__ import annotations

import io

import numpy as np

COLOURS = {"computed": "#1f77b4", "FE": "#ff7f0e", "Ex": "#2ca02c"}
LABELS = {"computed": "computed (flexlink)", "FE": "paper FE", "Ex": "measured (Ex)"}


def frequency_plot(summary: dict, size: tuple[float, float] = (8.0, 5.0), dpi: int = 120) -> bytes:
    """PNG of one case's ``report.case_summary``: a point per mode and series, log frequency
    axis.

    ``size`` [in] and ``dpi`` give the picture size in pixels (size * dpi)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    rows = summary["modes"]
    refs = [k[:-3] for k in (rows[0] if rows else {}) if k.endswith("_Hz") and k != "computed_Hz"]
    series = ["computed"] + refs
    modes = np.array([r["mode"] for r in rows])
    width = 0.8 / len(series)
    fig = Figure(figsize=size, dpi=dpi, layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    for j, name in enumerate(series):
        values = np.array([r.get(f"{name}_Hz", np.nan) for r in rows], dtype=float)
        ax.plot(modes + (j - (len(series) - 1) / 2) * width, values, ls="none",
                marker="os^Dv"[j % 5], markersize=7, color=COLOURS.get(name, f"C{j}"),
                label=LABELS.get(name, name))
    top = max(r["computed_Hz"] for r in rows) if rows else 1.0
    for r, x in zip(rows, modes - (len(series) - 1) / 2 * width):
        notes = [f"{r[f'error_vs_{ref}_pct']:+.0f} % vs {ref}" for ref in refs
                 if f"error_vs_{ref}_pct" in r]
        if notes:
            ax.annotate("\n".join(notes), (x, r["computed_Hz"]), xytext=(0, 4),
                        textcoords="offset points", ha="center", va="bottom", fontsize=8)
    ax.set_yscale("log")
    lows = [r[k] for r in rows for k in r if k.endswith("_Hz") and r[k] > 0]
    ax.set_ylim(min(lows, default=1.0) / 2, top * 4)
    ax.set_xticks(modes, [f"mode {m}" for m in modes])
    ax.set_ylabel("natural frequency [Hz]")
    pose = summary["pose"]
    angle = "" if pose["mu_deg"] is None else f"\u03bc = {pose['mu_deg']:.1f} deg, "
    ax.set_title(f"{summary['scene']}: {angle}{summary['elements_per_link']} elements/link")
    ax.grid(axis="y", which="both", alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()
