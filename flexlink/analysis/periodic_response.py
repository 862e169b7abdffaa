"""The steady (periodic) solution of a damped, forced linear periodic system
x' = A(t) x + b(t) with period T, by shooting with the monodromy matrix.

The forcing is carried by one extra, constant state: z = (x, 1) obeys the homogeneous
z' = [[A, b], [0, 0]] z, so the Magnus integrator of ``floquet.propagators`` gives over one
period [[Phi, x_p], [0, 1]], with Phi the monodromy matrix of the unforced system and x_p the
state after one period from rest. The periodic state at t = 0 solves x0 = Phi x0 + x_p:

    x0 = (I - Phi)^-1 x_p,

which exists and is unique when no Floquet multiplier is 1; when one has |mu| >= 1 the free
motion does not die out and no steady state is reached, so the solution is refused.

Why shooting rather than harmonic balance: the monodromy matrix is the one the stability map
already integrates, so stability and response come from the same integration; its error is
set by the step (fourth order) alone, while harmonic balance must keep every crank harmonic up
to f_max / f_crank, hundreds at low speed, and solve one coupled system of that size.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexlink.analysis.floquet import FloquetResult, floquet, ordered_product, propagators
from flexlink.errors import NumericalError


@dataclass(frozen=True)
class PeriodicSolution:
    """The steady state over one period: states (samples, N) at times (samples,) [s], equally
    spaced from 0 (T excluded); ``stability``: the unforced system's multipliers."""

    times: np.ndarray
    states: np.ndarray
    stability: FloquetResult

    def __post_init__(self):
        if self.states.ndim != 2 or self.states.shape[0] != self.times.shape[0]:
            raise ValueError(f"states {self.states.shape} need one row per time "
                             f"{self.times.shape}")


class UnstableError(NumericalError):
    """The free motion grows (a Floquet multiplier |mu| >= 1): no steady state exists."""


def augmented(system, forcing):
    """t -> [[A(t), b(t)], [0, 0]]: the forced system as a homogeneous one of one more state."""
    def z(t):
        a, b = np.asarray(system(t)), np.asarray(forcing(t))
        out = np.zeros(a.shape[:-2] + (a.shape[-1] + 1, a.shape[-1] + 1))
        out[..., :-1, :-1] = a
        out[..., :-1, -1] = b
        return out
    return z


def periodic_solution(system, forcing, period: float, steps: int,
                      samples: int) -> PeriodicSolution:
    """The periodic solution of x' = A(t) x + b(t) sampled at ``samples`` equal times.

    system: times (m,) [s] -> A (m, N, N); forcing: times (m,) -> b (m, N); both periodic with
    ``period`` [s]; steps: Magnus steps per period at least (rounded up to a multiple of
    ``samples``). UnstableError when a multiplier has |mu| >= 1."""
    if samples < 1:
        raise NumericalError(f"samples must be at least 1, got {samples}")
    per = max(1, math.ceil(steps / samples))
    interval = period / samples
    steps_between = propagators(augmented(system, forcing), period, samples, per)
    z = ordered_product(steps_between)
    n = z.shape[0] - 1
    phi, x_p = z[:n, :n], z[:n, n]
    stability = floquet(phi, period)
    if stability.largest_modulus >= 1.0:
        raise UnstableError(f"largest Floquet multiplier |mu| = {stability.largest_modulus:.6g}"
                            " >= 1: the free motion grows, no steady state exists")
    state = np.append(np.linalg.solve(np.eye(n) - phi, x_p), 1.0)
    states = np.empty((samples, n))
    for k, p in enumerate(steps_between):
        states[k] = state[:n]
        state = p @ state
    return PeriodicSolution(times=interval * np.arange(samples), states=states,
                            stability=stability)
