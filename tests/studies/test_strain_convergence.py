"""The steady response's peak strain converges as the reduced basis grows towards the whole
finite-element model (``studies.strain_convergence``)."""
import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.fe.assembly import reduced_columns, rigid_elimination
from flexlink.fe.model_at_pose import pose_model
from flexlink.scene import load_scene
from strain_convergence import strain_convergence
from flexlink.units import RPM


@pytest.mark.slow
def test_peak_strain_approaches_the_whole_model_as_the_basis_grows():
    # case 1 at 1 element per link (17 reduced DOFs) and 13 poses: the checked bases of 2, 4
    # and 6 static modes per snapshot pose, against the basis of every DOF (the finite-element
    # model itself in other coordinates), at 1500 rev/min. Measured: the largest peak-strain
    # difference from the whole model falls 8.8 %, 0.70 %, 0.22 %; the 2-mode basis passes its
    # frequency check (0.024 %) yet misses the strain by 8.8 %: strain needs more shapes
    scene = load_scene(CASES_DIR / "case1.toml")
    model = pose_model(scene.topology(1), scene.rigid_state(None).points)
    every = reduced_columns(rigid_elimination(model), model.n_dofs)[1]
    study = strain_convergence(scene, np.array([1500.0]) * RPM,
                               ((2, 0), (4, 0), (6, 0), (every, 0)), poses=13,
                               elements_per_link=1, samples=36)
    assert study.basis_sizes[-1] == every and study.basis_errors[-1] < 1e-9
    change = study.change
    assert change[0] > change[1] > change[2] > 0.0, change
    assert change[0] > 0.05 and change[2] < 0.01, change  # the measured 8.8 % and 0.22 %
    assert np.all(np.isfinite(study.peak_strain))
