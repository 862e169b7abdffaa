"""A general scene's start pose given by its transmission angle, on both assembly branches,
against a loop closure written here without flexlink's kinematics.

The reference closes the loop O2-A-B-O4 by intersecting the circle of radius coupler about A
with the circle of radius rocker about O4, picks the intersection on the branch's side of the
diagonal O4 -> A (open: clockwise of it, B on the same side as in the drawn, uncrossed
four-bar; crossed: the mirror image), and finds the crank angle in [0, 180] deg where the angle
at B between BA and BO4 equals the one asked for by bisection on that closure alone. Both are
exact up to round-off: 1e-12 m in joint positions on a 0.3 m linkage, 1e-10 rad in angles
(the bisection's tolerance).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from flexlink.scene import load_scene

LENGTHS = {"ground": 0.300, "crank": 0.080, "coupler": 0.240, "rocker": 0.200}  # [m]


def closed_loop(theta2: float, branch: str) -> dict[str, np.ndarray]:
    """Joint positions [m] at crank angle ``theta2`` [rad] on ``branch``, by two circles."""
    O2, O4 = np.zeros(2), np.array([LENGTHS["ground"], 0.0])
    A = LENGTHS["crank"] * np.array([math.cos(theta2), math.sin(theta2)])
    r0, r1 = LENGTHS["coupler"], LENGTHS["rocker"]
    d = np.linalg.norm(O4 - A)
    along = (r0 * r0 - r1 * r1 + d * d) / (2 * d)  # from A towards O4
    height = math.sqrt(r0 * r0 - along * along)
    unit = (O4 - A) / d
    normal = np.array([-unit[1], unit[0]])
    candidates = [A + along * unit + s * height * normal for s in (1.0, -1.0)]

    def side(B):  # > 0: B counter-clockwise of the diagonal O4 -> A, seen from O4
        a, b = A - O4, B - O4
        return a[0] * b[1] - a[1] * b[0]
    B = next(c for c in candidates if (side(c) < 0) == (branch == "open"))
    return {"O2": O2, "A": A, "B": B, "O4": O4}


def angle_at_b(joints) -> float:
    """The transmission angle [rad]: between B->A and B->O4."""
    u, v = joints["A"] - joints["B"], joints["O4"] - joints["B"]
    return math.atan2(abs(u[0] * v[1] - u[1] * v[0]), u @ v)


def reference_start(mu: float, branch: str) -> tuple[float, dict]:
    """(crank angle in [0, pi] [rad] where the angle at B is ``mu``, the joints there)."""
    theta2 = brentq(lambda t: angle_at_b(closed_loop(t, branch)) - mu, 0.0, math.pi,
                    xtol=1e-13)
    return theta2, closed_loop(theta2, branch)


def general_scene(tmp_path, mu_deg: float, branch: str, point: bool = False):
    """The four-bar by its lengths as a general scene; ``point``: with a joint C fixed on the
    coupler half-way from A to B (the loop is then closed from the scene's guess, not by the
    four-bar's closed form)."""
    path = tmp_path / f"start_{branch}_{mu_deg:g}_{point}.toml"
    lengths = "\n".join(f'{k} = "{1e3 * v:g} mm"' for k, v in LENGTHS.items())
    extra = '[linkage.points.C]\non = "coupler"\nat = 0.5\n' if point else ""
    path.write_text(f'name = "four-bar by lengths"\n[linkage]\ntype = "general"\n'
                    f'branch = "{branch}"\nstart_transmission_angle = "{mu_deg:g} deg"\n'
                    f'[linkage.four_bar]\n{lengths}\n{extra}')
    return load_scene(path)


@pytest.mark.parametrize("point", [False, True], ids=["four-bar", "with a point"])
@pytest.mark.parametrize("mu_deg", [60.0, 90.0, 115.0])
@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_the_start_pose_closes_the_loop_at_the_asked_angle_on_its_branch(tmp_path, branch,
                                                                         mu_deg, point):
    scene = general_scene(tmp_path, mu_deg, branch, point)
    theta2, joints = reference_start(math.radians(mu_deg), branch)
    if point:
        joints["C"] = 0.5 * (joints["A"] + joints["B"])
    assert scene.start == pytest.approx(theta2, abs=1e-10)
    pose = scene.rigid_pose().joints
    for name, point in joints.items():
        np.testing.assert_allclose(pose[name], point, rtol=0, atol=1e-12)
    # the rigid state the studies start from is the same pose
    state = scene.rigid_state()
    for name, point in joints.items():
        np.testing.assert_allclose(state.points[name], point, rtol=0, atol=1e-12)


def test_the_two_branches_mirror_b_about_the_diagonal(tmp_path):
    # the same crank angle (the transmission angle fixes it whatever the branch), and B
    # reflected across the line O4 -> A
    open_, crossed = (general_scene(tmp_path, 75.0, b) for b in ("open", "crossed"))
    assert open_.start == pytest.approx(crossed.start, abs=1e-12)
    a, o4 = (np.array(open_.rigid_pose().joints[k]) for k in ("A", "O4"))
    b_open, b_crossed = (np.array(s.rigid_pose().joints["B"]) for s in (open_, crossed))
    unit = (a - o4) / np.linalg.norm(a - o4)
    reflected = o4 + 2 * ((b_open - o4) @ unit) * unit - (b_open - o4)
    np.testing.assert_allclose(b_crossed, reflected, rtol=0, atol=1e-12)
    assert np.linalg.norm(b_open - b_crossed) > 0.05  # far apart: a swapped branch shows
