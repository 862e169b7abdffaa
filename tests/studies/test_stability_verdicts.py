"""The stability checks' own PASS/FAIL (the exit code of `flexlink stability`) follows the
criterion each states: the bearing sweep promises the highest penalty stiffness "within 1e-6
of the exact rigid path", so a penalty path 1e-4 off that path must FAIL. The offset is made
by scaling every penalty run's eigenvalues by (1 - 2e-4), which leaves every other criterion
as it was (the runs stay monotone in k, finite and >= 0; the rigid runs and the backward
errors are untouched), so only that criterion can turn the verdict."""

import dataclasses
import re

import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.fe.model_at_pose import pose_model
from flexlink.scene import load_scene
from flexlink.studies.verification import self_checks as st
from flexlink.units import parse_quantity

SHIFT = 2e-4  # relative, on eigenvalues: 1e-4 on frequencies, 100 x the promised 1e-6


def test_a_penalty_path_off_the_rigid_path_fails_the_bearing_sweep(monkeypatch):
    real = st._modes

    def shifted(topology, points, n_elastic, *args, **kwargs):
        result = real(topology, points, n_elastic, *args, **kwargs)
        springs = pose_model(topology, points, warn=False).springs.stiffness
        if not np.isfinite(springs).any():  # every joint rigid: the exact path, as solved
            return result
        return dataclasses.replace(result, eigenvalues=result.eigenvalues * (1 - SHIFT),
                                   frequencies=result.frequencies * np.sqrt(1 - SHIFT))

    monkeypatch.setattr(st, "_modes", shifted)
    check = st.bearing_sweep(load_scene(CASES_DIR / "case1.toml"))
    d = check.details
    # the other criteria still hold ...
    lams = np.array(d["eigenvalues"])
    assert np.all(np.diff(lams, axis=0) >= -1e-9 * max(np.max(d["exact_eigenvalues"]), 1.0))
    assert d["rigid_vs_exact"] < 1e-12 and d["backward_error_max"] < 1e-10
    assert d["sweep"][0]["zero_modes"] == 8 and d["warnings_logged"] > 0
    # ... the penalty path is 1e-4 off (sqrt(1 - 2e-4) = 1 - 1e-4, to 1 %), and it fails
    assert d["penalty_vs_exact"] == pytest.approx(1e-4, rel=0.01)
    assert not check.passed


def test_the_untouched_sweep_passes_and_states_its_stiffness_in_units_flexlink_reads():
    check = st.bearing_sweep(load_scene(CASES_DIR / "case1.toml"))
    assert check.passed
    # the printed name gives the swept stiffness's units; a reader can type them back into a
    # scene file, so they must be units the scene reader knows, as written
    named = re.search(r"\(Kt (.+?) = Kr (.+?)\)", check.name)
    assert named, check.name
    translational, rotational = named.groups()
    assert parse_quantity(f"1 {translational}", "translational stiffness") == 1.0
    assert parse_quantity(f"1 {rotational}", "rotational stiffness") == 1.0
