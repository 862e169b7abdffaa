"""The rigid-motion study (``studies.cycle.rigid_motion``) rendered: the JSON document of `flexlink
kinematics` (every field name declared here, once), the human-readable report and the CSV."""

from __future__ import annotations

import math
from pathlib import Path

from flexlink.kinematics.linkage import Cycle
from flexlink.fileio import write_atomic
from flexlink.kinematics.motion import Extremes
from flexlink.output.pose.synthesis_text import synthesis_line
from flexlink.studies.cycle.rigid_motion import BodyMotion, MotionStudy, VariantMotion
from flexlink.units import rev_per_min


def kinematics_document(study: MotionStudy, members: tuple[VariantMotion, ...],
                        files: list) -> dict:
    """The JSON document of `flexlink kinematics`: the study's crank speed, the scene's
    synthesis, per body the extremes of angle [deg], K, L (and at the crank speed omega
    [rad/s], alpha [rad/s^2] and the peak |alpha|), the torque ratio, limit positions, swing
    [deg] and time ratio; the transmission angles' extremes [deg]; each [[family]] member the
    same with its table's name, field and value; the ``files`` written and the assumptions."""

    def extremes(e: Extremes) -> dict:
        return {"min": e.min, "min_at_deg": e.min_at_deg, "max": e.max,
                "max_at_deg": e.max_at_deg}

    def body(b: BodyMotion) -> dict:
        s = b.summary
        out = {"angle_deg": None if s.angle is None else extremes(s.angle),
               "K": extremes(s.K), "L": extremes(s.L)}
        if s.torque_ratio is not None:
            out["torque_ratio_min_abs"] = {"value": s.torque_ratio.value,
                                           "at_deg": s.torque_ratio.at_deg}
        if s.omega is not None:
            out["omega_rad_s"] = extremes(s.omega)
            out["alpha_rad_s2"] = extremes(s.alpha)
            out["peak_abs_alpha"] = {"value_rad_s2": s.peak_alpha.value,
                                     "at_deg": s.peak_alpha.at_deg}
        if b.limits:
            out["limit_positions"] = [{"crank_deg": p.crank_deg, "angle_deg": p.angle_deg,
                                       "K": p.K} for p in b.limits]
            out["swing_deg"] = b.swing
        if b.time_ratio is not None:
            out["time_ratio"] = b.time_ratio
        return out

    def motion(s: MotionStudy) -> dict:
        return {"scene": s.scene.name, "synthesis": s.scene.synthesis,
                "bodies": {name: body(b) for name, b in s.bodies.items()},
                "transmission_angle_deg": {pair: extremes(e)
                                           for pair, e in s.transmission.items()}}

    omega = study.crank_speed
    return {"command": "kinematics", "poses": study.poses,
            "crank_speed_rev_per_min": rev_per_min(omega) if omega else None,
            **motion(study),
            "family": [{**motion(m.study), "family": m.name, "field": m.field,
                        "value": m.value} for m in members],
            "files": [str(p) for p in files],
            "assumptions": [f"{a.field}: {a.note}" for a in study.scene.assumptions]}


def _span(e: Extremes, fmt: str) -> str:
    """'min@at .. max@at' of extremes."""
    return (f"{format(e.min, fmt):>8}@{e.min_at_deg:<5.1f}.. "
            f"{format(e.max, fmt):>8}@{e.max_at_deg:<5.1f}")


