"""What each mode is: where its strain and kinetic energy sit, a short label, and its effective
modal mass for ground motion in x and y.

Energy parts are the links (strain split into axial and bending) and the joints (their
translational springs Kt, their torsional spring Kr, the drive spring, and for kinetic energy
their lumped mass). Each mode's strain parts and its kinetic parts each sum to 1: they are the
parts of u^T K u and u^T M u (consistent mass), computed link by link in the link frame with
the element matrices of ``fe/link.py``, and spring by spring.

Effective modal mass for ground motion in direction d (x or y): with r_d the rigid translation
of every DOF not fixed to the ground (u = T q, so grounded DOFs stay put: the mass on them moves
with the ground and does not take part), Gamma = u^T M r_d for a mass-normalised mode u, and
m_eff = Gamma^2 [kg]. Over all modes of the model these sum to r_d^T M r_d, the participating
mass (``participating_mass``): the whole mass of the model when no joint is rigidly grounded.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.joints import spring_energies
from flexlink.fe.model import FrameModel

DIRECTIONS = ("x", "y")
DOMINANT = 0.5  # a part holding at least this strain-energy fraction names the mode
NAMED_JOINT = 0.2  # a joint named in a joint-spring label holds at least this much


@dataclasses.dataclass(frozen=True)
class EnergyParts:
    """Per part (``names``) and mode: the part's share of u^T K u (twice the strain energy) and
    of u^T M u (twice the kinetic energy over omega^2), in the units of the shapes given; and
    the axial share of each link's strain (the rest is bending), or the translational (Kt)
    share of each joint's (the rest is Kr and the drive)."""

    names: tuple[str, ...]
    is_link: tuple[bool, ...]
    strain: np.ndarray  # (parts, k)
    kinetic: np.ndarray  # (parts, k)
    axial: np.ndarray  # (parts, k): the axial (links) or translational (joints) share of strain

    def fractions(self) -> tuple[np.ndarray, np.ndarray]:
        """(strain, kinetic) fractions (parts, k), each column summing to 1."""
        return self.strain / self.strain.sum(axis=0), self.kinetic / self.kinetic.sum(axis=0)


def _joint_name(label: str) -> str:
    """Joint (or "drive") a spring label of ``model._layout`` belongs to."""
    return "drive" if label.startswith("drive ") else label.split()[0]


def energy_parts(model: FrameModel, shapes: np.ndarray) -> EnergyParts:
    """Strain and kinetic energy of each link and joint for every column of ``shapes``
    (n_dofs, k), global DOFs (``model.py``)."""
    U = np.asarray(shapes, dtype=float).reshape(model.n_dofs, -1)
    names, is_link, strain, kinetic, axial = [], [], [], [], []
    for link in model.links:
        K, M = link.local_matrices()
        nodes = link.nodes
        c, s = math.cos(link.angle), math.sin(link.angle)
        local = np.empty((3 * len(nodes), U.shape[1]))
        ux, uy = U[3 * nodes], U[3 * nodes + 1]
        local[0::3], local[1::3], local[2::3] = c * ux + s * uy, -s * ux + c * uy, U[3 * nodes + 2]
        du = np.diff(local[0::3], axis=0)  # element stretches [m]: EA / h du^2 is the axial part
        h = link.length / link.elements
        names.append(link.name)
        is_link.append(True)
        strain.append(np.einsum("ik,ik->k", local, K @ local))
        kinetic.append(np.einsum("ik,ik->k", local, M @ local))
        axial.append(link.section.EA / h * (du**2).sum(axis=0))
    springs = model.springs
    per_spring = spring_energies(springs, U)
    groups: dict[str, list[int]] = {}
    for i, label in enumerate(springs.labels):
        if math.isfinite(springs.stiffness[i]):  # rigid springs carry no energy
            groups.setdefault(_joint_name(label), []).append(i)
    mass_at = {}
    for node, mass in model.point_masses:
        joint = next(j for j, ns in model.joint_nodes.items() if node in ns)
        mass_at.setdefault(joint, []).append((node, mass))
    for joint in list(groups) + [j for j in mass_at if j not in groups]:
        idx = np.array(groups.get(joint, []), dtype=int)
        energy = per_spring[idx]
        translational = springs.dof_a[idx] % 3 != 2
        names.append(joint)
        is_link.append(False)
        strain.append(energy.sum(axis=0))
        axial.append(energy[translational].sum(axis=0))
        kin = np.zeros(U.shape[1])
        for node, mass in mass_at.get(joint, []):
            kin += mass * (U[3 * node] ** 2 + U[3 * node + 1] ** 2)
        kinetic.append(kin)
    return EnergyParts(tuple(names), tuple(is_link), np.array(strain), np.array(kinetic),
                       np.array(axial))


