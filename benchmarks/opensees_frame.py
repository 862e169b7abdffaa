"""The same frame as a flexlink FrameModel, built and solved in OpenSeesPy (optional).

Node for node and element for element: every link is a chain of elasticBeamColumn elements with
consistent mass (-cMass: the same cubic Hermite bending and linear axial mass as flexlink), every
finite spring a zeroLength element between the two coincident joint nodes (or between the node
and a fixed ground node at the same place), every rigid spring to ground a ``fix`` of that DOF
and every rigid spring between two nodes an ``equalDOF``.
"""

from __future__ import annotations

import math

import numpy as np

from flexlink.fe.model import GROUND, FrameModel

_TRANSF = 1


def build(ops, model: FrameModel, transformation: str = "Linear") -> None:
    """Wipe OpenSees and define ``model`` in it (tags: node i + 1, ground nodes after them).
    ``transformation``: the elements' geomTransf ("Linear", or "PDelta" for the geometric
    stiffness N / L of each element's chord)."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    for i, (x, y) in enumerate(model.nodes):
        ops.node(i + 1, float(x), float(y))
    ops.geomTransf(transformation, _TRANSF)
    tag = 0
    for link in model.links:
        s = link.section
        for e in range(link.elements):
            tag += 1
            a = link.first_node + e + 1
            ops.element("elasticBeamColumn", tag, a, a + 1, s.area, s.E, s.second_moment, _TRANSF,
                        "-mass", s.mass_per_length, "-cMass")
    springs = model.springs
    next_node, materials, fixed, tied = len(model.nodes) + 1, {}, {}, {}
    ground_of = {}
    for a, b, k in zip(springs.dof_a, springs.dof_b, springs.stiffness):
        node_a, dof = int(a) // 3 + 1, int(a) % 3 + 1
        if not math.isfinite(k):
            if b == GROUND:
                fixed.setdefault(node_a, [0, 0, 0])[dof - 1] = 1
            else:  # one equalDOF per node pair: the Transformation handler keeps one only
                tied.setdefault((int(b) // 3 + 1, node_a), []).append(dof)
            continue
        if b == GROUND:
            if node_a not in ground_of:
                x, y = model.nodes[node_a - 1]
                ops.node(next_node, float(x), float(y))
                ops.fix(next_node, 1, 1, 1)
                ground_of[node_a] = next_node
                next_node += 1
            node_b = ground_of[node_a]
        else:
            node_b = int(b) // 3 + 1
        if k not in materials:
            materials[k] = len(materials) + 1
            ops.uniaxialMaterial("Elastic", materials[k], float(k))
        tag += 1
        ops.element("zeroLength", tag, node_b, node_a, "-mat", materials[k], "-dir", dof)
    for node, dofs in fixed.items():
        ops.fix(node, *dofs)
    for (retained, constrained), dofs in tied.items():
        ops.equalDOF(retained, constrained, *dofs)
    for node, mass in model.point_masses:
        ops.mass(node + 1, mass, mass, 0.0)


def preload(ops, loads: np.ndarray) -> None:
    """Apply nodal ``loads`` (flexlink's full DOF order: ux, uy, rz per node) and take one
    linear static step: the tangent at zero load (K) gives u = K^-1 f, after which each element
    holds its axial force and the tangent stiffness includes its transformation's K_g(N)."""
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for i, (fx, fy, mz) in enumerate(np.asarray(loads, dtype=float).reshape(-1, 3)):
        if fx or fy or mz:
            ops.load(i + 1, float(fx), float(fy), float(mz))
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("FullGeneral")
    ops.algorithm("Linear")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees static step failed")


def frequencies(ops, n_modes: int, solver: str = "-fullGenLapack") -> np.ndarray:
    """Lowest ``n_modes`` natural frequencies [Hz] of the model defined in OpenSees."""
    lam = np.asarray(ops.eigen(solver, n_modes), dtype=float)
    return np.sqrt(np.clip(lam, 0.0, None)) / (2 * math.pi)
