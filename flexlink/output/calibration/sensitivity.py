"""Text and JSON-ready forms of the alternatives (orientation, shear source) and of the
sensitivity study (``studies/calibration/sensitivity.py``) for ``flexlink modes``."""

from __future__ import annotations

from flexlink.studies.pose.alternatives import Alternative
from flexlink.studies.calibration.sensitivity import SceneSensitivity


def alternative_document(alt: Alternative | None) -> dict | None:
    """The JSON document of one alternative (None stays None)."""
    if alt is None:
        return None
    out = {"field": alt.field, "value": alt.value, "computed_Hz": alt.frequencies.tolist(),
           "mean_abs_error_pct": alt.mean_abs_error_pct}
    return out if alt.used is None else {**out, "used": alt.used}


def alternative_line(label: str, alt: Alternative) -> str:
    """One line: what the other value of a modelling choice gives."""
    freqs = ", ".join(f"{f:.4g}" for f in alt.frequencies)
    errors = ", ".join(f"vs {k} {v:.1f} %" for k, v in sorted(alt.mean_abs_error_pct.items()))
    used = f" (used: {alt.used})" if alt.used is not None else ""
    return f"{label}{used}: with {alt.field} = {alt.value!r}: {freqs} Hz" + (
        f"; mean |error| {errors}" if errors else "")


def sensitivity_document(study: SceneSensitivity) -> dict:
    """JSON-ready end points and 95 % interval of one scene's sensitivity study."""
    points, interval = study.points, study.interval
    return {
        "elements_per_link": study.elements,
        "nominal_Hz": points.nominal.tolist(),
        "inputs": [{"field": s.field, "value": s.value, "low": s.low, "high": s.high,
                    "reason": s.reason, "low_Hz": ends[0].tolist(), "high_Hz": ends[1].tolist()}
                   for s, ends in zip(points.spans, points.ends)],
        "monte_carlo": {"samples": int(interval.samples.shape[0]), "seed": interval.seed,
                        "failed": interval.failed, "low_Hz": interval.low.tolist(),
                        "high_Hz": interval.high.tolist(),
                        "inside": {k: interval.contains(v).tolist()
                                   for k, v in study.reference.items()}},
    }


def format_sensitivity(data: dict) -> str:
    """The end-point table and the 95 % interval, Ex values inside marked with '*'."""
    n = len(data["nominal_Hz"])
    head = "input".ljust(24) + "end".ljust(16) + "".join(f"f{i + 1} Hz".rjust(10) for i in range(n))
    lines = [f"sensitivity ({data['elements_per_link']} elements/link): each assumed input at "
             "both ends of its range, the others nominal", head,
             "nominal".ljust(40) + "".join(f"{f:10.4g}" for f in data["nominal_Hz"])]
    for row in data["inputs"]:
        for end in ("low", "high"):
            name = row["field"] if end == "low" else ""
            lines.append(name.ljust(24) + str(row[end]).ljust(16)
                         + "".join(f"{f:10.4g}" for f in row[f"{end}_Hz"]))
    mc = data["monte_carlo"]
    lines.append(f"Monte Carlo 95 % interval ({mc['samples']} samples, seed {mc['seed']}, "
                 f"{mc['failed']} failed; ranged inputs with the Table I spreads, orientation "
                 "fixed):")
    lines.append("".ljust(40) + "".join(f"{lo:.3g}-{hi:.3g}".rjust(10)
                                        for lo, hi in zip(mc["low_Hz"], mc["high_Hz"])))
    for name, inside in mc["inside"].items():
        lines.append(f"{name} inside (*)".ljust(40) + "".join(
            ("*" if flag else "-").rjust(10) for flag in inside))
    return "\n".join(lines)
