"""Rendering of ``studies.kinetostatics.parametric.ParametricStudy``: CSV, JSON, text and the
plot of each ratio's median against each factor."""

from __future__ import annotations

import io
import math

from flexlink.studies.kinetostatics.parametric import UNITS


def _n(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


def parametric_csv(study) -> str:
    """factor, level, unit, then the median |ratio| of each ratio (empty where undefined)."""
    names = list(study.base)
    lines = [",".join(["factor", "level", "unit"] + [f"median |{n}|" for n in names])]
    for sweep in study.sweeps:
        for i, level in enumerate(sweep.levels):
            values = [sweep.medians[n][i] for n in names]
            lines.append(",".join([sweep.factor.value, f"{level:g}", UNITS[sweep.factor]]
                                  + [f"{v:.10g}" if math.isfinite(v) else "" for v in values]))
    return "\n".join(lines) + "\n"


def parametric_document(study) -> dict:
    return {
        "base": {"crank_speed_rev_per_min": study.base_speed_rpm,
                 "input_torque_N_m": study.base_torque, "friction_m": study.base_friction,
                 "efficiency_eta": study.efficiency,
                 "median_abs_ratios": {k: _n(v) for k, v in study.base.items()}},
        "matters_above_percent": study.matters_percent,
        "factors": [{"factor": s.factor.value, "unit": UNITS[s.factor],
                     "levels": s.levels.tolist(),
                     "median_abs_ratios": {k: [_n(v) for v in m] for k, m in s.medians.items()},
                     "effect_percent": {k: _n(v) for k, v in s.effect.items()},
                     "matters": {k: bool(math.isfinite(v) and v >= study.matters_percent)
                                 for k, v in s.effect.items()}}
                    for s in study.sweeps]}


def parametric_text(doc: dict) -> str:
    b = doc["base"]
    lines = [(f"  parametric study about {b['input_torque_N_m']:.6g} N m, "
              f"{b['crank_speed_rev_per_min']:.6g} rev/min, m = {b['friction_m']:g}, eta = "
              f"{b['efficiency_eta']:g}: effect = spread of the median |ratio| over the factor's "
              f"range / its base value (matters from {doc['matters_above_percent']:g} %)")]
    for f in doc["factors"]:
        lo, hi = f["levels"][0], f["levels"][-1]
        for name, e in f["effect_percent"].items():
            verdict = "undefined" if e is None else ("matters" if f["matters"][name]
                                                     else "negligible")
            shown = "--" if e is None else f"{e:.3g} %"
            lines.append(f"    {f['factor']:<13} {lo:g}..{hi:g} {f['unit']:<8} {name:<26} "
                         f"effect {shown:>10}  {verdict}")
    return "\n".join(lines)


def parametric_plot(study, size=(11.0, 4.0), dpi: int = 110) -> bytes:
    """PNG: one panel per factor, the median |ratio| of every ratio against its levels."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, dpi=dpi, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, len(study.sweeps), sharey=True)
    for ax, sweep in zip(axes, study.sweeps):
        for name, m in sweep.medians.items():
            ax.plot(sweep.levels, m, marker="o", ms=3,
                    label=f"{name} ({sweep.effect[name]:.3g} %)")
        ax.set_xlabel(f"{sweep.factor.value} [{UNITS[sweep.factor]}]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("median |ratio| over the turn [-]")
    fig.suptitle(f"{study.scene}: transmission ratios against each factor (effect size in "
                 "brackets)", fontsize=10)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()
