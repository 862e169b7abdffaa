"""What the rigid motion over a cycle amounts to: extremes of angles, velocity coefficients
K, their derivatives L, angular velocity and acceleration at a constant crank speed, limit
positions of rockers, and the frictionless static torque ratio.

With the crank at constant speed w [rad/s]: omega = K w, alpha = L w^2 (K qddot vanishes).
Virtual work: T_crank dq + T_out dtheta = 0, so |T_out / T_crank| = 1 / |K|: a rocker holds
an unbounded torque at its limit positions (K = 0), the least where |K| is largest.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.kinematics.linkage import Cycle, Linkage, crossings

LIMIT_TOL = 1e-13  # |K| [-] at a refined limit position


@dataclasses.dataclass(frozen=True)
class Extremes:
    """Smallest (``min``) and largest (``max``) sampled value, in the unit of the values, and
    the input angles [deg, 0..360] where they occur."""

    min: float
    min_at_deg: float
    max: float
    max_at_deg: float

    def __post_init__(self):
        if not self.min <= self.max:
            raise ValueError(f"Extremes.min is {self.min}, expected at most max = {self.max}")
        for name in ("min_at_deg", "max_at_deg"):
            # x % 360.0 rounds to 360.0 for x just below 0, so 360 itself is allowed
            if not 0.0 <= getattr(self, name) <= 360.0:
                raise ValueError(f"Extremes.{name} is {getattr(self, name)}, expected 0..360 deg")


@dataclasses.dataclass(frozen=True)
class Peak:
    """One sampled value, in the unit its owner names, and the input angle [deg] where it is."""

    value: float
    at_deg: float


@dataclasses.dataclass(frozen=True)
class LimitPosition:
    """Where a body stops and turns back: crank angle [deg, 0..360], the body's angle [deg,
    -180..180] and the K [-] left there by the refinement."""

    crank_deg: float
    angle_deg: float
    K: float


@dataclasses.dataclass(frozen=True)
class BodySummary:
    """One body over the cycle: extremes of its angle [deg] (None for a body turning fully,
    whose angle has no extremes), of K [-] and L [-]; for an output body the smallest
    |torque ratio| 1 / max |K| (``torque_ratio``, None otherwise); at a crank speed the
    extremes of omega [rad/s] and alpha [rad/s^2] and the peak |alpha| [rad/s^2] (all three
    None without one)."""

    angle: Extremes | None
    K: Extremes
    L: Extremes
    torque_ratio: Peak | None = None
    omega: Extremes | None = None
    alpha: Extremes | None = None
    peak_alpha: Peak | None = None

    def __post_init__(self):
        at_speed = [x is not None for x in (self.omega, self.alpha, self.peak_alpha)]
        if any(at_speed) and not all(at_speed):
            raise ValueError("BodySummary has only some of omega, alpha and peak_alpha, "
                             "expected all three (at a crank speed) or none")


def extremes(q: np.ndarray, values: np.ndarray) -> Extremes:
    """Smallest and largest sampled value and the input angles [deg] where they occur."""
    i, j = int(np.argmin(values)), int(np.argmax(values))
    return Extremes(float(values[i]), math.degrees(q[i]) % 360.0,
                    float(values[j]), math.degrees(q[j]) % 360.0)


def limit_positions(linkage: Linkage, cycle: Cycle, body: str) -> tuple[LimitPosition, ...]:
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
        out.append(LimitPosition(
            crank_deg=math.degrees(q) % 360.0,
            angle_deg=math.degrees(math.remainder(state.angles[col], 2 * math.pi)),
            K=float(state.K[col])))
    return tuple(out)


def body_summary(cycle: Cycle, body: str, crank_speed: float | None,
                 output: bool = False) -> BodySummary:
    """Extremes over the cycle of one body's angle [deg], K, L, and (given the crank speed
    [rad/s]; 0 counts as none) omega [rad/s] and alpha [rad/s^2]; for an ``output`` body (one
    turning about a ground pivot) the smallest |torque ratio| 1 / max |K|."""
    col = cycle.column(body)
    K, L = cycle.K[:, col], cycle.L[:, col]
    angles = np.degrees(cycle.angles[:, col])
    # a full turn (a crank): the extremes of its angle mean nothing
    turns = angles.max() - angles.min() >= 360.0 * (1 - 1.5 / len(angles))
    k_abs = np.abs(K)
    torque_ratio = None
    if output and k_abs.max() > 0:
        i = int(np.argmax(k_abs))
        torque_ratio = Peak(float(1.0 / k_abs[i]), math.degrees(cycle.q[i]) % 360.0)
    omega = alpha = peak_alpha = None
    if crank_speed:
        peak = int(np.argmax(np.abs(L)))
        omega, alpha = extremes(cycle.q, K * crank_speed), extremes(cycle.q, L * crank_speed**2)
        peak_alpha = Peak(float(abs(L[peak]) * crank_speed**2), math.degrees(cycle.q[peak]) % 360.0)
    return BodySummary(angle=None if turns else extremes(cycle.q, angles),
                       K=extremes(cycle.q, K), L=extremes(cycle.q, L), torque_ratio=torque_ratio,
                       omega=omega, alpha=alpha, peak_alpha=peak_alpha)
