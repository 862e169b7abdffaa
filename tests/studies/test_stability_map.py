"""The linkage's periodic equations over one crank turn and the stability map built on them."""
import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.errors import InputError
from flexlink.scene import load_scene
from flexlink.studies.stability_map import _nearest, periodic_model, stability_map


@pytest.fixture(scope="module")
def model():
    # a coarse mesh and few poses: the checks below are identities, not converged numbers
    # (13 poses: with 9 the interpolated stiffness turns indefinite between poses)
    return periodic_model(load_scene(CASES_DIR / "case1.toml"), n_modes=3, poses=13,
                          elements_per_link=2)


def test_mass_is_constant_over_the_turn_in_co_rotating_coordinates(model):
    # A link's mass matrix only turns with the link; in co-rotating node coordinates it is the
    # same at every crank angle (to round-off, 1e-12 of the unit modal mass).
    assert np.allclose(model.mass, model.mass[0], atol=1e-12, rtol=0)
    assert np.allclose(model.mass[0], np.eye(model.mass.shape[1]), atol=1e-12)


def test_reference_pose_is_diagonal_with_the_static_frequencies(model):
    # the basis is given as the reference pose's Ritz vectors: K = diag(omega_i^2) there
    omega2 = (2 * np.pi * model.frequencies) ** 2
    assert np.allclose(model.stiffness[0], np.diag(omega2), rtol=0, atol=1e-9 * omega2.max())


def test_no_instability_at_zero_and_crawling_speed(model):
    # At zero speed nothing varies; at 60 rev/min the damped modes decay over the revolution.
    result = stability_map(model, np.array([0.0, 2 * np.pi]))
    assert result.largest_modulus[0] == 1.0 and result.growth_rate[0] == 0.0
    assert result.largest_modulus[1] < 1.0
    assert result.ranges == ()


def test_damping_ratio_outside_zero_one_is_refused():
    scene = load_scene(CASES_DIR / "case1.toml")
    for zeta in (-0.1, 1.0):
        with pytest.raises(InputError, match="damping ratio"):
            periodic_model(scene, n_modes=2, poses=3, damping_ratio=zeta, elements_per_link=2)


def test_resonance_label_is_the_nearest_parametric_one():
    # f = 10, 25 Hz; 12.5 rev/s is 2 f_2 / 4 exactly (primary); 11.7 rev/s is (f_1 + f_2)/3.
    assert _nearest(np.array([10.0, 25.0]), 12.5, 6) == ((2,), 4, "primary")
    assert _nearest(np.array([10.0, 25.0]), 35.0 / 3.0, 6) == ((1, 2), 3, "combination")


@pytest.mark.parametrize("speeds, expected", [("3000:0 rev/min", "--speeds"),
                                              ("500:500 rev/min", "--speeds")])
def test_backwards_or_empty_speed_range_is_a_one_line_error(tmp_path, speeds, expected):
    from click.testing import CliRunner

    from flexlink.cli import main
    result = CliRunner().invoke(main, ["stability-map", str(CASES_DIR / "case1.toml"),
                                       "--speeds", speeds, "--out", str(tmp_path)])
    assert result.exit_code == 2
    assert expected in result.output and "Traceback" not in result.output


def test_document_lists_instability_ranges(model):
    from flexlink.output.stability_map import stability_csv, stability_document
    result = stability_map(model, np.array([0.0, 2 * np.pi]))
    document = stability_document("case 1", result, model)
    assert document["instability_ranges"] == []
    assert document["largest_modulus"][0] == 1.0
    assert stability_csv(result).count("\n") == 3
