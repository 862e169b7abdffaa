"""A partially compliant linkage over the crank turn at large deflection: the crank turned
quasi-statically through 360 crank angles, every link a chain of co-rotational frame elements
(``fe.corotational``, solved by ``analysis.large_deflection``), beside the pseudo-rigid-body
(PRB) model of the scene's [prb] table.

The FE model is the scene's own mesh and joints at its start pose, where the strip is straight
and unstressed; the crank's rotation at its ground pivot is prescribed (no inertia: the
driving torque is the one that bends the strip). It gives every node's position (the pose of
every link and the strip's deflected shape), the strip's axial force, bending moment and
extreme-fibre stresses along it, and the driving torque two ways: the reaction moment at the
crank and dU/dtheta2 of the stored strain energy (central differences over the cycle's own
samples), which must agree by virtual work.

The PRB model (Howell's fixed-pinned segment): the scene's rigid four-bar with the strip
replaced by a rigid link of length gamma l to the characteristic pivot and a torsional spring
K = gamma K_Theta E I / l there, turned by Theta = (PRB link angle - clamping body angle) -
its start value. Its spring torque is K Theta, its driving torque K Theta dTheta/dtheta2, and
its stress estimate at the clamp follows from statics of the rigid links: with F the ground
pin's force on the PRB link,
    (O4 - B) x F = K Theta   (the PRB link, moments about B),
    (B - A) x F = -K Theta   (the clamping body, moments about its crank pin A),
so the strip's bending moment at the clamp is M = (O4 - C) x F, its axial force
N = F . (O4 - C)/|O4 - C|, and sigma = N/A -+ M c/I at the fibres y = +-c. The crank's torque
-(A - O2) x F checks the PRB's dU/dtheta2.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.sparse as sp

from flexlink.analysis.large_deflection import CorotationalFrame, driven_path
from flexlink.errors import InputError
from flexlink.fe.assembly import rigid_elimination, spring_entries
from flexlink.fe.corotational import chord_end_forces
from flexlink.fe.model_at_pose import pose_model
from flexlink.fe.stress import FIBRES, end_resultants, fibre_stress
from flexlink.kinematics.linkage import crank_angles
from flexlink.studies.array_shapes import check_shape

CRANK_ANGLES = 360


@dataclasses.dataclass(frozen=True)
class StripStress:
    """Stress resultants and extreme-fibre stresses along a strip over the crank turn, at its
    nodes: ``crank_angles`` (n,) [rad], ``arc_length`` (p,) [m] from the strip's start joint
    (unstretched), ``axial_force`` (n, p) [N] (tension positive), ``bending_moment`` (n, p)
    [N m] (M = EI v'' in the strip's frame), ``fibre_stress`` (n, p, 2) [Pa] at y = +c, -c
    (sigma = N/A - M y/I). For the fatigue chain: ``fibre_pairs()``."""

    crank_angles: np.ndarray
    arc_length: np.ndarray
    axial_force: np.ndarray
    bending_moment: np.ndarray
    fibre_stress: np.ndarray

    def __post_init__(self):
        n, p = len(self.crank_angles), len(self.arc_length)
        for name, shape in (("crank_angles", (n,)), ("arc_length", (p,)),
                            ("axial_force", (n, p)), ("bending_moment", (n, p)),
                            ("fibre_stress", (n, p, 2))):
            check_shape("StripStress", name, getattr(self, name), shape)

    def fibre_pairs(self) -> np.ndarray:
        """(n, 2 p) [Pa]: each node's +c then -c fibre, the column pairs that
        ``studies.life`` fatigue takes."""
        return self.fibre_stress.reshape(len(self.crank_angles), -1)

    @property
    def peak(self) -> tuple[float, int, int]:
        """(largest |sigma| [Pa], its crank-angle index, its node index)."""
        s = np.abs(self.fibre_stress).max(axis=2)
        k, j = np.unravel_index(np.argmax(s), s.shape)
        return float(s[k, j]), int(k), int(j)


@dataclasses.dataclass(frozen=True)
class PrbCycle:
    """The PRB model over the same crank angles: ``points`` joint -> (n, 2) [m], ``Theta``
    (n,) [rad], ``spring_torque`` K Theta (n,) [N m], ``drive_torque`` (n,) [N m]
    (K Theta dTheta/dtheta2), ``statics_torque`` (n,) [N m] (the crank's torque from the pin
    forces), ``clamp_moment`` (n,) [N m], ``clamp_stress`` (n, 2) [Pa] (+c, -c), ``spring``
    K [N m/rad]."""

    points: dict[str, np.ndarray]
    Theta: np.ndarray
    spring_torque: np.ndarray
    drive_torque: np.ndarray
    statics_torque: np.ndarray
    clamp_moment: np.ndarray
    clamp_stress: np.ndarray
    spring: float

    def __post_init__(self):
        n = len(self.Theta)
        for name in ("spring_torque", "drive_torque", "statics_torque", "clamp_moment"):
            check_shape("PrbCycle", name, getattr(self, name), (n,))
        check_shape("PrbCycle", "clamp_stress", self.clamp_stress, (n, 2))
        for joint, xy in self.points.items():
            check_shape("PrbCycle", f"points[{joint!r}]", xy, (n, 2))


@dataclasses.dataclass(frozen=True)
class CompliantCycle:
    """The nonlinear FE cycle and the PRB cycle of one scene: ``crank_angles`` (n,) [rad];
    FE ``nodes`` (n, N, 2) [m] (every link's deformed shape), ``link_nodes`` link -> node
    indices, ``joints`` joint -> (n, 2) [m]; the strip's ``stress``; the FE driving torque as
    the crank's ``reaction`` (n,) [N m] and as ``energy_torque`` dU/dtheta2 (n,) [N m] of the
    strain ``energy`` (n,) [J]; ``iterations`` (n,) Newton steps per crank angle; ``closure``
    [m]: how far the mesh is from its start after the full turn (continuation drift);
    ``strip``: the strip link's name; ``prb``."""

    crank_angles: np.ndarray
    nodes: np.ndarray
    link_nodes: dict[str, np.ndarray]
    joints: dict[str, np.ndarray]
    stress: StripStress
    reaction: np.ndarray
    energy_torque: np.ndarray
    energy: np.ndarray
    iterations: np.ndarray
    closure: float
    strip: str
    prb: PrbCycle

    def __post_init__(self):
        n = len(self.crank_angles)
        check_shape("CompliantCycle", "nodes", self.nodes, (n, None, 2))
        for name in ("reaction", "energy_torque", "energy", "iterations"):
            check_shape("CompliantCycle", name, getattr(self, name), (n,))
        for joint, xy in self.joints.items():
            check_shape("CompliantCycle", f"joints[{joint!r}]", xy, (n, 2))


def _driven_link(scene):
    body = scene.linkage.body(scene.linkage.driver)
    pivot, other = body.joints[0], body.joints[1]
    for spec in scene.links:
        if {spec.start, spec.end} == {pivot, other}:
            return spec, pivot
    raise InputError(f"no link joins the driver's joints {pivot!r} and {other!r}",
                     source=scene.path, field="links", expected="a crank link")


def _periodic_derivative(values, step):
    return (np.roll(values, -1) - np.roll(values, 1)) / (2 * step)


@dataclasses.dataclass(frozen=True)
class DrivenFrame:
    """The scene's frame at its start pose for large-deflection statics: ``model`` (its
    ``FrameModel``, drive spring removed), ``T`` (the exact constraints), ``frame`` (the
    co-rotational elements on the unknowns of T), ``driven`` (the unknown of the crank's
    rotation at its ground pivot) and ``springs`` (n, n) the finite joint springs on those
    unknowns (linear in the DOFs, and so exact: they join coincident nodes or hold a node to
    the ground)."""

    model: object
    T: object
    frame: CorotationalFrame
    driven: int
    springs: np.ndarray


def driven_frame(scene, elements: int | None = None) -> DrivenFrame:
    """The scene's ``DrivenFrame`` (InputError if the crank cannot turn at its pivot)."""
    topology = scene.topology(elements)
    model = pose_model(topology, scene.rigid_pose().joints, warn=False)
    model = dataclasses.replace(model, springs=_without_drive(model.springs))
    T = rigid_elimination(model)
    frame = CorotationalFrame.of(model).eliminated(T)
    spec, pivot = _driven_link(scene)
    link_index = [s.name for s in topology.links].index(spec.name)
    mesh = model.links[link_index]
    node = mesh.first_node if spec.start == pivot else mesh.first_node + mesh.elements
    rz = 3 * node + 2
    rows, cols, values = spring_entries(model)
    K = sp.coo_matrix((values, (rows, cols)), shape=(model.n_dofs,) * 2).tocsr()
    if T is None:
        return DrivenFrame(model, T, frame, rz, K.toarray())
    Tc = T.tocsr()
    if Tc.indptr[rz + 1] - Tc.indptr[rz] != 1:
        raise InputError(f"the driven link {spec.name!r} cannot turn at {pivot!r}: its "
                         "rotation there is held", source=scene.path, field=f"joints.{pivot}")
    driven = int(Tc.indices[Tc.indptr[rz]])
    if Tc.tocsc()[:, driven].nnz > 1:
        raise InputError(f"the driven link {spec.name!r} is welded to another at {pivot!r}",
                         source=scene.path, field=f"joints.{pivot}")
    return DrivenFrame(model, T, frame, driven, (T.T @ K @ T).toarray())


def fe_cycle(scene, angles, elements: int | None = None, progress=None,
             max_iterations: int = 30):
    """The co-rotational FE model driven through ``angles`` [rad] (from the scene's start
    pose, equally spaced over one turn) and on to a full turn. Returns (the ``DrivenFrame``,
    the path (n + 1 states, the last after the full turn), the full-DOF displacements
    (n + 1, n_dofs), the closure error [m]: how far any node is from its start after the
    full turn)."""
    d = driven_frame(scene, elements)
    T, frame, driven = d.T, d.frame, d.driven

    def label(turn):
        return f"crank angle {math.degrees(scene.start + turn) % 360:.1f} deg"

    turns = np.append(np.asarray(angles) - scene.start, 2 * math.pi)
    path = driven_path(frame, driven, turns, label, max_iterations, progress, d.springs)
    u = path.q @ (np.eye(frame.n_dofs) if T is None else T.T.toarray())
    closure = float(np.abs(u[-1].reshape(-1, 3)[:, :2]).max())
    return d, path, u, closure


def _without_drive(springs):
    """The joints' springs without the drive's (its rotation is prescribed instead)."""
    keep = np.array([not label.startswith("drive ") for label in springs.labels], bool)
    return dataclasses.replace(springs, dof_a=springs.dof_a[keep], dof_b=springs.dof_b[keep],
                               stiffness=springs.stiffness[keep],
                               labels=tuple(np.array(springs.labels, object)[keep]))


def strip_stress(frame, states, link_index: int, section, angles) -> StripStress:
    """The strip's resultants and fibre stresses at its nodes over ``angles`` from the
    element ``states`` (one per angle)."""
    elements = np.flatnonzero(frame.link == link_index)
    h = frame.chords.L0[elements]
    arc = np.concatenate([[0.0], np.cumsum(h)])
    N, M = [], []
    for state in states:
        n_end, m_end = end_resultants(chord_end_forces(state))
        # node j: element j's start (j = 0), else element j-1's end (equal at equilibrium:
        # nothing loads the strip between its nodes)
        N.append(np.append(n_end[elements, 0][:1], n_end[elements, 1]))
        M.append(np.append(m_end[elements, 0][:1], m_end[elements, 1]))
    N, M = np.array(N), np.array(M)
    return StripStress(np.asarray(angles), arc, N, M, fibre_stress(section, N, M))


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def prb_cycle(scene, angles) -> PrbCycle:
    """The PRB model of the scene's [prb] table over ``angles`` [rad] (module doc)."""
    p = scene.options.prb
    if p is None:
        raise InputError("no [prb] table: no pseudo-rigid-body model to compare",
                         source=scene.path, field="prb")
    cycle = scene.linkage.cycle(np.asarray(angles), scene.guess)
    names = [b.name for b in scene.linkage.bodies]
    i_link, i_clamp = names.index(p.link), names.index(p.clamp)
    points = {j: np.array([s.points[j] for s in cycle.states], float)
              for j in cycle.states[0].points}
    strip = {s.name: s for s in scene.links}[p.strip]
    ground_end = strip.start if strip.start in scene.linkage.ground else strip.end
    clamp_end = strip.end if ground_end == strip.start else strip.start
    relative = np.array([s.angles[i_link] - s.angles[i_clamp] for s in cycle.states])
    Theta = np.unwrap(relative) - relative[0]
    rate = np.array([s.K[i_link] - s.K[i_clamp] for s in cycle.states])
    length = float(np.hypot(*(points[ground_end][0] - points[clamp_end][0])))
    section = strip.section
    K = p.gamma * p.K_theta * section.EI / length
    torque = K * Theta
    O4, B, C = points[ground_end], points[p.pivot], points[clamp_end]
    crank = scene.linkage.body(scene.linkage.driver)
    O2, A = points[crank.joints[0]], points[crank.joints[1]]
    a, b = O4 - B, B - A
    det = _cross(a, b)  # (a x F, b x F) = (torque, -torque): F = torque (b + a) / (a x b)
    F = torque[:, None] * (a + b) / det[:, None]
    to_ground = O4 - C
    moment = _cross(to_ground, F)
    axial = np.einsum("ij,ij->i", F, to_ground) / np.hypot(*to_ground.T)
    stress = fibre_stress(section, axial, moment)
    return PrbCycle(points, Theta, torque, torque * rate, -_cross(A - O2, F), moment, stress, K)


def compliant_cycle(scene, count: int = CRANK_ANGLES, elements: int | None = None,
                    progress=None, max_iterations: int = 30) -> CompliantCycle:
    """The nonlinear FE and the PRB cycle of a scene with a [prb] table over ``count`` crank
    angles (module doc). A crank angle where Newton's method does not converge raises
    NumericalError naming it; nothing is returned."""
    p = scene.options.prb
    if p is None:
        raise InputError("no [prb] table: the compliant strip is not named", source=scene.path,
                         field="prb")
    angles = crank_angles(count, scene.start)  # from the unstressed pose
    prb = prb_cycle(scene, angles)
    d, path, u, closure = fe_cycle(scene, angles, elements, progress, max_iterations)
    model, frame = d.model, d.frame
    names = [link.name for link in model.links]
    index = names.index(p.strip)
    nodes = model.nodes[None] + u[:-1].reshape(len(angles), -1, 3)[:, :, :2]
    joints = {j: nodes[:, ns[0]] for j, ns in model.joint_nodes.items()}
    stress = strip_stress(frame, path.states[:-1], index, model.links[index].section, angles)
    energy = path.energy[:-1]
    return CompliantCycle(
        crank_angles=angles, nodes=nodes,
        link_nodes={link.name: link.nodes for link in model.links}, joints=joints,
        stress=stress, reaction=path.moment[:-1],
        energy_torque=_periodic_derivative(energy, 2 * math.pi / count), energy=energy,
        iterations=path.iterations[:-1], closure=closure, strip=p.strip, prb=prb)


@dataclasses.dataclass(frozen=True)
class StripLife:
    """The fatigue verdict of the strip's worst point by one model ("FE" or "PRB"): the
    ``fatigue`` (``analysis.fatigue.Fatigue``: life in turns, safety factor against the
    endurance limit, the worst cycle's amplitude, mean and equivalent, yield factor), where
    (``arc_length`` [m] from the strip's start joint, ``fibre`` +1 or -1 for y = +c or -c),
    the part's endurance limit [Pa] and the strength data's source."""

    model: str
    fatigue: object
    arc_length: float
    fibre: float
    endurance: float
    material: str


def strip_lives(scene, cycle: CompliantCycle, conditions=None) -> tuple[StripLife, ...]:
    """The strip's life by the fatigue chain of ``studies.life.life`` (rainflow counting over
    the turn, mean-stress correction, the part's S-N line from the strip's material file and
    Marin factors) for the FE stress at every node and the PRB stress at the clamp; InputError
    naming the file and key where the strip's material lacks strength data."""
    from flexlink.studies.life.life import Conditions, check_strengths, fibre_pair_fatigue

    conditions = conditions or Conditions()
    check_strengths(scene, [cycle.strip])
    material = scene.materials[cycle.strip].isotropic
    section = {link.name: link.section for link in scene.links}[cycle.strip]
    out = []
    for model, histories, arcs in (("FE", cycle.stress.fibre_pairs(), cycle.stress.arc_length),
                                   ("PRB", cycle.prb.clamp_stress, np.zeros(1))):
        results, kinds, curves, _ = fibre_pair_fatigue(histories, material, section, conditions)
        column = min(range(len(results)), key=lambda c: (results[c].safety, -results[c].damage))
        out.append(StripLife(model, results[column], float(arcs[column // 2]),
                             FIBRES[column % 2], curves[kinds[column]].endurance,
                             material))
    return tuple(out)
