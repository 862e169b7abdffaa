"""The rigid-motion study of a scene over one crank revolution: every body's angle, velocity
coefficient K and its derivative L, limit positions, swing and time ratio of rockers, torque
ratio, transmission angles; and the same for every member of the scene's [[family]] tables."""

from __future__ import annotations

import math

from flexlink.kinematics.linkage import Cycle
from flexlink.kinematics.motion import body_summary, extremes, limit_positions
from flexlink.scene import Scene
from flexlink.scene import load_scene
from flexlink.studies.cycle import kinematic_cycle, transmission_angles


def time_ratio(limits: list[dict]) -> float:
    """Crank turn [deg] from the first limit position to the second over the turn back (>= 1)."""
    a, b = limits[0]["crank_deg"], limits[1]["crank_deg"]
    forward = (b - a) % 360.0
    return max(forward, 360.0 - forward) / min(forward, 360.0 - forward)


def motion_study(scene: Scene, poses: int, crank_speed: float | None,
                 progress=None) -> tuple[Cycle, dict]:
    """The cycle at ``poses`` crank angles and its JSON-ready summary: per body the extremes
    (``motion.body_summary``; omega [rad/s] and alpha [rad/s^2] given ``crank_speed``
    [rad/s]), and for a body turning about a ground pivot its limit positions [deg], swing
    [deg] and time ratio; the transmission angles' extremes [deg]."""
    cycle = kinematic_cycle(scene, poses, progress)
    linkage = scene.linkage
    bodies = {}
    for b in linkage.bodies:
        output = b.name != linkage.driver and b.joints[0] in linkage.ground
        bodies[b.name] = summary = body_summary(cycle, b.name, crank_speed, output)
        limits = limit_positions(linkage, cycle, b.name) if output else []
        if limits:
            summary["limit_positions"] = limits
            angles = [lim["angle_deg"] for lim in limits]
            summary["swing_deg"] = max(angles) - min(angles)
            if len(limits) == 2:
                summary["time_ratio"] = time_ratio(limits)
    mu = {k: extremes(cycle.q, v * 180 / math.pi)
          for k, v in transmission_angles(scene, cycle).items()}
    return cycle, {"scene": scene.name, "synthesis": scene.synthesis, "bodies": bodies,
                   "transmission_angle_deg": mu}


def variant_studies(scene_path, scene: Scene, poses: int,
                    crank_speed: float | None) -> list[dict]:
    """``motion_study`` of every variant the scene's [[family]] tables declare (the scene file
    reloaded with ``field = value``), tagged with the variant's name (under the scene key's
    word, "family"), field and value."""
    members = []
    for variant in scene.options.variants:
        field, label = variant.field, variant.name
        for value in variant.values:
            member = load_scene(scene_path, overrides={field: value})
            _, doc = motion_study(member, poses, crank_speed)
            members.append({**doc, "family": label, "field": field, "value": value})
    return members
