"""The two model formulations of a linkage lying in one plane, behind one interface:
"in-plane" (frame elements, ``model.py``, ``assembly.py``) and "out-of-plane" (strip bending
and torsion, ``strip.py``). For doubly symmetric sections the two sets of motions decouple to
first order, so each is an eigenproblem of its own on the same mesh.

A ``Formulation`` says, for its part: the three DOF names per node, how joints act on them
(``joints.JointDofs``; the joint-to-spring building itself is ``joints.springs_of_joints``,
one for both), which DOFs carry a lumped joint mass and which are rotations, the model at a
pose, its element and mass entries, its eigenvalue and element stiffness scales, and the
quadratic forms s^T K s, s^T M s of shapes. ``FORMULATIONS`` maps each part's name to its formulation.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping

import numpy as np

from flexlink.fe.assembly import (node_rotation, placed_link_entries, rotated_entries,
                                  springs_stiffness_entries)
from flexlink.fe.beams import link_entries
from flexlink.fe.joints import JointDofs, Springs, joint_mass_entries, springs_of_joints
from flexlink.fe.model import DOF_NAMES as FRAME_DOFS
from flexlink.fe.motions import Part
from flexlink.fe.model import IN_PLANE_JOINTS, FrameModel, Topology, in_plane_stiffness, layout
from flexlink.fe.model_at_pose import in_plane_eigen_scale, pose_model
from flexlink.fe.rigid import element_stiffness_scale, rigidified
from flexlink.fe.strip import DOF_NAMES as STRIP_DOFS
from flexlink.fe.strip import (OUT_OF_PLANE_JOINTS, StripProperties, link_strips,
                               out_of_plane_eigen_scale, out_of_plane_stiffness, strip_entries,
                               strip_element_matrices, strip_node_rotation,
                               strip_stiffness_scale)

Tilt = Mapping[str, float]  # Ktilt [N m/rad] per joint (the scene's ``options.tilt``)


@dataclasses.dataclass(frozen=True)
class Formulation:
    """One part of a linkage's small vibrations (see the module docstring).

    part: its name; dof_names: the three DOFs of a node, in order; joints: how joints act on
    them; joint_stiffness(joint, tilt): a joint's bearing stiffness on each DOF [N/m or
    N m/rad]; mass_dofs: node DOFs a lumped joint mass [kg] acts on; rotational_dofs: node DOFs
    that are rotations; rotation(angle): R with local = R @ global per node; model(topology,
    points, tilt): the model at joint positions [m], very stiff springs made rigid;
    eigen_scale(model): the eigenvalue scale [rad^2/s^2] below which modes are rigid-body;
    stiffness_scale(model): (translational, rotational) stiffness of its stiffest element;
    element_entries(model): (rows, cols, values (2, e) = K and M) in global DOFs;
    link_forms(model, shapes): per shape, the links' s^T K s and s^T M s."""

    part: Part
    dof_names: tuple[str, str, str]
    joints: JointDofs
    joint_stiffness: Callable[[object, Tilt], tuple[float, float, float]]
    mass_dofs: tuple[int, ...]
    rotational_dofs: tuple[int, ...]
    rotation: Callable[[float], np.ndarray]
    model: Callable[[Topology, Mapping, Tilt], FrameModel]
    eigen_scale: Callable[[FrameModel], float]
    stiffness_scale: Callable[[FrameModel], tuple[float, float]]
    element_entries: Callable[[FrameModel], tuple]
    link_forms: Callable[[FrameModel, np.ndarray], tuple[np.ndarray, np.ndarray]]

    def springs(self, topology: Topology, tilt: Tilt) -> Springs:
        """The joint and drive springs of ``topology`` as the scene sets them (none made rigid
        yet), in the order of its models' springs."""
        lay = layout(topology)
        return springs_of_joints(topology, lay.joint_nodes, lay.first_nodes, self.joints,
                             lambda joint: self.joint_stiffness(joint, tilt))

    def mass_entries(self, model: FrameModel):
        """(rows, cols, values [kg]) of the lumped joint masses on ``mass_dofs``."""
        return joint_mass_entries(model.point_masses, self.mass_dofs)

    def quadratic_forms(self, model: FrameModel, shapes: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray]:
        """(s^T K s, s^T M s) for each column s of ``shapes`` (model.n_dofs, k) on this part's
        K and M of ``model`` (finite springs only: rigid ones are constraints the shapes obey)."""
        q_K, q_M = self.link_forms(model, shapes)
        rows, cols, vals = springs_stiffness_entries(model.springs)
        q_K = q_K + (vals[:, None] * shapes[rows] * shapes[cols]).sum(axis=0)
        m_rows, m_cols, m_vals = self.mass_entries(model)
        q_M = q_M + (m_vals[:, None] * shapes[m_rows] * shapes[m_cols]).sum(axis=0)
        return q_K, q_M


