"""Output torques for a given input torque over one crank turn (``kinematics.kinetostatics`` at
every pose of the scene's cycle): each output's torque, the transmission ratios, the pin and
ground forces and where each peaks, the friction and bearing losses, and the dead points.

Dead points: where an output stops and turns back (K = dtheta/dq = 0, ``motion.limit_positions``)
the torque a finite input torque can hold there, and the pin forces, grow without bound. A
sample is "next to a dead point" where some output's |K| is below ``DEAD_BAND`` times its
largest |K| over the turn (its torque ratio 1/|K| then exceeds ten times its least value, and
how large the sample is depends on how near the grid happens to fall to the dead point, not
on the design). Peaks are taken over the other samples; a larger sampled value next to a dead
point is reported as that, with the dead point's crank angle, never as a result.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics.dynamics import check_speed
from flexlink.kinematics.inverse import BodyMass
from flexlink.kinematics.kinetostatics import Losses, Transmission, output_torques
from flexlink.kinematics.motion import limit_positions
from flexlink.scene import Scene
from flexlink.scene.contract import KinetostaticsSpec, LoadSpec
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.modal_map import kinematic_cycle
from flexlink.studies.running.torque import scene_masses, wrench

DEAD_BAND = 0.1  # |K| / max |K| of an output below this: next to its dead point
SAME_DEG = 1e-6  # [deg] two dead points this close are one

MODEL = (
    "rigid bodies; the crank moves as prescribed (at rest, or at the crank speed) and the input "
    "torque holds it; the unknown is the load the outputs carry",
    ("losses oppose each output's motion: its bearing passes eta of the torque its input link "
     "puts on it, and the first output's contact takes m of the torque it is driven with"),
    ("each beam is a uniform straight bar between its joints; joint masses are point masses on "
     "the first body carrying the joint; no gravity; other loads only as in [[loads]]"),
)


@dataclasses.dataclass(frozen=True)
class DeadPoint:
    """Where output ``body`` stops and turns back: crank angle [deg, 0..360]."""

    body: str
    crank_deg: float


@dataclasses.dataclass(frozen=True)
class CurvePeak:
    """The largest |value| of one curve away from the dead points (``value`` signed, in the
    curve's unit, at ``at_deg``), and, if larger, the sampled value next to a dead point
    (``near_value`` at ``near_at_deg``, the dead point at ``dead_point_deg``): unbounded there,
    so only a sample, not a result. ``at_band_edge``: the peak sits beside those samples, so the
    curve is still rising towards the dead point there (the peak is the band's, not the
    design's)."""

    name: str
    unit: str
    value: float
    at_deg: float
    at_band_edge: bool = False  # the peak borders the samples next to a dead point
    near_value: float | None = None
    near_at_deg: float | None = None
    dead_point_deg: float | None = None


@dataclasses.dataclass(frozen=True)
class OutputCurve:
    """Over the crank angles ``q`` [rad]: input torque [N m]; per output (columns in
    ``outputs`` order) its torque [N m], the torque its input link puts on it [N m] and its
    velocity coefficient K [-]; the ratios [-] by name; contact-friction torque [N m], power lost
    to friction and bearings [W], kinetic energy [J], power of the other loads [W]; the force [N]
    on each body at each reported joint ("joint:body"); ``near``: samples next to a dead point."""

    scene: str
    speed: float  # [rad/s]
    crank_acceleration: float  # [rad/s^2]
    transmission: Transmission
    losses: Losses
    q: np.ndarray
    input_torque: np.ndarray
    torques: np.ndarray
    received: np.ndarray
    K: np.ndarray
    ratios: dict[str, np.ndarray]
    friction_torque: np.ndarray
    loss_power: np.ndarray
    kinetic_energy: np.ndarray
    load_power: np.ndarray
    forces: dict[str, np.ndarray]
    near: np.ndarray
    dead_points: tuple[DeadPoint, ...]
    masses: tuple[BodyMass, ...]
    model: tuple[str, ...] = MODEL

    def __post_init__(self):
        n, k = len(self.q), len(self.transmission.outputs)
        for name in ("input_torque", "friction_torque", "loss_power", "kinetic_energy",
                     "load_power", "near"):
            check_shape("OutputCurve", name, getattr(self, name), (n,))
        for name in ("torques", "received", "K"):
            check_shape("OutputCurve", name, getattr(self, name), (n, k))
        for name, r in self.ratios.items():
            check_shape("OutputCurve", f"ratios[{name}]", r, (n,))
        for name, f in self.forces.items():
            check_shape("OutputCurve", f"forces[{name}]", f, (n, 2))

    @property
    def outputs(self) -> tuple[str, ...]:
        return tuple(o.body for o in self.transmission.outputs)

    def dead_point_angles(self) -> dict[float, tuple[str, ...]]:
        """Crank angle [deg] of each dead point -> the outputs that stop there."""
        out: dict[float, tuple[str, ...]] = {}
        for d in self.dead_points:
            at = next((a for a in out if _gap(a, d.crank_deg) < SAME_DEG), d.crank_deg)
            out[at] = out.get(at, ()) + (d.body,)
        return out

    def _bounded(self, a: int | None, b: int) -> bool:
        """A ratio of two outputs that stop at the same crank angles stays bounded there."""
        if a is None:
            return False
        outs = self.outputs
        both = [sorted(d.crank_deg for d in self.dead_points if d.body == outs[i]) for i in (a, b)]
        return len(both[0]) == len(both[1]) and all(
            _gap(x, y) < SAME_DEG for x, y in zip(*both))

    def curves(self) -> dict[str, tuple[str, np.ndarray, bool]]:
        """Every reported curve by name: (unit, values, bounded next to the dead points)."""
        out = {f"T[{o}]": ("N m", self.torques[:, i], False) for i, o in enumerate(self.outputs)}
        for name, a, b in ratio_names(self.outputs):
            out[name] = ("-", self.ratios[name], self._bounded(a, b))
        out.update({f"F[{key}]": ("N", np.hypot(f[:, 0], f[:, 1]), False)
                    for key, f in self.forces.items()})
        return out

    def peaks(self) -> tuple[CurvePeak, ...]:
        """The peak of every curve (see ``CurvePeak`` and the module doc)."""
        deg = crank_deg(self.q)
        n = len(self.q)
        out = []
        for name, (unit, values, bounded) in self.curves().items():
            finite = np.isfinite(values)
            ok = finite & (True if bounded else ~self.near)
            if not ok.any():
                continue
            i = int(np.flatnonzero(ok)[np.argmax(np.abs(values[ok]))])
            edge = not bounded and bool(self.near[(i - 1) % n] or self.near[(i + 1) % n])
            peak = CurvePeak(name, unit, float(values[i]), float(deg[i]), at_band_edge=edge)
            close = self.near & finite
            if not bounded and close.any():
                j = int(np.flatnonzero(close)[np.argmax(np.abs(values[close]))])
                if abs(values[j]) > abs(values[i]):
                    dead = min(self.dead_point_angles(), key=lambda d: _gap(d, deg[j]))
                    peak = dataclasses.replace(peak, near_value=float(values[j]),
                                               near_at_deg=float(deg[j]), dead_point_deg=dead)
            out.append(peak)
        return tuple(out)


def _gap(a: float, b: float) -> float:
    return abs((a - b + 180.0) % 360.0 - 180.0)


def ratio_names(outputs: tuple[str, ...]) -> list[tuple[str, int | None, int]]:
    """(name, numerator's... ) of each ratio: every output over the input (T[o]/T_in), and
    each output over the one before it (T[o2]/T[o1]); the index None is the input."""
    out = [(f"T[{o}]/T_in", None, i) for i, o in enumerate(outputs)]
    out += [(f"T[{outputs[i + 1]}]/T[{outputs[i]}]", i, i + 1) for i in range(len(outputs) - 1)]
    return out


def output_study(scene: Scene, speed: float = 0.0, crank_acceleration: float = 0.0,
                 poses: int = 360, spec: KinetostaticsSpec | None = None,
                 progress=None, cycle=None, masses=None) -> OutputCurve:
    """Output torques of ``scene`` at ``poses`` crank angles over one turn, at crank speed
    ``speed`` [rad/s] (0: at rest) and ``crank_acceleration`` [rad/s^2], for the input torque,
    outputs and losses of ``spec`` (default: the scene's [kinetostatics]). ``cycle`` and
    ``masses`` may be passed in when a study repeats this over other inputs."""
    check_speed(speed, crank_acceleration)
    if not speed >= 0:
        raise InputError(f"got {speed!r} rad/s", source="command line", field="--speed",
                         expected="a speed >= 0 (the crank turns counter-clockwise)")
    spec = spec or scene.kinetostatics
    if spec is None:
        raise InputError("no input torque: give [kinetostatics] input_torque and outputs in the "
                         "scene, or --input-torque and --output", source=scene.path,
                         field="kinetostatics")
    linkage = scene.linkage
    cycle = cycle if cycle is not None else kinematic_cycle(scene, poses, progress)
    masses = masses if masses is not None else scene_masses(scene)
    outs = spec.transmission.outputs
    cols = [cycle.column(o.body) for o in outs]
    rows, t_in = [], []
    for state in cycle.states:
        tau = float(_value(spec.input_torque, state.q))
        loads = [wrench(linkage, state, load) for load in scene.loads]
        t_in.append(tau)
        rows.append(output_torques(linkage, state, speed, masses, tau, spec.transmission,
                                   spec.losses, loads, crank_acceleration))
    t_in = np.array(t_in)
    torques = np.array([r.torques for r in rows])
    K = cycle.K[:, cols]
    dead = tuple(DeadPoint(o.body, p.crank_deg) for o in outs
                 for p in limit_positions(linkage, cycle, o.body))
    near = np.any(np.abs(K) < DEAD_BAND * np.abs(K).max(axis=0), axis=1)
    near |= ~np.all(np.isfinite(torques), axis=1)
    ratios = {}
    with np.errstate(divide="ignore", invalid="ignore"):
        for name, a, b in ratio_names(tuple(o.body for o in outs)):
            den = t_in if a is None else torques[:, a]
            ratios[name] = np.where(den != 0, torques[:, b] / den, np.nan)
    keys = [k for k in rows[0].forces if _reported(linkage, *k)]
    forces = {f"{j}:{b}": np.array([r.forces[(j, b)] for r in rows]) for j, b in keys}
    return OutputCurve(
        scene=scene.name, speed=float(speed), crank_acceleration=float(crank_acceleration),
        transmission=spec.transmission, losses=spec.losses, q=cycle.q, input_torque=t_in,
        torques=torques, received=np.array([r.received for r in rows]), K=K, ratios=ratios,
        friction_torque=np.array([r.friction_torque for r in rows]),
        loss_power=np.array([r.loss_power for r in rows]),
        kinetic_energy=np.array([r.kinetic_energy for r in rows]),
        load_power=np.array([r.load_power for r in rows]), forces=forces, near=near,
        dead_points=dead, masses=tuple(masses))


def _value(load: LoadSpec, q: float) -> float:
    return float(load.value_at(q)[0])


def _reported(linkage, joint: str, body: str) -> bool:
    """A force worth a column: at a ground pivot (the ground's reaction, negated), or on each
    body after the first that carries a pin (the first's is minus the sum of the others)."""
    if joint in linkage.ground:
        return True
    carriers = [b.name for b in linkage.bodies if joint in b.joints]
    return len(carriers) > 1 and body != carriers[0]


def with_inputs(spec: KinetostaticsSpec, input_torque: LoadSpec | None = None,
                friction: float | None = None, efficiency: float | None = None,
                source: str = "command line") -> KinetostaticsSpec:
    """``spec`` with the command line's input torque, m and eta in place of the scene's."""
    losses = spec.losses
    if friction is not None or efficiency is not None:
        losses = Losses(losses.friction if friction is None else friction,
                        losses.efficiency if efficiency is None else efficiency, source=source)
    return dataclasses.replace(spec, input_torque=input_torque or spec.input_torque,
                               losses=losses)


def crank_deg(q) -> np.ndarray:
    """Crank angles [deg, 0..360) of ``q`` [rad]."""
    return np.degrees(np.asarray(q)) % 360.0


def angle_index(curve: OutputCurve, deg: float) -> int:
    """The sample nearest the crank angle ``deg``."""
    return int(np.argmin([_gap(d, deg) for d in crank_deg(curve.q)]))

