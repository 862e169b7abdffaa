"""The Campbell diagram's renderings (``studies.campbell``): bands, critical speeds and the
nearest margin as JSON-ready values, the CSV of critical ranges and the PNG diagram."""

from __future__ import annotations

import numpy as np

from flexlink.output.figures import write_figure
from flexlink.studies.campbell import RPM, Band, CriticalSpeed, NearestMargin


def campbell_json(found: list[Band], critical: list[CriticalSpeed],
                  nearest: NearestMargin | None, labels=None) -> dict:
    """JSON-ready bands [Hz], ``critical_speeds`` [rev/min] and the nearest margin."""
    labels = labels or {}
    return {
        "bands": [{"mode": b.mode, "label": labels.get(b.mode), "min_Hz": b.low,
                   "max_Hz": b.high} for b in found],
        "critical_speeds": [{"mode": c.mode, "harmonic": c.harmonic,
                             "from_rev_per_min": c.low / RPM, "to_rev_per_min": c.high / RPM}
                            for c in critical],
        "nearest_margin": None if nearest is None else {
            "mode": nearest.mode, "harmonic": nearest.harmonic, "relative_gap": nearest.gap,
            "at_rev_per_min": nearest.speed / RPM},
    }


def critical_csv(critical: list[CriticalSpeed], found: list[Band]) -> str:
    """One row per critical range: mode, its band [Hz], harmonic, speed range [rev/min]."""
    by_mode = {b.mode: b for b in found}
    lines = ["mode,band_min_Hz,band_max_Hz,harmonic,from_rev_per_min,to_rev_per_min"]
    for c in critical:
        b = by_mode[c.mode]
        lines.append(f"{c.mode},{b.low:.8g},{b.high:.8g},{c.harmonic},{c.low / RPM:.6g},"
                     f"{c.high / RPM:.6g}")
    return "\n".join(lines) + "\n"


def plot_campbell(found: list[Band], speeds: tuple[float, float], margin: float,
                  harmonics: int, critical: list[CriticalSpeed], path, title: str = "",
                  labels=None) -> None:
    """PNG: bands (and their margin bands, lighter) against crank speed [rev/min], harmonic
    lines n x speed, and the critical speed ranges shaded along the speed axis. Written to
    ``path`` atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = labels or {}
    low, high = speeds[0] / RPM, speeds[1] / RPM
    fig, ax = plt.subplots(figsize=(8, 5))
    top = max(b.high for b in found) * (1 + margin) * 1.1
    for b in found:
        colour = f"C{b.mode - 1}"
        ax.axhspan(b.low * (1 - margin), b.high * (1 + margin), color=colour, alpha=0.12, lw=0)
        ax.axhspan(b.low, b.high, color=colour, alpha=0.45, lw=0,
                   label=f"mode {b.mode}" + (f": {labels[b.mode]}" if labels.get(b.mode) else ""))
    rpm = np.array([low, high])
    for n in range(1, harmonics + 1):
        f = n * rpm / 60.0
        ax.plot(rpm, f, color="0.3", lw=0.8)
        if f[-1] <= top:
            ax.annotate(f"{n}x", (rpm[-1], f[-1]), fontsize=7, ha="right", va="bottom")
        else:
            ax.annotate(f"{n}x", (60.0 * top / n, top), fontsize=7, ha="right", va="top")
    for c in critical:
        ax.axvspan(c.low / RPM, c.high / RPM, color="red", alpha=0.08, lw=0)
    ax.set_xlim(low, high)
    ax.set_ylim(0, top)
    ax.set_xlabel("crank speed [rev/min]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(title + f" (margin {100 * margin:g} %)")
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    write_figure(fig, path)