def motion_text(study: MotionStudy) -> str:
    """Extremes per body, limit positions, swing, time ratio, torque ratio, (at a crank speed)
    angular velocity and acceleration, and the transmission angles."""
    lines = [study.scene.name]
    s = study.scene.synthesis
    if s:
        lines.append("  " + synthesis_line(s))
    lines.append("  extremes over the cycle as value@crank angle [deg]")
    lines.append(f"  {'body':<9} {'angle [deg]':^27} {'K = dtheta/dq':^29} {'L = dK/dq':^29}")
    for name, b in study.bodies.items():
        a = b.summary.angle
        span = _span(a, ".3f") if a else f"{'full turn':^27}"
        lines.append(f"  {name:<9} {span} {_span(b.summary.K, '.4f')} "
                     f"{_span(b.summary.L, '.4f')}")
        for lim in b.limits:
            lines.append(f"            limit position {lim.angle_deg:.3f} deg at crank "
                         f"{lim.crank_deg:.3f} deg")
        if b.swing is not None:
            ratio = f", time ratio {b.time_ratio:.4f}" if b.time_ratio is not None else ""
            lines.append(f"            swing {b.swing:.3f} deg{ratio}")
        t = b.summary.torque_ratio
        if t is not None:
            lines.append(f"            |T_{name}/T_crank| = 1/|K| >= {t.value:.4f} (at crank "
                         f"{t.at_deg:.1f} deg)")
        if b.summary.omega is not None and b.limits:
            w, p = b.summary.omega, b.summary.peak_alpha
            lines.append(f"            omega {w.min:.3f}..{w.max:.3f} rad/s; peak |alpha| "
                         f"{p.value:.1f} rad/s^2 at crank {p.at_deg:.1f} deg")
    for pair, m in study.transmission.items():
        lines.append(f"  transmission angle {pair}: {m.min:.3f} deg (crank "
                     f"{m.min_at_deg:.1f}) .. {m.max:.3f} deg (crank {m.max_at_deg:.1f})")
    return "\n".join(lines)


def variant_text(members: tuple[VariantMotion, ...]) -> str:
    """One line per variant (a member of a [[family]] table) and output body: limit positions,
    swing, time ratio, (at a crank speed) omega and peak alpha."""
    lines, label = [], None
    for m in members:
        with_speed = bool(m.study.crank_speed)
        if m.name != label:
            label = m.name
            lines += ["", f"{label}:",
                      f"  {'value':>7} {'body':<8} {'limits [deg]':>17} {'swing':>8} {'ratio':>7}"
                      + (f" {'omega min..max [rad/s]':>23} {'peak |alpha| [rad/s^2] at':>29}"
                         if with_speed else "")]
        for name, b in m.study.bodies.items():
            if not b.limits:
                continue
            limits = "/".join(f"{lim.angle_deg:.2f}" for lim in b.limits)
            ratio = float("nan") if b.time_ratio is None else b.time_ratio
            line = (f"  {m.value:>7g} {name:<8} {limits:>17} {b.swing:>8.3f} {ratio:>7.4f}")
            if with_speed:
                w, p = b.summary.omega, b.summary.peak_alpha
                line += (f" {w.min:>10.2f}..{w.max:<10.2f} {p.value:>15.1f} "
                         f"at {p.at_deg:>6.1f} deg")
            lines.append(line)
    return "\n".join(lines)


def kinematics_text(study: MotionStudy, members: tuple[VariantMotion, ...]) -> str:
    """What `flexlink kinematics` prints: ``motion_text``, then ``variant_text`` of the
    [[family]] members if there are any."""
    return motion_text(study) + ("\n" + variant_text(members) if members else "")


def motion_csv(cycle: Cycle, crank_speed: float | None = None) -> str:
    """One row per pose: crank angle [deg], then per body angle [deg], K, L (and omega,
    alpha at the crank speed)."""
    cols = ["crank_angle_deg"]
    for b in cycle.body_names:  # a body named "crank" must not repeat the input's heading
        angle = f"{b}_angle_deg" if f"{b}_angle_deg" not in cols else f"{b}_body_angle_deg"
        cols += [angle, f"{b}_K", f"{b}_L"]
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


def write_kinematics_csv(study: MotionStudy, folder: Path) -> list[Path]:
    """kinematics.csv (``motion_csv`` of the study's cycle) in ``folder``, written atomically;
    returns its path in a list."""
    path = folder / "kinematics.csv"
    write_atomic(path, motion_csv(study.cycle, study.crank_speed))
    return [path]
