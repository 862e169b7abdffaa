"""The scene summary checks its own shapes on construction (each wrong field refused with a
message naming it), keeps a non-planar family's modes apart from the planar model's identity,
and pools the mean |error| over scenes as one mean over every paired mode."""

import dataclasses

import numpy as np
import pytest

from flexlink.analysis.identity import ModeIdentity
from flexlink.analysis.mesh import COMMAND_LINE, MeshRule
from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene
from flexlink.studies.pose.alternatives import Alternative
from flexlink.studies.pose.scene_summary import overall_mean_abs_error, scene_summary, summary_of

from conftest import CASES_DIR

N = 3
ELEMENTS = 4  # a coarse mesh: the checks here are of shapes and bookkeeping, not of accuracy


@pytest.fixture(scope="module")
def summary():
    case = analyze(load_scene(CASES_DIR / "case1.toml"), N, ELEMENTS)
    return summary_of(case, N, MeshRule(ELEMENTS, COMMAND_LINE))


def test_a_planar_summary_has_one_entry_per_mode(summary):
    assert summary.frequencies.shape == (N,) and summary.kinds is None
    assert len(summary.identity) == N and summary.damping_ratio.shape == (N,)
    assert set(summary.errors) == set(summary.reference) == {"Ex", "FE"}
    for name, values in summary.reference.items():
        # % error of each paired mode, recomputed here from its definition
        expected = 100 * (summary.frequencies[:len(values)] - np.array(values)) / np.array(values)
        np.testing.assert_array_equal(summary.errors[name], expected)


@pytest.mark.parametrize("field, value, named", [
    ("frequencies", np.zeros((N, 1)), "frequencies"),
    ("kinds", ("in-plane",) * (N - 1), "kinds"),
    ("damping_ratio", np.zeros(N - 1), "damping_ratio"),
    ("mechanism", np.zeros((1, 1)), "mechanism"),
    ("participating", np.zeros(3), "participating"),
    ("errors", {"Ex": np.zeros(N)}, "errors"),
    ("reference", {"Ex": (1.0,) * (N + 1), "FE": (1.0,)}, "reference"),
])
def test_a_wrong_shape_is_refused_naming_the_field(summary, field, value, named):
    with pytest.raises(ValueError, match=rf"SceneSummary\.{named}"):
        dataclasses.replace(summary, **{field: value})


def test_an_identity_of_other_modes_is_refused(summary):
    ident = summary.identity
    fewer = ModeIdentity(ident.parts, ident.labels[1:], ident.strain[1:], ident.kinetic[1:],
                         ident.effective_mass[1:])
    with pytest.raises(ValueError, match=r"SceneSummary\.identity"):
        dataclasses.replace(summary, identity=fewer)


def test_error_arrays_must_match_their_reference_columns(summary):
    errors = {**summary.errors, "Ex": summary.errors["Ex"][:-1]}
    with pytest.raises(ValueError, match=r"SceneSummary\.errors\['Ex'\]"):
        dataclasses.replace(summary, errors=errors)


def test_per_mode_fields_may_be_empty_for_another_family(summary):
    other = dataclasses.replace(summary, kinds=("out-of-plane",) * N, identity=None,
                                damping_ratio=np.zeros(0))
    assert other.kinds == ("out-of-plane",) * N


def test_an_alternative_checks_its_frequencies():
    with pytest.raises(ValueError, match=r"Alternative\.frequencies"):
        Alternative("model.beam", "timoshenko", np.zeros((2, 2)), {})


def test_overall_error_is_the_mean_over_every_paired_mode(summary):
    # two scenes with different numbers of paired modes: the pooled mean weights each mode
    # once, which is not the mean of the two scenes' means
    short = dataclasses.replace(
        summary, reference={k: v[:1] for k, v in summary.reference.items()},
        errors={k: v[:1] for k, v in summary.errors.items()})
    pooled = overall_mean_abs_error([summary, short])
    for name in summary.errors:
        every = np.abs(np.concatenate([summary.errors[name], short.errors[name]]))
        assert pooled[name] == pytest.approx(every.mean(), rel=1e-15)  # same sum, same count


def test_another_family_gives_its_modes_with_their_kinds_and_no_planar_identity(tmp_path):
    scene = tmp_path / "flat.toml"
    scene.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n'
                     '[model]\nfamily = "out-of-plane"\n')
    other = scene_summary(scene, N, ELEMENTS)
    assert other.family == "out-of-plane" and other.kinds == ("out-of-plane",) * N
    assert other.identity is None and other.damping_ratio.shape == (0,)
    planar = scene_summary(scene, N, ELEMENTS, in_plane_only="this test")
    assert planar.family == "planar" and planar.kinds is None and "this test" in planar.note
    # out-of-plane bending of flat strips is softer than in-plane: the two sets differ
    assert not np.allclose(other.frequencies, planar.frequencies)
