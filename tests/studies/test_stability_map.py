"""The linkage's periodic equations over one crank turn and the stability map built on them."""
import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.errors import InputError
from flexlink.scene import load_scene
from flexlink.analysis.periodic import PeriodicModel, periodic_model
from flexlink.studies.running.stability_map import _nearest, stability_map


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
    # set, not computed: at zero speed nothing varies
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
    from flexlink.output.running.stability_map import stability_csv, stability_document
    result = stability_map(model, np.array([0.0, 2 * np.pi]))
    document = stability_document("case 1", result, model)
    assert document["instability_ranges"] == []
    assert document["largest_modulus"][0] == 1.0  # zero speed: set, not computed
    assert stability_csv(result).count("\n") == 3
    # each checked mode's band over the turn: the full model's frequencies at the checked poses
    band, exact = document["frequencies_over_turn_Hz"], model.basis.exact
    assert band == {"low": exact.min(axis=0).tolist(), "high": exact.max(axis=0).tolist()}
    assert np.all(np.array(band["low"]) < np.array(band["high"]))  # the four-bar's modes move


def mathieu_model(speed_stiffness: float) -> PeriodicModel:
    """One DOF, q'' + 2 zeta omega0 q' + (omega0^2 (1 + 0.3 cos theta) + Omega^2 K2) q = 0,
    given directly (no basis): at crank speed Omega a Mathieu equation in theta."""
    angles = 2 * np.pi * np.arange(9) / 9
    omega0 = 2 * np.pi * 10.0
    K = omega0**2 * (1 + 0.3 * np.cos(angles))
    ones = np.ones((9, 1, 1))
    return PeriodicModel(angles=angles, mass=ones, coriolis=0 * ones, stiffness=K[:, None, None],
                         speed_stiffness=speed_stiffness * ones, frequencies=np.array([10.0]),
                         damping_ratio=0.001)


def test_inertia_softening_past_the_stiffness_is_labelled_divergence():
    # K2 = -0.2: K + Omega^2 K2 is negative at every angle once Omega^2 > 1.3 omega0^2 / 0.2,
    # Omega > 25.5 rev/s (at the softest angle from 18.7 rev/s, where it need not grow yet)
    revs = np.linspace(27.0, 35.0, 5)
    result = stability_map(mathieu_model(-0.2), 2 * np.pi * revs)
    assert np.all(result.stiffness_floor < 0)
    assert np.all(result.largest_modulus > 1)  # diverging at every speed of the scan
    assert [r.kind for r in result.ranges] == ["divergence"]
    assert result.ranges[0].modes == () and result.ranges[0].harmonic == 0


def test_even_pose_count_is_a_one_line_error(tmp_path):
    from click.testing import CliRunner

    from flexlink.cli import main
    result = CliRunner().invoke(main, ["stability-map", str(CASES_DIR / "case1.toml"),
                                       "--speeds", "0:3000 rev/min", "--poses", "36",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 2
    assert "--poses" in result.output and "Traceback" not in result.output
