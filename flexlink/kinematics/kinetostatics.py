"""Kinetostatics for a given input torque: the torque each output body delivers when the
driver is held with a known torque and the linkage moves as prescribed (at rest, or at a crank
speed), with the pin and ground forces, the contact friction at the first output and the
bearing losses of every output.

The Newton-Euler equations of ``inverse.newton_euler`` are solved with the driving torque
known (T_in, counter-clockwise positive) and one unknown load level lambda in its place: each
loaded output i holds an external load torque -lambda w_i, so it delivers T_i = lambda w_i to
its load. How the input is shared (``Sharing``):
  - SERIES: only the last output is loaded (w = 1); the earlier outputs pass the torque on
    through the next loop (the wiper's rocker 1 drives rocker 2 through link 2). An earlier
    output's torque is the one it is driven with, after its bearing: T_i = eta R_i.
  - SPLIT: every output is loaded, the loads sharing the power at rest as ``shares``:
    w_i = share_i / K_i (K_i = dtheta_i/dq), so T_i K_i / T_in is share_i without losses.
R_i is the torque the output's input link puts on it: the moment about its ground pivot of the
force at the joint they share. Losses, each a torque opposing the output's motion (its sense
is sgn K_i, the way it turns when the crank turns forward):
  - the bearing of every output passes eta of the torque it carries: a loss (1 - eta) |R_i|;
  - the first output's contact (a wiper blade on the screen) takes T_f = m eta |R_1|, the share
    m of the torque it is driven with (the paper's T_f3 = m T3).
A loss torque -c |R| sgn K is linear in the pin forces once the sign of R is known: the signs
are taken from the lossless solution and corrected until they agree (``SIGN_ROUNDS``).
Power: T_in Omega = sum T_i omega_i (loaded) + sum c_i |R_i omega_i| + dKE/dt - P_loads.
Where an output cannot turn (K_i = 0, a dead point) the equations are singular and every
torque and force is unbounded; the solution there is NaN, never a large number.
"""

from __future__ import annotations

import dataclasses
import enum
import itertools
from collections.abc import Sequence

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics.dynamics import RigidMotion, rigid_motion
from flexlink.kinematics.inverse import BodyMass, Wrench, newton_euler
from flexlink.kinematics.linkage import Linkage, State

SIGN_ROUNDS = 4  # sign corrections before every combination of signs is tried


class Sharing(enum.StrEnum):
    """How an input torque is shared between two or more outputs (see the module doc)."""

    SERIES = "series"
    SPLIT = "split"


@dataclasses.dataclass(frozen=True)
class Output:
    """An output body turning about ground joint ``pivot``, driven by body ``feeder`` through
    their shared joint ``feed``."""

    body: str
    pivot: str
    feed: str
    feeder: str


@dataclasses.dataclass(frozen=True)
class Losses:
    """Contact-friction factor m [-] of the first output (0 <= m < 1) and bearing
    transmission efficiency eta [-] of every output (0 < eta <= 1)."""

    friction: float = 0.0
    efficiency: float = 1.0
    source: str = "command line"

    def __post_init__(self):
        if not 0.0 <= self.friction < 1.0:
            raise InputError(f"got {self.friction!r}", source=self.source,
                             field="kinetostatics.friction", expected="m in [0, 1)")
        if not 0.0 < self.efficiency <= 1.0:
            raise InputError(f"got {self.efficiency!r}", source=self.source,
                             field="kinetostatics.efficiency", expected="eta in (0, 1]")


@dataclasses.dataclass(frozen=True)
class Transmission:
    """How the outputs share the input: the convention and, for SPLIT, each output's share of
    the input power at rest (>= 0, summing to 1)."""

    outputs: tuple[Output, ...]
    sharing: Sharing = Sharing.SERIES
    shares: tuple[float, ...] = ()

    def __post_init__(self):
        if not self.outputs:
            raise InputError("no output body", field="kinetostatics.outputs")
        if self.sharing is Sharing.SPLIT:
            s = np.asarray(self.shares, float)
            if s.shape != (len(self.outputs),) or np.any(s < 0) or abs(s.sum() - 1) > 1e-12:
                raise InputError(f"shares {self.shares!r}", field="kinetostatics.share",
                                 expected="one share >= 0 per output, summing to 1")

    def loaded(self) -> tuple[bool, ...]:
        if self.sharing is Sharing.SERIES:
            return tuple(i == len(self.outputs) - 1 for i in range(len(self.outputs)))
        return tuple(True for _ in self.outputs)


