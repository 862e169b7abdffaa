"""A fit to a modal test (``studies.calibration.by_test``) as JSON and text: the fitted inputs
with their 95 % intervals, and the MAC pairs with their frequency errors at the start (the
scene's own inputs) and at the end (the fitted ones)."""

from __future__ import annotations

import math

from flexlink.studies.calibration.by_test import TestFit


def _pairs(c) -> list[dict]:
    errors = c.errors_pct()
    return [{"test": i + 1, "model": j + 1, "test_Hz": float(c.test.frequencies[i]),
             "model_Hz": float(c.model.frequencies[j]), "error_pct": float(e), "mac": float(v),
             "quality": str(q)}
            for (i, j), e, v, q in zip(c.correlation.pairs, errors, c.correlation.pair_mac,
                                       c.correlation.pair_quality)]


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def by_test_json(fit: TestFit) -> dict:
    return {"scene": fit.scene_path, "test": fit.test.source, "mac_weight": fit.mac_weight,
            "converged": fit.converged, "evaluations": fit.evaluations, "cost": fit.cost,
            "inputs": [{"name": p.name, "unit": p.unit, "bounds": [p.low, p.high],
                        "nominal": float(n), "fitted": float(v), "low_95": _finite(lo),
                        "high_95": _finite(hi), "rel_se": _finite(se)}
                       for p, n, v, lo, hi, se in zip(fit.parameters, fit.nominal, fit.values,
                                                      fit.low, fit.high, fit.rel_se)],
            "pairs_start": _pairs(fit.start), "pairs_end": _pairs(fit.end),
            "unpaired_test_start": [i + 1 for i in fit.start.correlation.unpaired_test],
            "unpaired_test_end": [i + 1 for i in fit.end.correlation.unpaired_test]}


def _pair_lines(title: str, pairs: list[dict], unpaired: list[int]) -> list[str]:
    lines = [title, "test  test Hz  model  model Hz  error %    MAC"]
    lines += [f"{p['test']:>4} {p['test_Hz']:>8.2f} {p['model']:>6} {p['model_Hz']:>9.2f} "
              f"{p['error_pct']:>+8.3f} {p['mac']:>6.3f}" for p in pairs]
    if unpaired:
        lines.append("unpaired test modes: " + ", ".join(map(str, unpaired)))
    return lines


def by_test_text(document: dict) -> str:
    d = document
    weight = f", MAC term weight {d['mac_weight']:g}" if d["mac_weight"] > 0 else ""
    lines = [f"{d['scene']} fitted to test {d['test']} (frequencies paired by MAC{weight}; "
             f"{d['evaluations']} evaluations, "
             f"{'converged' if d['converged'] else 'stopped at the evaluation limit'})",
             "input        nominal       fitted        95 % interval"]
    for i in d["inputs"]:
        interval = ("not determined" if i["low_95"] is None
                    else f"{i['low_95']:.6g} .. {i['high_95']:.6g}")
        lines.append(f"{i['name']:<12} {i['nominal']:<13.6g} {i['fitted']:<13.6g} "
                     f"{interval} {i['unit']}")
    lines += _pair_lines("pairs at the start (the scene's inputs):", d["pairs_start"],
                         d["unpaired_test_start"])
    lines += _pair_lines("pairs at the end (fitted inputs):", d["pairs_end"],
                         d["unpaired_test_end"])
    return "\n".join(lines)
