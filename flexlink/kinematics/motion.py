"""What the rigid motion over a cycle amounts to: extremes of angles, velocity coefficients
K, their derivatives L, angular velocity and acceleration at a constant crank speed, limit
positions of rockers, and the frictionless static torque ratio.

With the crank at constant speed w [rad/s]: omega = K w, alpha = L w^2 (K qddot vanishes).
Virtual work: T_crank dq + T_out dtheta = 0, so |T_out / T_crank| = 1 / |K|: a rocker holds
an unbounded torque at its limit positions (K = 0), the least where |K| is largest.
"""

from __future__ import annotations

import math

import numpy as np

from flexlink.kinematics.linkage import Cycle, Linkage, crossings

LIMIT_TOL = 1e-13  # |K| [-] at a refined limit position


def extremes(q: np.ndarray, values: np.ndarray) -> dict:
    """Smallest and largest sampled value and the input angles [deg] where they occur."""
    i, j = int(np.argmin(values)), int(np.argmax(values))
    return {"min": float(values[i]), "min_at_deg": math.degrees(q[i]) % 360.0,
            "max": float(values[j]), "max_at_deg": math.degrees(q[j]) % 360.0}


def limit_positions(linkage: Linkage, cycle: Cycle, body: str) -> list[dict]:
    """Where ``body`` stops and turns back (K = 0): crank angle [deg] and body angle [deg],
    refined from the sampled sign changes of K by Newton steps on K (dK/dq = L)."""
    col = cycle.column(body)
    out = []
    for q0 in crossings(cycle.q, cycle.K[:, col], 0.0):
        gap = np.remainder(cycle.q - q0 + math.pi, 2 * math.pi) - math.pi
        nearest = int(np.argmin(np.abs(gap)))
        state, q = cycle.states[nearest], q0
        for _ in range(20):
            state = linkage.solve(q, state.points)
            if abs(state.K[col]) < LIMIT_TOL:
                break
            q -= state.K[col] / state.L[col]
        out.append({"crank_deg": math.degrees(q) % 360.0,
                    "angle_deg": math.degrees(math.remainder(state.angles[col], 2 * math.pi)),
                    "K": float(state.K[col])})
    return out


def body_summary(cycle: Cycle, body: str, crank_speed: float | None, output: bool = False) -> dict:
    """Extremes over the cycle of one body's angle [deg], K, L, and (given the crank speed
    [rad/s]) omega [rad/s] and alpha [rad/s^2]; for an ``output`` body (one turning about a
    ground pivot) the smallest |torque ratio| 1 / max |K|."""
    col = cycle.column(body)
    K, L = cycle.K[:, col], cycle.L[:, col]
    angles = np.degrees(cycle.angles[:, col])
    # a full turn (a crank): the extremes of its angle mean nothing
    turns = angles.max() - angles.min() >= 360.0 * (1 - 1.5 / len(angles))
    out = {"angle_deg": None if turns else extremes(cycle.q, angles),
           "K": extremes(cycle.q, K), "L": extremes(cycle.q, L)}
    k_abs = np.abs(K)
    if output and k_abs.max() > 0:
        i = int(np.argmax(k_abs))
        out["torque_ratio_min_abs"] = {"value": float(1.0 / k_abs[i]),
                                       "at_deg": math.degrees(cycle.q[i]) % 360.0}
    if crank_speed:
        out["omega_rad_s"] = extremes(cycle.q, K * crank_speed)
        out["alpha_rad_s2"] = extremes(cycle.q, L * crank_speed**2)
        peak = int(np.argmax(np.abs(L)))
        out["peak_abs_alpha"] = {"value_rad_s2": float(abs(L[peak]) * crank_speed**2),
                                 "at_deg": math.degrees(cycle.q[peak]) % 360.0}
    return out
