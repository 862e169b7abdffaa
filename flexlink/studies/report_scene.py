"""What the HTML report shows of one scene beyond its summary: the modal map over the crank
cycle, and for a scene that declares an operating speed the driving torque over the cycle and
the modes at its pose from rest to that speed; for each, why there is none when it could not be
made (a linkage that cannot turn a full cycle still gets its page)."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.errors import FlexlinkError
from flexlink.scene import Scene, load_scene
from flexlink.studies.array_shapes import check_shape
from flexlink.studies.cycle.modal_map import ModalMap, modal_map
from flexlink.studies.kinetostatics.outputs import OutputCurve, output_study
from flexlink.studies.cycle.rigid_motion import MotionStudy, motion_study
from flexlink.studies.life.life import LifeStudy, check_strengths, life_study
from flexlink.studies.life.stress_field import stress_field, stress_model
from flexlink.studies.running.modes_at_speed import OperatingPoint, operating_modes
from flexlink.studies.pose.scene_summary import SceneSummary, SensitivityRun, scene_summary
from flexlink.studies.running.steady_response import ForcedModel, SteadyResponse, forced_model, steady_response
from flexlink.studies.running.torque import TorqueCurve, torque_study

KINEMATIC_POSES = 120  # crank angles of a kinematics-only scene's motion without a cycle map
SPEED_STEPS = 11  # crank speeds from rest to the operating speed in the frequency diagram
TORQUE_POSES = 72
OUTPUT_POSES = 360  # output torques over the turn: 1-degree steps, to show the dead points


@dataclasses.dataclass(frozen=True)
class AtSpeed:
    """A scene at its declared operating ``speed`` [rad/s] and ``crank_acceleration``
    [rad/s^2]: the driving ``torque`` over the cycle, and the operating ``points`` at the
    scene's pose at ``speeds`` [rad/s] from rest to the operating speed, each with that
    acceleration; where either could not be made, None (no points) and the reason. ``response``:
    the steady elastic response at the speed (``steady_response``, its ``forced`` model giving
    the strain points), or the reason in ``response_unavailable``."""

    speed: float
    crank_acceleration: float
    torque: TorqueCurve | None
    torque_unavailable: str | None
    speeds: np.ndarray
    points: tuple[OperatingPoint, ...]
    points_unavailable: str | None = None
    forced: ForcedModel | None = None
    response: SteadyResponse | None = None
    response_unavailable: str | None = None

    def __post_init__(self):
        check_shape("AtSpeed", "speeds", self.speeds, (SPEED_STEPS,))
        if (self.torque is None) == (self.torque_unavailable is None):
            raise ValueError("AtSpeed needs a torque curve or the reason there is none, "
                             "expected exactly one")
        if self.points_unavailable is None and len(self.points) != SPEED_STEPS:
            raise ValueError(f"AtSpeed has {len(self.points)} operating points, expected one "
                             f"per speed ({SPEED_STEPS}) or the reason there are none")


def at_speed(scene: Scene, n_modes: int, elements_per_link: int) -> AtSpeed | None:
    """``scene`` at its declared operating point ([operation] crank_speed, and
    crank_acceleration, 0 if not given) on
    ``elements_per_link``, its lowest ``n_modes`` modes; None when it declares no speed."""
    speed = scene.options.crank_speed
    if speed is None:
        return None
    acc = scene.options.crank_acceleration or 0.0
    speeds = np.linspace(0.0, speed, SPEED_STEPS)
    torque, torque_unavailable = None, None
    try:
        torque = torque_study(scene, speed, acc, poses=TORQUE_POSES)
    except FlexlinkError as exc:
        torque_unavailable = str(exc)
    forced, response, response_unavailable = None, None, None
    try:  # six modes: the stability map's default basis request
        forced = forced_model(scene, n_modes=6, elements_per_link=elements_per_link)
        response = steady_response(forced, speed)
    except FlexlinkError as exc:
        response_unavailable = str(exc)
    response_parts = dict(forced=forced, response=response,
                          response_unavailable=response_unavailable)
    try:
        points = tuple(operating_modes(scene, w, n_modes, elements_per_link, crank_acceleration=acc)
                       for w in speeds)
    except FlexlinkError as exc:
        return AtSpeed(speed, acc, torque, torque_unavailable, speeds, (), str(exc),
                       **response_parts)
    return AtSpeed(speed, acc, torque, torque_unavailable, speeds, points, **response_parts)


@dataclasses.dataclass(frozen=True)
class ReportScene:
    """One scene of the report: its ``summary`` (the planar modes, with a note for another
    family), its ``cycle`` map (None when none was asked for or it could not be made) and
    ``cycle_unavailable``, the reason it could not; ``at_speed``: the scene at its operating
    speed, None when it declares none; ``kinetostatics``: the output torques for the input
    torque the scene declares (None without one; ``kinetostatics_unavailable``: why not)."""

    summary: SceneSummary | None
    cycle: ModalMap | None
    cycle_unavailable: str | None = None
    at_speed: AtSpeed | None = None
    life: LifeStudy | None = None  # stress and life at the operating speed (``life_at_speed``)
    life_unavailable: str | None = None
    kinetostatics: OutputCurve | None = None  # for a scene declaring an input torque
    kinetostatics_unavailable: str | None = None
    motion: MotionStudy | None = None  # a scene without beams: its rigid motion instead

    def __post_init__(self):
        if self.cycle is not None and self.cycle_unavailable is not None:
            raise ValueError("ReportScene has a cycle map and a reason it is unavailable, "
                             "expected at most one")
        if (self.summary is None) == (self.motion is None):
            raise ValueError("ReportScene needs a summary of the modes or, for a scene "
                             "without beams, its rigid motion, expected exactly one")


def report_scene(path, n_modes: int, elements: int | None, tol: float | None, solver,
                 cycle_poses: int, sensitivity: SensitivityRun | None = None) -> ReportScene:
    """The scene file at ``path`` summarised (``scene_summary``, its in-plane modes) with its
    modal map over ``cycle_poses`` crank angles (none for 0) and its operating speed, on the
    same mesh."""
    own = load_scene(path)
    if not own.links:  # kinematics only: what the page can show is the rigid motion
        poses = cycle_poses or KINEMATIC_POSES
        return ReportScene(None, None, motion=motion_study(own, poses, own.options.crank_speed))
    summary = scene_summary(path, n_modes, elements, tol, solver, in_plane_only="this page",
                            sensitivity=sensitivity)
    scene, elements = summary.case.scene, summary.mesh.elements
    cycle, unavailable = None, None
    try:
        cycle = modal_map(scene, cycle_poses, n_modes, elements) if cycle_poses else None
    except FlexlinkError as exc:
        unavailable = str(exc)
    life, life_unavailable = life_at_speed(scene, elements)
    outputs, outputs_unavailable = None, None
    if scene.kinetostatics is not None:
        try:
            outputs = output_study(scene, scene.options.crank_speed or 0.0, poses=OUTPUT_POSES)
        except FlexlinkError as exc:
            outputs_unavailable = str(exc)
    return ReportScene(summary, cycle, unavailable, at_speed(scene, n_modes, elements), life,
                       life_unavailable, kinetostatics=outputs,
                       kinetostatics_unavailable=outputs_unavailable)


def life_at_speed(scene: Scene, elements_per_link: int) -> tuple[LifeStudy | None, str | None]:
    """Each link's stress and life at the scene's operating speed (``studies.life``, its
    default conditions), or (None, the reason) where it cannot be made; (None, None) for a
    scene that declares no speed or whose materials give no strength data."""
    if scene.options.crank_speed is None:
        return None, None
    try:
        check_strengths(scene)
    except FlexlinkError:
        return None, None
    try:
        model = stress_model(scene, elements_per_link=elements_per_link)
        field = stress_field(model, scene.options.crank_speed)
        return life_study(scene, model, field), None
    except FlexlinkError as exc:
        return None, str(exc)
