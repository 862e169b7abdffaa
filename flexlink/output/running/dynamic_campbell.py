"""Rendering of the speed-dependent Campbell diagram (``studies.running.dynamic_campbell``): JSON, CSV,
text lines and the plot of each mode's band at each speed against the crank harmonics, beside
the frozen-pose bands."""

from __future__ import annotations

import math

import numpy as np

from flexlink.studies.running.dynamic_campbell import (CriticalShift, Divergence, DynamicCampbell,
                                               frozen_bands)
from flexlink.studies.running.modes_at_speed import ASSUMPTIONS
from flexlink.studies.cycle.tracking import PAIR_MAC
from flexlink.units import rev_per_min


def _rpm(pair):
    return None if pair is None else [rev_per_min(pair[0]), rev_per_min(pair[1])]


def shift_json(shift: CriticalShift, ends: tuple[float, float]) -> dict:
    """One critical range, frozen and at speed [rev/min], and how far each edge moved; an edge
    both ranges take from the speed range's ``ends`` [rad/s] did not move, it is cut (None)."""
    moved = None
    if shift.frozen and shift.dynamic:
        moved = {edge: None if f == d and f in ends else
                 {"rev_per_min": rev_per_min(d - f), "percent": 100 * (d - f) / f if f else None}
                 for edge, f, d in zip(("from", "to"), shift.frozen, shift.dynamic)}
    return {"mode": shift.mode, "harmonic": shift.harmonic,
            "frozen_rev_per_min": _rpm(shift.frozen), "at_speed_rev_per_min": _rpm(shift.dynamic),
            "moved": moved}


def dynamic_json(result: DynamicCampbell, shifts: list[CriticalShift]) -> dict:
    """JSON-ready: the bands at every speed [Hz], the frozen bands, the critical ranges side by
    side, the divergence if any, and the model's assumptions."""
    low, high = result.bands()
    return {
        "assumptions": list(ASSUMPTIONS) + [
            "constant crank speed" if not result.crank_acceleration else
            "the same crank acceleration at every speed and pose (not a run-up)"],
        "basis_static_modes": result.basis,
        "crank_acceleration_rad_s2": result.crank_acceleration,
        "frozen_bands": [{"mode": b.mode, "min_Hz": b.low, "max_Hz": b.high}
                         for b in frozen_bands(result)],
        "bands_at_speed": [{"rev_per_min": rev_per_min(w),
                            "min_Hz": None if not np.isfinite(lo).all() else lo.tolist(),
                            "max_Hz": None if not np.isfinite(hi).all() else hi.tolist()}
                           for w, lo, hi in zip(result.speeds, low, high)],
        "divergence": divergence_json(result.divergence),
        "ambiguous_speed_steps": result.ambiguous,
        "critical_speeds": [shift_json(s, _ends(result)) for s in shifts],
        "critical_speeds_compared_rev_per_min": [rev_per_min(e) for e in _ends(result)],
    }


def divergence_json(d: Divergence | None) -> dict | None:
    """The divergence [rev/min, deg, 1/s], or None."""
    if d is None:
        return None
    return {"rev_per_min": None if d.speed is None else rev_per_min(d.speed),
            "crank_deg": math.degrees(d.q) % 360.0, "line": d.line,
            "grid_rev_per_min": rev_per_min(d.grid_speed), "growth_rate_per_s": d.growth_rate}


def divergence_line(d: Divergence) -> str:
    """One sentence: which line diverges, where, and how fast it grows past it."""
    who = f"mode {d.line}" if d.line else "a mode above the tracked lines"
    at = "" if d.speed is None else f" at {rev_per_min(d.speed):.1f} rev/min"
    return (f"divergence: {who} falls to 0 Hz{at} (crank angle {math.degrees(d.q) % 360:.1f} "
            f"deg) and grows past it (real root +{d.growth_rate:.4g} 1/s at "
            f"{rev_per_min(d.grid_speed):.1f} rev/min): no band from {rev_per_min(d.grid_speed):.1f} rev/min on")


def dynamic_csv(result: DynamicCampbell) -> str:
    """One row per speed: speed [rev/min], each mode's band min and max [Hz] (empty past a
    divergence)."""
    low, high = result.bands()
    n = low.shape[1]
    rows = ["rev_per_min," + ",".join(f"mode{j + 1}_min_Hz,mode{j + 1}_max_Hz" for j in range(n))]
    for w, lo, hi in zip(result.speeds, low, high):
        cells = [f"{v:.8g}" if np.isfinite(v) else "" for pair in zip(lo, hi) for v in pair]
        rows.append(f"{rev_per_min(w):.6g}," + ",".join(cells))
    return "\n".join(rows) + "\n"


