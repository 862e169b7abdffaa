"""What the crank-cycle pictures share: the atomic PNG writer for a pyplot figure and the axes
of a plot over one revolution of crank angle."""

from __future__ import annotations

import io
import math

import numpy as np

from flexlink.fileio import write_atomic


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


def figure_png(fig, dpi: int = 120) -> bytes:
    """A pyplot figure as PNG bytes; the figure is closed whatever happens."""
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, format="png", dpi=dpi)
    finally:
        plt.close(fig)
    return buffer.getvalue()


def write_figure(fig, path, dpi: int = 120) -> None:
    """Save a pyplot figure as PNG to ``path`` atomically (a drawing that fails half-way leaves
    the old picture) and close it."""
    write_atomic(path, figure_png(fig, dpi))
