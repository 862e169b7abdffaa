"""How crank speed, input torque and the contact-friction factor m change the transmission
ratios, one factor at a time about the scene's own case (its input torque, m and eta, at rest
unless the scene runs at a speed), as the wiper paper varies them; and the bearing efficiency
eta, to show its effect beside m's.

Each ratio is summarised over the turn by its median |value| over the samples away from the
dead points (the ratios are unbounded next to them and change sign with the outputs' sense,
so neither a peak nor a mean says what a factor does). A factor's plain effect size is the
spread of that median over the factor's range relative to its value at the base case, in
percent: a factor matters for a ratio where the spread reaches ``MATTERS`` percent. An input
torque of 0 leaves the ratios to the input undefined (0/0 at rest, inertia/0 at speed), and
the ratio between two outputs then describes only the links' inertia, not a transmission:
such a level shows no ratio and is left out of the spread.
"""

from __future__ import annotations

import dataclasses
import enum
import math

import numpy as np

from flexlink.kinematics.kinetostatics import Losses
from flexlink.scene import Scene
from flexlink.scene.contract import LoadKind, LoadSpec
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.modal_map import kinematic_cycle
from flexlink.studies.kinetostatics.outputs import output_study
from flexlink.studies.running.torque import scene_masses
from flexlink.units import RPM, rev_per_min

MATTERS = 1.0  # [%] spread of a ratio's median over a factor's range that counts as an effect
SPEEDS_RPM = (0.0, 500.0, 1000.0, 1500.0, 2000.0, 2500.0, 3000.0)
TORQUES_N_M = (0.0, 200.0, 400.0, 600.0, 800.0, 1000.0)
FRICTIONS = (0.0, 0.15, 0.3, 0.45, 0.6, 0.75, 0.9)
EFFICIENCIES = (0.6, 0.7, 0.8, 0.9, 1.0)  # not among the paper's factors: eta's effect shown


class Factor(enum.StrEnum):
    SPEED = "crank speed"
    TORQUE = "input torque"
    FRICTION = "friction m"
    EFFICIENCY = "efficiency eta"


UNITS = {Factor.SPEED: "rev/min", Factor.TORQUE: "N m", Factor.FRICTION: "-",
         Factor.EFFICIENCY: "-"}


@dataclasses.dataclass(frozen=True)
class FactorSweep:
    """One factor's levels (in ``UNITS``) and, per ratio name, the median |ratio| over the
    turn away from the dead points at each level (NaN where undefined); ``effect`` per ratio:
    the spread over the levels relative to the base case [%]."""

    factor: Factor
    levels: np.ndarray
    medians: dict[str, np.ndarray]
    effect: dict[str, float]

    def __post_init__(self):
        for name, m in self.medians.items():
            check_shape("FactorSweep", f"medians[{name}]", m, (len(self.levels),))


@dataclasses.dataclass(frozen=True)
class ParametricStudy:
    """The base case (speed [rev/min], input torque [N m], m, eta), its medians, and one
    ``FactorSweep`` per factor."""

    scene: str
    base_speed_rpm: float
    base_torque: float
    base_friction: float
    efficiency: float
    base: dict[str, float]
    sweeps: tuple[FactorSweep, ...]
    matters_percent: float = MATTERS


def _medians(curve) -> dict[str, float]:
    regular = ~curve.near
    out = {}
    for name, r in curve.ratios.items():
        v = np.abs(r[regular & np.isfinite(r)])
        out[name] = float(np.median(v)) if v.size else math.nan
    return out


def parametric_study(scene: Scene, speed: float = 0.0, poses: int = 120,
                     progress=None) -> ParametricStudy:
    """The one-factor-at-a-time study of ``scene`` about its [kinetostatics] case at crank
    speed ``speed`` [rad/s], ``poses`` crank angles per turn (see the module doc)."""
    spec = scene.kinetostatics
    cycle = kinematic_cycle(scene, poses)
    masses = scene_masses(scene)
    base_torque = float(np.mean(spec.input_torque.values))

    def run(omega, torque=None, friction=None, efficiency=None):
        s = spec
        if torque is not None:
            s = dataclasses.replace(s, input_torque=LoadSpec(
                LoadKind.TORQUE, spec.input_torque.body, np.array([[torque]])))
        if friction is not None or efficiency is not None:
            s = dataclasses.replace(s, losses=Losses(
                spec.losses.friction if friction is None else friction,
                spec.losses.efficiency if efficiency is None else efficiency,
                spec.losses.source))
        medians = _medians(output_study(scene, omega, spec=s, cycle=cycle, masses=masses))
        if torque == 0:  # no input: nothing is transmitted, so no ratio describes a transmission
            medians = dict.fromkeys(medians, math.nan)
        return medians

    base = run(speed)
    plan = [(Factor.SPEED, SPEEDS_RPM, lambda v: run(v * RPM)),
            (Factor.TORQUE, TORQUES_N_M, lambda v: run(speed, torque=v)),
            (Factor.FRICTION, FRICTIONS, lambda v: run(speed, friction=v)),
            (Factor.EFFICIENCY, EFFICIENCIES, lambda v: run(speed, efficiency=v))]
    steps = [(f, v, fn) for f, levels, fn in plan for v in levels]
    results = {}
    for f, v, fn in (progress(steps) if progress else steps):
        results[(f, v)] = fn(v)
    sweeps = []
    for f, levels, _ in plan:
        medians = {name: np.array([results[(f, v)][name] for v in levels]) for name in base}
        effect = {}
        for name, m in medians.items():
            ok = m[np.isfinite(m)]
            effect[name] = (float(100 * (ok.max() - ok.min()) / abs(base[name]))
                            if ok.size and base[name] else math.nan)
        sweeps.append(FactorSweep(f, np.array(levels, float), medians, effect))
    return ParametricStudy(scene=scene.name, base_speed_rpm=rev_per_min(speed),
                           base_torque=base_torque, base_friction=spec.losses.friction,
                           efficiency=spec.losses.efficiency, base=base, sweeps=tuple(sweeps))
