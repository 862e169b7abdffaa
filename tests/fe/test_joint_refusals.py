"""A joint's stiffness or mass that is negative or NaN (and an infinite mass) is refused from
Python as it is from a scene: an InputError naming the joint and the field, before any matrix
is built, never a NaN frequency or a failed eigen solve later."""

import math

import pytest

from flexlink.analysis import outofplane
from flexlink.errors import InputError
from flexlink.fe.model import DriveSpec, JointSpec
from flexlink.scene import load_scene

from conftest import CASES_DIR

CASE1 = CASES_DIR / "case1.toml"
UNITS = {"Kt": "N/m", "Kr": "N*m/rad", "mass": "kg", "Ktilt": "N*m/rad"}
BAD = [math.nan, -1.0, -math.inf]


@pytest.mark.parametrize("value", BAD, ids=str)
@pytest.mark.parametrize("field", ["Kt", "Kr", "mass"])
def test_a_joint_spec_refuses_what_a_scene_refuses(field, value):
    given = {"Kt": 1e6, "Kr": 10.0, field: value}
    with pytest.raises(InputError, match=f"joint A: {field}: must be >= 0") as refusal:
        JointSpec("A", ground=False, **given)
    assert UNITS[field] in str(refusal.value)
    # the scene refuses the same number written with its unit (NaN cannot even be read)
    with pytest.raises(InputError, match=f"joints.A.{field}"):
        load_scene(CASE1, overrides={f"joints.A.{field}": f"{value} {UNITS[field]}"})


def test_an_infinite_mass_is_refused_and_an_infinite_stiffness_is_rigid():
    with pytest.raises(InputError, match="joint A: mass: must be >= 0 and finite"):
        JointSpec("A", ground=False, Kt=1e6, Kr=10.0, mass=math.inf)
    with pytest.raises(InputError, match="joints.A.mass"):
        load_scene(CASE1, overrides={"joints.A.mass": "1e400 kg"})
    rigid = JointSpec("A", ground=False, Kt=math.inf, Kr=math.inf, mass=0.0)
    assert rigid.Kt == rigid.Kr == math.inf  # 'rigid' in a scene


@pytest.mark.parametrize("value", BAD, ids=str)
def test_a_drive_refuses_what_a_scene_refuses(value):
    with pytest.raises(InputError, match="drive: stiffness: must be >= 0"):
        DriveSpec("crank", "O2", value)
    with pytest.raises(InputError, match="drive.stiffness"):
        load_scene(CASE1, overrides={"drive.stiffness": f"{value} N*m/rad"})


@pytest.mark.parametrize("value", BAD, ids=str)
def test_a_tilt_stiffness_given_in_python_is_refused_before_the_solve(value):
    # the out-of-plane model takes Ktilt per joint as a plain mapping: NaN would give
    # frequencies, a negative one an indefinite K and a failed solve far from its cause
    scene = load_scene(CASE1)
    tilt = {j.name: 5.0 for j in scene.joints} | {"B": value}
    with pytest.raises(InputError, match="joint B: Ktilt: must be >= 0"):
        outofplane.out_of_plane_modes(scene.topology(2), scene.rigid_pose().joints, tilt, 2)
    with pytest.raises(InputError, match="joints.B.Ktilt"):
        load_scene(CASE1, overrides={"joints.B.Ktilt": f"{value} N*m/rad"})