def _link_chains(model: FrameModel, shapes: np.ndarray, rotation):
    """Per link: its nodes' shape entries in the link frame, (nodes, 3, k). Each link's
    element entries act on these as they are (every node belongs to one link), so the forms
    need a ninth of the rotated entries the assembly sums."""
    for link in model.links:
        nodes = link.nodes
        block = shapes[3 * nodes[0]:3 * nodes[-1] + 3].reshape(len(nodes), 3, -1)
        yield link, np.einsum("ij,njk->nik", rotation(link.angle), block)


def _frame_link_forms(model: FrameModel, shapes: np.ndarray):
    q_K, q_M = np.zeros(shapes.shape[1]), np.zeros(shapes.shape[1])
    for link, chain in _link_chains(model, shapes, node_rotation):
        rows, cols, k, m = link_entries(link.length, link.elements, link.section)
        flat = chain.reshape(-1, shapes.shape[1])
        q_K += (k[:, None] * flat[rows] * flat[cols]).sum(axis=0)
        q_M += (m[:, None] * flat[rows] * flat[cols]).sum(axis=0)
    return q_K, q_M


def _strip_link_forms(model: FrameModel, shapes: np.ndarray):
    strips = link_strips(model)
    props = StripProperties(*(np.array([getattr(p, f.name) for p in strips])
                              for f in dataclasses.fields(StripProperties)))
    k_links, m_links = strip_element_matrices(
        np.array([link.length / link.elements for link in model.links]), props)
    q_K, q_M = np.zeros(shapes.shape[1]), np.zeros(shapes.shape[1])
    for index, (_link, chain) in enumerate(_link_chains(model, shapes, strip_node_rotation)):
        pairs = np.concatenate([chain[:-1], chain[1:]], axis=1).transpose(2, 0, 1)  # (k, e, 6)
        q_K += ((pairs @ k_links[index]) * pairs).sum(axis=(1, 2))
        q_M += ((pairs @ m_links[index]) * pairs).sum(axis=(1, 2))
    return q_K, q_M


def _strip_model(topology: Topology, points: Mapping, tilt: Tilt) -> FrameModel:
    """The planar mesh with the out-of-plane joint springs; a spring stiff enough to spoil
    K's round-off, judged against the strip elements' own stiffness, made an exact
    constraint."""
    planar = pose_model(topology, points, warn=False)  # its mesh; its springs are replaced
    strip = OUT_OF_PLANE_FORMULATION
    springs = strip.springs(topology, tilt)
    return rigidified(dataclasses.replace(planar, springs=springs),
                      scales=strip.stiffness_scale(planar),
                      rotational=np.isin(springs.dof_a % 3, strip.rotational_dofs))


IN_PLANE_FORMULATION = Formulation(
    part=Part.IN_PLANE, dof_names=FRAME_DOFS, joints=IN_PLANE_JOINTS,
    joint_stiffness=lambda joint, tilt: in_plane_stiffness(joint),
    mass_dofs=(0, 1), rotational_dofs=(2,), rotation=node_rotation,
    model=lambda topology, points, tilt: pose_model(topology, points, warn=False),
    eigen_scale=in_plane_eigen_scale, stiffness_scale=element_stiffness_scale,
    element_entries=lambda model: rotated_entries(*placed_link_entries(model)),
    link_forms=_frame_link_forms)

OUT_OF_PLANE_FORMULATION = Formulation(
    part=Part.OUT_OF_PLANE, dof_names=STRIP_DOFS, joints=OUT_OF_PLANE_JOINTS,
    joint_stiffness=out_of_plane_stiffness,
    mass_dofs=(0,), rotational_dofs=(1, 2), rotation=strip_node_rotation,
    model=_strip_model, eigen_scale=out_of_plane_eigen_scale,
    stiffness_scale=strip_stiffness_scale,
    element_entries=lambda model: strip_entries(model, link_strips(model)),
    link_forms=_strip_link_forms)

FORMULATIONS = {f.part: f for f in (IN_PLANE_FORMULATION, OUT_OF_PLANE_FORMULATION)}
