"""The rigid-motion study (``studies.kinematics``) as a human-readable report and as CSV."""

from __future__ import annotations

import math

from flexlink.kinematics.linkage import Cycle


def _span(e: dict, fmt: str) -> str:
    """'min@at .. max@at' of a ``motion.extremes`` dict."""
    return (f"{format(e['min'], fmt):>8}@{e['min_at_deg']:<5.1f}.. "
            f"{format(e['max'], fmt):>8}@{e['max_at_deg']:<5.1f}")


def motion_text(doc: dict, with_speed: bool) -> str:
    """Extremes per body, limit positions, swing, time ratio, torque ratio, (``with_speed``)
    angular velocity and acceleration, and the transmission angles."""
    lines = [doc["scene"]]
    if doc.get("synthesis"):
        s = doc["synthesis"]
        lines.append(f"  synthesis {s['method']} {s['inputs']}: " + ", ".join(
            f"{k} {1e3 * v:.3f} mm" for k, v in s["lengths_m"].items()))
    lines.append("  extremes over the cycle as value@crank angle [deg]")
    lines.append(f"  {'body':<9} {'angle [deg]':^27} {'K = dtheta/dq':^29} {'L = dK/dq':^29}")
    for name, b in doc["bodies"].items():
        a, K, L = b["angle_deg"], b["K"], b["L"]
        span = _span(a, ".3f") if a else f"{'full turn':^27}"
        lines.append(f"  {name:<9} {span} {_span(K, '.4f')} {_span(L, '.4f')}")
        for lim in b.get("limit_positions", []):
            lines.append(f"            limit position {lim['angle_deg']:.3f} deg at crank "
                         f"{lim['crank_deg']:.3f} deg")
        if "swing_deg" in b:
            ratio = f", time ratio {b['time_ratio']:.4f}" if "time_ratio" in b else ""
            lines.append(f"            swing {b['swing_deg']:.3f} deg{ratio}")
        if "torque_ratio_min_abs" in b:
            t = b["torque_ratio_min_abs"]
            lines.append(f"            |T_{name}/T_crank| = 1/|K| >= {t['value']:.4f} (at crank "
                         f"{t['at_deg']:.1f} deg)")
        if with_speed and "peak_abs_alpha" in b and "limit_positions" in b:
            w, p = b["omega_rad_s"], b["peak_abs_alpha"]
            lines.append(f"            omega {w['min']:.3f}..{w['max']:.3f} rad/s; peak |alpha| "
                         f"{p['value_rad_s2']:.1f} rad/s^2 at crank {p['at_deg']:.1f} deg")
    for pair, m in doc["transmission_angle_deg"].items():
        lines.append(f"  transmission angle {pair}: {m['min']:.3f} deg (crank "
                     f"{m['min_at_deg']:.1f}) .. {m['max']:.3f} deg (crank {m['max_at_deg']:.1f})")
    return "\n".join(lines)


def variant_text(members: list[dict], with_speed: bool) -> str:
    """One line per variant (a member of a [[family]] table) and output body: swing, time ratio, (``with_speed``) omega
    and peak alpha."""
    lines, label = [], None
    for m in members:
        if m["family"] != label:
            label = m["family"]
            lines += ["", f"{label}:",
                      f"  {'value':>7} {'body':<8} {'limits [deg]':>17} {'swing':>8} {'ratio':>7}"
                      + (f" {'omega min..max [rad/s]':>23} {'peak |alpha| [rad/s^2] at':>29}"
                         if with_speed else "")]
        for name, b in m["bodies"].items():
            if "limit_positions" not in b:
                continue
            limits = "/".join(f"{lim['angle_deg']:.2f}" for lim in b["limit_positions"])
            line = (f"  {m['value']:>7g} {name:<8} {limits:>17} {b['swing_deg']:>8.3f} "
                    f"{b.get('time_ratio', float('nan')):>7.4f}")
            if with_speed:
                w, p = b["omega_rad_s"], b["peak_abs_alpha"]
                line += (f" {w['min']:>10.2f}..{w['max']:<10.2f} {p['value_rad_s2']:>15.1f} "
                         f"at {p['at_deg']:>6.1f} deg")
            lines.append(line)
    return "\n".join(lines)


def motion_csv(cycle: Cycle, crank_speed: float | None = None) -> str:
    """One row per pose: crank angle [deg], then per body angle [deg], K, L (and omega,
    alpha at the crank speed)."""
    cols = ["crank_angle_deg"]
    for b in cycle.body_names:
        cols += [f"{b}_angle_deg", f"{b}_K", f"{b}_L"]
        if crank_speed:
            cols += [f"{b}_omega_rad_s", f"{b}_alpha_rad_s2"]
    lines = [",".join(cols)]
    for i, q in enumerate(cycle.q):
        row = [math.degrees(q)]
        for j in range(len(cycle.body_names)):
            row += [math.degrees(cycle.angles[i, j]), cycle.K[i, j], cycle.L[i, j]]
            if crank_speed:
                row += [cycle.K[i, j] * crank_speed, cycle.L[i, j] * crank_speed**2]
        lines.append(",".join(f"{v:.10g}" for v in row))
    return "\n".join(lines) + "\n"