@dataclasses.dataclass(frozen=True)
class OutputState:
    """At one crank angle: each output's torque T_i [N m] (delivered to its load, or for an
    output passing torque on, the torque it is driven with after its bearing), the torque R_i
    [N m] its input link puts on it, the contact-friction torque [N m] (first output), the power
    lost to friction and bearings [W], the force [N] on each body at each joint (keyed
    (joint, body)), kinetic energy [J] and power of the other loads [W]. NaN at a dead point."""

    q: float
    torques: np.ndarray
    received: np.ndarray
    friction_torque: float
    loss_power: float
    forces: dict[tuple[str, str], np.ndarray]
    kinetic_energy: float
    load_power: float


def _moment_row(system, motion: RigidMotion, out: Output) -> np.ndarray:
    """Coefficients of R (moment about the pivot of the force on the output at its feed)."""
    r = motion.points[out.feed] - motion.points[out.pivot]
    c = system.columns[(out.feed, out.body)]
    row = np.zeros(system.matrix.shape[1])
    row[c], row[c + 1] = -r[1], r[0]
    return row


def output_torques(linkage: Linkage, state: State, speed: float, masses: Sequence[BodyMass],
                   input_torque: float, transmission: Transmission, losses: Losses = Losses(),
                   loads: Sequence[Wrench] = (), crank_acceleration: float = 0.0) -> OutputState:
    """The outputs' torques and the pin forces at the pose ``state`` moving at crank speed
    ``speed`` [rad/s] (0: at rest) and ``crank_acceleration`` [rad/s^2], with the driver held
    by ``input_torque`` [N m] (see the module doc)."""
    motion = rigid_motion(linkage, state, speed, crank_acceleration)
    system = newton_euler(linkage, motion, masses, loads)
    outs = transmission.outputs
    names = [b.name for b in linkage.bodies]
    K = np.array([state.K[names.index(o.body)] for o in outs])
    sense = np.sign(K)  # the way each output turns when the crank turns forward
    A, rhs = system.matrix.copy(), system.rhs.copy()
    rhs[system.moment_rows[linkage.driver]] -= input_torque
    A[:, -1] = 0.0
    loaded = transmission.loaded()
    weights = np.zeros(len(outs))
    for i, out in enumerate(outs):
        if not loaded[i]:
            continue
        w = 1.0
        if transmission.sharing is Sharing.SPLIT:
            w = transmission.shares[i] / K[i] if K[i] != 0 else np.inf
        weights[i] = w
        A[system.moment_rows[out.body], -1] -= w
    R_rows = [_moment_row(system, motion, o) for o in outs]
    c = np.full(len(outs), 1.0 - losses.efficiency)
    c[0] += losses.friction * losses.efficiency
    n = A.shape[0]
    if not np.all(np.isfinite(A)):
        return _dead(motion, outs, system)

    def solve(signs):
        M = A.copy()
        for i, out in enumerate(outs):
            M[system.moment_rows[out.body]] -= c[i] * sense[i] * signs[i] * R_rows[i]
        return np.linalg.solve(M, rhs)

    try:
        x = solve(np.zeros(len(outs)))
        if np.any(c > 0):
            signs = np.sign([r @ x for r in R_rows])
            for _ in range(SIGN_ROUNDS):
                x = solve(signs)
                new = np.sign([r @ x for r in R_rows])
                if np.all((new == signs) | (new == 0)):
                    break
                signs = new
            else:
                x = next((y for s in itertools.product((1.0, -1.0), repeat=len(outs))
                          if np.all(np.sign([r @ (y := solve(s)) for r in R_rows]) * s >= 0)),
                         None)
                if x is None:
                    return _dead(motion, outs, system)
    except np.linalg.LinAlgError:
        return _dead(motion, outs, system)
    if not (np.all(np.isfinite(x)) and x.shape == (n,)):
        return _dead(motion, outs, system)
    R = np.array([r @ x for r in R_rows])
    torques = np.where(loaded, x[-1] * weights, losses.efficiency * R)
    loss = float(np.sum(c * np.abs(R * K * speed)))
    forces = {key: x[col:col + 2] for key, col in system.columns.items()}
    return OutputState(q=motion.q, torques=torques, received=R,
                       friction_torque=float(losses.friction * losses.efficiency * abs(R[0])),
                       loss_power=loss, forces=forces, kinetic_energy=system.kinetic_energy,
                       load_power=system.load_power)


def _dead(motion: RigidMotion, outs, system) -> OutputState:
    nan = np.full(len(outs), np.nan)
    return OutputState(q=motion.q, torques=nan, received=nan.copy(), friction_torque=np.nan,
                       loss_power=np.nan,
                       forces={key: np.full(2, np.nan) for key in system.columns},
                       kinetic_energy=system.kinetic_energy, load_power=system.load_power)