def dynamic_lines(result: DynamicCampbell, shifts: list[CriticalShift]) -> list[str]:
    """The text summary: the model, the divergence, and each critical range frozen against at
    speed with the moves of its edges."""
    out = ["at speed: operating-point modes (inertia preload, centrifugal, Coriolis) at every "
           f"pose, reduced onto {result.basis} static modes per pose"
           + (f", crank acceleration {result.crank_acceleration:.6g} rad/s^2 at every speed"
              if result.crank_acceleration else "") + "; " + "; ".join(ASSUMPTIONS)]
    if result.divergence is not None:
        out.append(divergence_line(result.divergence))
    if result.ambiguous:
        out.append(f"{result.ambiguous} speed step(s) of a line paired with MAC below "
                   f"{PAIR_MAC} (shapes that change fast between grid speeds, near a "
                   "divergence or a veering): more --speed-steps resolve them")
    if not shifts:
        out.append("no critical speed in the range, frozen or at speed")
        return out
    low, high = _ends(result)
    if high < result.speeds[-1]:
        out.append(f"critical ranges compared from {rev_per_min(low):.6g} to "
                   f"{rev_per_min(high):.6g} rev/min, the last speed of the grid before the "
                   "divergence: a range there is cut ('range end'), and the frozen ranges "
                   "above it are only in the frozen table")
    out.append(f"{'mode':>4} {'harm.':>5} {'frozen [rev/min]':>17} {'at speed [rev/min]':>19} "
               f"{'moved from / to':>20}")
    for s in shifts:
        j = shift_json(s, _ends(result))
        frozen = "-" if s.frozen is None else "{:.1f}-{:.1f}".format(*j["frozen_rev_per_min"])
        dyn = "-" if s.dynamic is None else "{:.1f}-{:.1f}".format(*j["at_speed_rev_per_min"])
        moved = "new at speed" if s.frozen is None else "gone at speed"
        if j["moved"]:
            moved = " / ".join("range end" if j["moved"][e] is None else
                               _percent(j["moved"][e]["percent"]) for e in ("from", "to"))
        out.append(f"{s.mode:>4} {s.harmonic:>5} {frozen:>17} {dyn:>19} {moved:>20}")
    return out


def _ends(result: DynamicCampbell) -> tuple[float, float]:
    """The speeds [rad/s] the critical ranges are cut to: the grid's, below any divergence."""
    return float(result.speeds[0]), float(result.speeds[max(result.stable_speeds, 1) - 1])


def _percent(value) -> str:
    return "-" if value is None else f"{value:+.2f} %"


def plot_dynamic(result: DynamicCampbell, margin: float, harmonics: int, path,
                 title: str = "") -> None:
    """PNG: each mode's band at each speed (filled between min and max over the cycle) and the
    frozen-pose band (dashed edges), against crank speed [rev/min], with the harmonic lines."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rpm = rev_per_min(result.speeds)
    low, high = result.bands()
    fig, ax = plt.subplots(figsize=(8, 5))
    frozen = frozen_bands(result)
    top = 1.1 * max(np.nanmax(high), max(b.high for b in frozen)) * (1 + margin)
    for j, band in enumerate(frozen):
        colour = f"C{j}"
        ax.fill_between(rpm, low[:, j], high[:, j], color=colour, alpha=0.45, lw=0,
                        label=f"mode {j + 1} at speed")
        for edge in (band.low, band.high):
            ax.axhline(edge, color=colour, ls="--", lw=0.8)
    for n in range(1, harmonics + 1):
        ax.plot(rpm, n * rpm / 60.0, color="0.3", lw=0.8)
        if n * rpm[-1] / 60.0 <= top:
            ax.annotate(f"{n}x", (rpm[-1], n * rpm[-1] / 60.0), fontsize=7, ha="right",
                        va="bottom")
    if result.divergence is not None:
        d = result.divergence
        ax.axvline(rev_per_min(d.speed or d.grid_speed), color="red", lw=1.2,
                   label=f"divergence{f' (mode {d.line})' if d.line else ''}")
    ax.set_xlim(rpm[0], rpm[-1])
    ax.set_ylim(0, top)
    ax.set_xlabel("crank speed [rev/min]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(title + " at speed (dashed: frozen-pose bands)")
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
