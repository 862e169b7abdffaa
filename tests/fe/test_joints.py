"""Joints become springs the same way in both formulations (``fe/joints.py``): the wiper's
welded rocker (two beams welded at the O2 bearing) is one body turning in one bearing in the
in-plane and in the out-of-plane model alike, whatever its tilt stiffness."""

import numpy as np
import pytest
from conftest import SCENES_DIR

from flexlink.analysis.families import part_modes
from flexlink.fe.formulation import FORMULATIONS
from flexlink.scene import load_scene

WIPER = SCENES_DIR / "wiper.toml"
ELEMENTS = 4  # the welded joint's springs do not depend on the mesh; 4 keeps the solves cheap


def wiper(tilt: str, family: str = "3d"):
    return load_scene(WIPER, {"joints.Ktilt": tilt, "model.family": family})


def o2_nodes(model):
    """The two arms' nodes at the welded joint O2."""
    return model.joint_nodes["O2"]


@pytest.mark.parametrize("part", sorted(FORMULATIONS))
def test_welded_joint_has_a_weld_and_one_bearing_in_each_part(part):
    """Finite Ktilt: the arms are welded in all three DOFs, and the bearing springs (the finite
    ones and the rigid ground ties) sit on the first arm's node only."""
    scene = wiper("50 N*m/rad")
    model = FORMULATIONS[part].model(scene.topology(ELEMENTS), scene.rigid_pose().joints,
                                     scene.options.tilt)
    first, second = o2_nodes(model)
    springs = model.springs
    weld = [i for i, label in enumerate(springs.labels) if label.startswith("O2 weld")]
    assert len(weld) == 3
    assert sorted(springs.dof_a[weld] - 3 * second) == [0, 1, 2]
    assert list(springs.dof_b[weld] - 3 * first) == list(springs.dof_a[weld] - 3 * second)
    assert np.all(np.isinf(springs.stiffness[weld]))
    bearing = [i for i, label in enumerate(springs.labels)
               if label.startswith("O2 ") and i not in weld]
    assert bearing and all(springs.dof_a[i] // 3 == first for i in bearing)
    assert all(springs.dof_b[i] == -1 for i in bearing)  # to ground


def test_welded_arms_move_as_one_body():
    """In every mode of both parts, the two arms' ends at O2 have the same displacement and
    rotation (exactly: the weld is an exact constraint, so equal to round-off)."""
    for part in part_modes(wiper("50 N*m/rad"), 4, ELEMENTS):
        first, second = o2_nodes(part.model)
        a = part.shapes[3 * first:3 * first + 3]
        b = part.shapes[3 * second:3 * second + 3]
        scale = np.abs(part.shapes).max(axis=0)
        assert np.all(np.abs(a - b) <= 1e-12 * scale), part.part


def test_finite_tilt_stiffness_converges_to_the_rigid_joint_as_one_over_ktilt():
    """Out of plane, a finite Ktilt softens the joints: each frequency rises towards the rigid
    joints' one, and (first-order perturbation of a stiff spring) the gap shrinks as 1 / Ktilt:
    ten times the stiffness, a tenth of the gap. The next term is of relative size
    gap / frequency (below 0.5 % here), so the ratio is 10 within 5 %."""
    def lowest(tilt):
        return part_modes(wiper(tilt, "out-of-plane"), 4, ELEMENTS)[0].frequencies

    rigid = lowest("rigid")
    soft, stiff = lowest("1e4 N*m/rad"), lowest("1e5 N*m/rad")
    assert np.all(soft < stiff) and np.all(stiff < rigid)
    ratio = (rigid - soft) / (rigid - stiff)
    assert np.all(np.abs(ratio - 10) < 0.5), ratio