def ground_motion(model: FrameModel, T=None) -> np.ndarray:
    """(n_dofs, 2): rigid translation in x and in y of every DOF not fixed to the ground
    (``T``: ``assembly.rigid_elimination``; grounded DOFs have no column in it)."""
    r = np.zeros((model.n_dofs, 2))
    r[0::3, 0] = 1.0
    r[1::3, 1] = 1.0
    if T is not None:
        r[np.diff(T.tocsr().indptr) == 0] = 0.0
    return r


def effective_masses(model: FrameModel, shapes: np.ndarray, M=None) -> np.ndarray:
    """(k, 2) effective modal mass [kg] in x and y of each mass-normalised column of
    ``shapes``; ``M``: the model's consistent mass (assembled when not given)."""
    if M is None:
        M = assemble(model)[1]
    gamma = np.asarray(shapes).T @ (M @ ground_motion(model, rigid_elimination(model)))
    return gamma**2


def participating_mass(model: FrameModel, M=None) -> np.ndarray:
    """(2,) r^T M r [kg] in x and y: what the effective masses of all modes sum to."""
    if M is None:
        M = assemble(model)[1]
    r = ground_motion(model, rigid_elimination(model))
    return np.einsum("ij,ij->j", r, M @ r)


def total_mass(model: FrameModel) -> float:
    """Mass of the links and joints [kg]: sum of rhoA L plus the lumped joint masses."""
    return (sum(l.section.mass_per_length * l.length for l in model.links)
            + sum(m for _, m in model.point_masses))


def _stem(parts: EnergyParts, strain: np.ndarray, j: int) -> str:
    """The label of mode ``j`` without its ordinal."""
    top = int(np.argmax(strain[:, j]))
    if parts.is_link[top] and strain[top, j] >= DOMINANT:
        axial = parts.axial[top, j] / parts.strain[top, j]
        return f"{parts.names[top]} {'axial' if axial >= 0.5 else 'bending'}"
    joints = [i for i, link in enumerate(parts.is_link) if not link]
    joint_share = strain[joints, j].sum() if joints else 0.0
    if joint_share >= DOMINANT:
        named = sorted((i for i in joints if strain[i, j] >= NAMED_JOINT * joint_share),
                       key=lambda i: -strain[i, j])
        total = parts.strain[joints, j].sum()
        axial = parts.axial[joints, j].sum() / total if total > 0 else 0.0
        kind = "axial" if axial >= 0.5 else "rotational"
        names = [parts.names[i] for i in named]
        if names == ["drive"]:
            return "drive"
        return f"joint springs {', '.join(names)} ({kind})"
    order = np.argsort(-strain[:, j])[:2]
    return "mixed " + " + ".join(parts.names[i] for i in order)


def mode_labels(parts: EnergyParts) -> list[str]:
    """A short label per mode (in the order given, lowest first): the link holding at least
    half the strain energy with "axial" or "bending" and an ordinal counting that link's modes
    of that kind ("coupler bending 1"); else the joints whose springs hold it ("joint springs
    A, O2 (axial)"); else "mixed" with the two largest parts."""
    strain, _ = parts.fractions()
    seen: dict[str, int] = {}
    labels = []
    for j in range(strain.shape[1]):
        stem = _stem(parts, strain, j)
        seen[stem] = seen.get(stem, 0) + 1
        labels.append(f"{stem} {seen[stem]}" if stem.endswith(("axial", "bending")) else stem)
    return labels


@dataclasses.dataclass(frozen=True)
class ModeIdentity:
    """What each of k modes is (in the order given, lowest first): its ``labels``
    (``mode_labels``), the fractions of its strain energy (``strain``) and of its kinetic energy
    (``kinetic``) held by each of ``parts`` (links, then joints; each row sums to 1), and its
    ``effective_mass`` [kg] for ground motion in each direction of ``DIRECTIONS``."""

    parts: tuple[str, ...]
    labels: tuple[str, ...]
    strain: np.ndarray  # (k, parts)
    kinetic: np.ndarray  # (k, parts)
    effective_mass: np.ndarray  # (k, len(DIRECTIONS)) [kg]

    def __post_init__(self):
        k = len(self.labels)
        for name, columns in (("strain", len(self.parts)), ("kinetic", len(self.parts)),
                              ("effective_mass", len(DIRECTIONS))):
            shape = np.shape(getattr(self, name))
            if shape != (k, columns):
                raise ValueError(f"ModeIdentity.{name} has shape {shape}, expected ({k}, "
                                 f"{columns}): one row per label, one column per "
                                 f"{'direction' if name == 'effective_mass' else 'part'}")

    def __len__(self) -> int:
        """The number of modes."""
        return len(self.labels)


def mode_identity(model: FrameModel, shapes: np.ndarray) -> ModeIdentity:
    """The identity of each mass-normalised column of ``shapes`` (n_dofs, k): label, energy
    fractions per link and joint, and effective masses."""
    parts = energy_parts(model, shapes)
    strain, kinetic = parts.fractions()
    return ModeIdentity(parts=parts.names, labels=tuple(mode_labels(parts)), strain=strain.T,
                        kinetic=kinetic.T, effective_mass=effective_masses(model, shapes))
