"""Joints as spring elements, written once for every formulation (in-plane frame, out-of-plane
strip): which node DOFs a joint ties, to what, and how stiffly.

Every link has its own chain of nodes, so the links meeting at a joint have coincident end
nodes, listed in link order. A formulation names its three DOFs per node and gives, per joint,
the bearing stiffness of each; the springs are then:
  - a pin (or bearing) between links: a spring per DOF from each attached node to the first;
  - a ground bearing: a spring per DOF from each attached node to the ground;
  - a ``welded`` ground joint (its links are one body turning in one bearing): every DOF of the
    other nodes tied rigidly to the first node, and the bearing springs on the first node only;
  - the drive, where the formulation has one: a spring on the driven link's node to ground.
A zero stiffness adds no spring; ``inf`` is an exact constraint (``assembly.rigid_elimination``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from flexlink.errors import InputError

GROUND = -1


@dataclasses.dataclass(frozen=True)
class JointDofs:
    """How a formulation's joints act on a node's three DOFs.

    bearing_labels, weld_labels: per node DOF, the label suffix of its bearing spring and of
    its weld; drive_dof: the node DOF the drive holds (None: the drive has no part here)."""

    bearing_labels: tuple[str, str, str]
    weld_labels: tuple[str, str, str]
    drive_dof: int | None


@dataclasses.dataclass(frozen=True)
class Springs:
    """Spring elements as arrays: DOFs ``dof_a`` and ``dof_b`` (GROUND = -1), stiffness
    [N/m or N m/rad], and a label each."""

    dof_a: np.ndarray
    dof_b: np.ndarray
    stiffness: np.ndarray
    labels: tuple[str, ...]


def springs_of_joints(topology, joint_nodes: Mapping[str, Sequence[int]],
                  first_nodes: Sequence[int], dofs: JointDofs,
                  stiffness: Callable[[object], tuple[float, float, float]]) -> Springs:
    """The springs of every joint of ``topology`` (``model.Topology``) and of its drive.

    ``joint_nodes``: joint name -> the attached link-end nodes, in link order; ``first_nodes``:
    each link's first node; ``stiffness(joint)``: the joint's bearing stiffness on each of the
    formulation's three node DOFs. Arrays are read-only (models of one topology share them)."""
    dof_a, dof_b, k, labels = [], [], [], []

    def spring(a_node, b_node, dof, value, label):
        if value == 0.0:
            return
        dof_a.append(3 * a_node + dof)
        dof_b.append(GROUND if b_node == GROUND else 3 * b_node + dof)
        k.append(value)
        labels.append(label)

    for joint in topology.joints:
        attached = list(joint_nodes[joint.name])
        partners = [GROUND] * len(attached) if joint.ground else [attached[0]] * len(attached)
        if joint.welded:
            for node in attached[1:]:
                for dof, name in enumerate(dofs.weld_labels):
                    spring(node, attached[0], dof, math.inf, f"{joint.name} weld {name}")
            attached, partners = attached[:1], partners[:1]
        values = stiffness(joint)
        for node, other in zip(attached, partners):
            if node == other:
                continue
            for dof, (name, value) in enumerate(zip(dofs.bearing_labels, values)):
                spring(node, other, dof, value, f"{joint.name} {name}")
    if topology.drive is not None and dofs.drive_dof is not None:
        drive = topology.drive
        node = drive_node(topology, first_nodes)
        spring(node, GROUND, dofs.drive_dof, drive.stiffness, f"drive {drive.link}@{drive.joint}")

    arrays = (np.asarray(dof_a, dtype=np.int64), np.asarray(dof_b, dtype=np.int64),
              np.asarray(k, dtype=float))
    for array in arrays:
        array.flags.writeable = False
    return Springs(*arrays, tuple(labels))


def spring_energies(springs: Springs, shapes: np.ndarray) -> np.ndarray:
    """k (s_a - s_b)^2, twice the energy [J per unit shape^2] of each spring in each shape:
    (springs, k) for ``shapes`` (n_dofs, k), s_b = 0 for a spring to ground; 0 for a rigid
    spring (an exact constraint, which the shapes obey)."""
    padded = np.vstack([shapes, np.zeros((1, shapes.shape[1]))])  # GROUND (-1) -> 0
    finite = np.isfinite(springs.stiffness)
    k = np.where(finite, springs.stiffness, 0.0)
    return k[:, None] * (padded[springs.dof_a] - padded[springs.dof_b]) ** 2


def joint_mass_entries(point_masses, dofs: Sequence[int]):
    """(rows, cols, values [kg]) of lumped joint masses ((node, mass) pairs) on the node
    DOFs ``dofs``: a diagonal entry per mass and DOF."""
    nodes = np.array([node for node, _ in point_masses], dtype=np.int64)
    mass = np.array([m for _, m in point_masses], dtype=float)
    idx = np.concatenate([3 * nodes + dof for dof in dofs])
    return idx, idx, np.concatenate([mass] * len(dofs))


def drive_node(topology, first_nodes: Sequence[int]) -> int:
    """The node the drive holds: the driven link's end at the drive's joint."""
    drive = topology.drive
    index = next((i for i, s in enumerate(topology.links) if s.name == drive.link), None)
    if index is None:
        raise InputError(f"drive names link {drive.link!r}, which is not defined",
                         field="drive.link")
    spec = topology.links[index]
    if drive.joint not in (spec.start, spec.end):
        raise InputError(f"drive joint {drive.joint!r} is not an end of link {drive.link!r}",
                         field="drive.joint")
    return first_nodes[index] + (0 if drive.joint == spec.start else spec.elements)
