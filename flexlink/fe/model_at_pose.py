"""The one way a pose becomes a FrameModel, used by every driver (modes, export, sweeps,
Craig-Bampton, out-of-plane, PRB comparison, stability checks).

A topology (links with their mesh, joints with springs and masses, the drive) meshed between
the pose's joint positions, with every spring stiff enough to spoil K's round-off turned into
an exact constraint (``rigid.rigidified``). Joint masses and the drive spring come from the
topology's layout (``model.build_model``), so they are the same in every driver.
"""

from __future__ import annotations

from collections.abc import Mapping

from flexlink.fe.model import FrameModel, Topology, _Layout, build_model
from flexlink.fe.rigid import rigidified


def pose_model(topology: Topology, points: Mapping[str, tuple[float, float]],
               known_layout: _Layout | None = None, warn: bool = True) -> FrameModel:
    """The FrameModel of ``topology`` with its joints at ``points`` [m] (joint name -> (x, y)).

    ``known_layout``: ``model.layout(topology)``, for callers looping over poses; ``warn``: log
    the springs made rigid (a sweep does so at its first pose only)."""
    return rigidified(build_model(topology, points, known_layout), warn=warn)


def in_plane_eigen_scale(model: FrameModel) -> float:
    """The model's own in-plane eigenvalue scale [rad^2/s^2]: the smallest EI / (rhoA L^4) of
    its links.

    A link's lowest bending eigenvalue is this times a constant of order 10 to 500, so modes
    many orders of magnitude below it are rigid-body or mechanism modes."""
    return min(l.section.EI / (l.section.mass_per_length * l.length**4) for l in model.links)
