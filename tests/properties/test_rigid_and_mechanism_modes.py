"""How many rigid-body and mechanism modes a linkage has, and what they look like.

Oracle: the links as rigid bodies in the plane (3 velocities each: u, v, theta about the
origin), and each joint's springs as velocity constraints, whether the spring is finite or
rigid (a spring of any stiffness > 0 takes energy from a motion that stretches it): Kt > 0
makes the two links' velocities at the joint equal (or zero at a ground bearing), Kr > 0
their rotation rates, a drive > 0 the crank's rotation rate zero; a spring of 0 constrains
nothing. The number of zero-frequency modes is 9 - rank(constraints) (Gruebler's count,
with redundant constraints counted once: e.g. a loop of rotational springs with every Kt = 0
holds only three rotations). Examples: a four-bar whose crank turns freely (no drive, Kr = 0
everywhere) has one mechanism mode, its own motion; a held crank (drive of any stiffness)
none; Kt = 0 at a pin disconnects the links there.

The one mechanism mode of a free four-bar is its rigid motion: the joints move along the
velocity coefficients dp/dq of the rigid kinematics (``Linkage.solve``), a stage independent
of the finite elements.
"""

import dataclasses

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from strategies import (
    GROUND,
    JOINTS,
    LINKS,
    RIGID,
    JointValues,
    linkages,
    load,
    log_uniform,
)

from flexlink.analysis.modal import analyze
from flexlink.analysis.solve import MECHANISM


def rigid_freedoms(spec) -> int:
    """9 - rank of the joint constraints on the three rigid links' velocities."""
    points = spec.local_points()
    column = {name: 3 * i for i, (name, _, _) in enumerate(LINKS)}
    attached = {j: [name for name, a, b in LINKS if j in (a, b)] for j in JOINTS}

    def velocity(link, p):  # (2, 9): velocity of point p carried by link
        row = np.zeros((2, 9))
        i = column[link]
        row[0, i], row[0, i + 2] = 1.0, -p[1]
        row[1, i + 1], row[1, i + 2] = 1.0, p[0]
        return row

    def rotation(link):
        row = np.zeros((1, 9))
        row[0, column[link] + 2] = 1.0
        return row

    def relative(block, j):  # the joint's first link against its partner, or the ground
        links = attached[j]
        return block(links[0]) - (block(links[1]) if len(links) > 1 else 0.0)

    rows = [np.zeros((0, 9))]
    for j, joint in spec.joints.items():
        if joint.Kt > 0:
            rows.append(relative(lambda link, p=points[j]: velocity(link, p), j))
        if joint.Kr > 0:
            rows.append(relative(rotation, j))
    if spec.drive is not None and spec.drive > 0:
        rows.append(rotation("crank"))
    return 9 - np.linalg.matrix_rank(np.vstack(rows))


@st.composite
def connections(draw):
    """A four-bar whose every joint has Kt and Kr each 0, finite or rigid, and a drive
    absent, finite or rigid. Finite springs go down to 1e-4 of the link scale (Kt of
    E A / L1, Kr and the drive of E I / L1): their modes then lie at about 1e-3 of the links'
    own bending eigenvalue scale or above, three orders above the solver's mechanism
    threshold (1e-6 of it), so every one of them must be labelled elastic."""
    spec = draw(linkages(elements=st.just(2)))
    crank = spec.sections["crank"]
    scale_t = spec.E * crank.A / spec.lengths[0]
    scale_r = spec.E * crank.I / spec.lengths[0]
    finite = log_uniform(1e-4, 1.0)
    joints = {}
    for name, joint in spec.joints.items():
        Kt = draw(st.sampled_from((0.0, draw(finite) * scale_t, RIGID)))
        Kr = draw(st.sampled_from((0.0, draw(finite) * scale_r, RIGID)))
        joints[name] = JointValues(Kt, Kr, joint.mass)
    drive = draw(st.sampled_from((None, draw(finite) * scale_r, RIGID)))
    return dataclasses.replace(spec, joints=joints, drive=drive)


@given(connections())
def test_the_number_of_zero_modes_is_the_linkages_freedom(spec):
    result = analyze(load(spec), 2)
    kinds = result.modes.kinds
    assert kinds.count(MECHANISM) == rigid_freedoms(spec), (kinds, spec.joints, spec.drive)
    # zero modes come first, every elastic mode after them
    assert list(kinds) == sorted(kinds, key=lambda k: k != MECHANISM)


@given(linkages(drive="none", elements=st.just(2)))
def test_a_free_crank_gives_one_mechanism_mode_that_moves_as_the_rigid_linkage(spec):
    joints = {n: JointValues(j.Kt, 0.0, j.mass) for n, j in spec.joints.items()}
    spec = dataclasses.replace(spec, joints=joints)
    scene = load(spec)
    result = analyze(scene, 2)
    assert result.modes.kinds.count(MECHANISM) == 1
    shape = result.modes.shapes[:, 0]
    assert result.modes.kinds[0] == MECHANISM
    state = scene.linkage.solve(scene.start, scene.guess)
    moving = [j for j in JOINTS if j not in GROUND]
    expected = np.concatenate([state.dpoints[j] for j in moving])
    model = result.model
    found = np.concatenate([shape[3 * model.joint_nodes[j][0]: 3 * model.joint_nodes[j][0] + 2]
                            for j in moving])
    mac = (expected @ found) ** 2 / ((expected @ expected) * (found @ found))
    # the mode is the rigid motion to round-off; finite springs are not stretched by it
    assert mac > 1 - 1e-9, mac
    assert result.modes.frequencies[0] < 1e-6 * result.modes.frequencies[1]


@given(linkages(drive="rigid", elements=st.just(2)))
def test_a_held_crank_leaves_no_mechanism_mode(spec):
    joints = {n: JointValues(j.Kt, 0.0, j.mass) for n, j in spec.joints.items()}
    result = analyze(load(dataclasses.replace(spec, joints=joints)), 2)
    assert MECHANISM not in result.modes.kinds
