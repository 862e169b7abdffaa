"""The cycle map's files: the CSV of frequencies over the crank angle and the PNG of the map
(``studies.cycle.ModalMap``), and the axes every cycle plot shares."""

from __future__ import annotations

import io
import math

import numpy as np

from flexlink.fileio import write_atomic
from flexlink.studies.cycle import ModalMap, Resonance


def modal_map_csv(result: ModalMap) -> str:
    """One row per pose: input angle [deg], then f1 ... fN [Hz]."""
    n = result.frequencies.shape[1]
    lines = ["crank_angle_deg," + ",".join(f"f{j + 1}_Hz" for j in range(n))]
    for q, row in zip(result.q, result.frequencies):
        lines.append(f"{math.degrees(q):.6g}," + ",".join(f"{v:.8g}" for v in row))
    return "\n".join(lines) + "\n"


def cycle_axes(ax, deg: np.ndarray, mu90: dict, hits, title: str) -> None:
    """What every cycle plot shows besides its lines: the mu = 90 deg poses (vertical), the
    resonating harmonics (horizontal, red), one revolution of crank angle [deg], the title and
    the legend."""
    for k, (pair, angles) in enumerate(mu90.items()):
        for i, a in enumerate(angles):
            ax.axvline(math.degrees(a), color="0.4", ls=":" if k else "--", lw=1,
                       label=f"mu = 90 deg ({pair})" if i == 0 else None)
    for f in sorted({h.frequency for h in hits}):
        ax.axhline(f, color="red", ls="-.", lw=0.8)
    ax.set_xlabel("crank angle [deg]")
    ax.set_ylabel("natural frequency [Hz]")
    ax.set_xlim(deg[0], deg[0] + 360)
    ax.set_title(title)
    ax.legend(fontsize=8)


def write_figure(fig, path, dpi: int = 120) -> None:
    """Save a pyplot figure as PNG to ``path`` atomically (a drawing that fails half-way leaves
    the old picture) and close it."""
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, format="png", dpi=dpi)
    finally:
        plt.close(fig)
    write_atomic(path, buffer.getvalue())


def plot_map(result: ModalMap, path, crank_speed: float | None = None,
             hits: list[Resonance] = ()) -> None:
    """PNG of frequency against input angle, one line per mode; vertical lines mark the poses
    where mu = 90 deg; crank harmonics that resonate are drawn as horizontal dashes. Written to
    ``path`` atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.8))
    deg = np.degrees(result.q)
    for j in range(result.frequencies.shape[1]):
        ax.plot(deg, result.frequencies[:, j], label=f"mode {j + 1}")
    cycle_axes(ax, deg, result.mu90, hits, result.scene + (
        f" (crank {crank_speed * 60 / (2 * math.pi):g} rev/min)" if crank_speed else ""))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    write_figure(fig, path)
