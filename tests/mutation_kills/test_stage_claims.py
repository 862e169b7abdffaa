"""Claims of the scene, fe and analysis stages that their own tests let mutants break
(docs/testing.md, mutation testing): closed forms, the scene's stated conventions and the
messages' contents, each checked against an independent value."""

import math

import numpy as np
import pytest

from conftest import CASES_DIR
from flexlink.analysis.sweep import craig_bampton_refusal
from flexlink.errors import InputError
from flexlink.fe.truncation import _horner
from flexlink.scene import load_scene
from flexlink.scene.parts import tube_shear_factor
from flexlink.scene.schema import SceneFile


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45])
def test_tube_shear_factor_meets_cowpers_solid_and_thin_wall_limits(nu):
    """Cowper (1966): a solid round section has k = 6 (1 + nu) / (7 + 6 nu) (0.886 at
    nu = 0.3); a thin-walled tube, inner -> outer, k = 2 (1 + nu) / (4 + 3 nu) (0.53)."""
    assert tube_shear_factor(0.01, 0.0, nu) == pytest.approx(6 * (1 + nu) / (7 + 6 * nu),
                                                             rel=1e-14)  # rounding only
    assert tube_shear_factor(0.01, 0.01, nu) == pytest.approx(2 * (1 + nu) / (4 + 3 * nu),
                                                              rel=1e-14)


def test_a_four_bar_cycle_starts_at_crank_angle_zero_whatever_pose_it_analyses():
    """The scene's stated convention: a four-bar sweep runs over crank angles 0 to 360 deg, so
    its origin is the pose at 0 deg, not the analysed pose (here mu = 90 deg)."""
    scene = load_scene(CASES_DIR / "case1.toml")
    assert scene.start != 0.0  # the analysed pose is elsewhere
    angle, joints = scene.cycle_origin()
    assert angle == 0.0
    at_zero = scene.rigid_pose(0.0).joints
    for name, point in joints.items():
        np.testing.assert_allclose(point, at_zero[name], atol=1e-12)  # metres, round-off


def test_the_craig_bampton_refusal_names_the_beam_theory_it_cannot_take():
    scene = load_scene(CASES_DIR / "case1.toml", overrides={"model.beam": "timoshenko"})
    # the whole sentence the cycle map prints: what was refused, and what was done instead
    assert craig_bampton_refusal(scene.topology(4)) == (
        "the Craig-Bampton reduction takes Euler-Bernoulli links only, not timoshenko ones: "
        "the full model was solved at every pose")
    assert craig_bampton_refusal(load_scene(CASES_DIR / "case1.toml").topology(4)) is None


def test_horner_gives_a_polynomial_and_its_derivative():
    """Against numpy's polynomial class: p(x) = sum_j c_j x^j and p'(x), on arrays of terms
    as the truncation series uses them (one polynomial per column)."""
    rng = np.random.default_rng(3)
    terms = rng.normal(size=(4, 5))
    lam = rng.uniform(-2.0, 2.0, size=5)
    value, slope = _horner(lam, terms)
    for j in range(5):
        p = np.polynomial.Polynomial(terms[:, j])
        assert value[j] == pytest.approx(p(lam[j]), rel=1e-12, abs=1e-12)
        assert slope[j] == pytest.approx(p.deriv()(lam[j]), rel=1e-12, abs=1e-12)


def test_whole_number_keys_are_integers_in_the_editor_schema():
    """An editor validating a scene with the JSON schema must refuse 2.5 elements, as
    flexlink does: whole-number keys carry the JSON type "integer"."""
    props = SceneFile.model_json_schema()["$defs"]["MeshTable"]["properties"]
    (choice,) = [c for c in props["elements_per_link"]["anyOf"] if c.get("type") != "null"]
    assert choice["type"] == "integer" and choice["minimum"] == 1
    assert math.isfinite(choice["maximum"])


@pytest.mark.parametrize("written, words", [('"5"', "a plain number, no unit"),
                                            ('"5 mm"', "a plain number, no unit"),
                                            ("true", "expected a whole number")])
def test_a_plain_number_key_refuses_text_and_booleans(tmp_path, written, words):
    """The schema's plain numbers (here the ply count) take a TOML number only: text, even a
    number in quotes, and true/false are refused in one line naming the key."""
    path = tmp_path / "plies.toml"
    path.write_text(f'base = "{(CASES_DIR / "case1.toml").as_posix()}"\n[section]\n'
                    f"plies = {written}\n")
    with pytest.raises(InputError) as info:
        load_scene(path)
    message = str(info.value)
    assert "section.plies" in message and words in message and "\n" not in message, message


def test_a_craig_bampton_sweep_solves_the_poses_outside_its_sample(monkeypatch):
    """A sweep longer than its sample (SAMPLE poses set the basis of the others) must answer
    at every pose as the full model does: within 1e-6, the reduction's tolerance (the mesh
    rule's own discretisation error; tests/fe/test_craig_bampton.py). Six poses with a
    sample of two leave four to the second pass."""
    from flexlink.analysis import sweep

    monkeypatch.setattr(sweep, "SAMPLE", 2)
    scene = load_scene(CASES_DIR / "case1.toml")
    poses = [scene.rigid_pose(t).joints for t in np.radians(np.arange(6) * 60.0 + 0.5)]
    topology = scene.topology(8)
    full = sweep.modal_sweep(topology, poses, 4).frequencies
    reduced = sweep.modal_sweep(topology, poses, 4, reduction="craig-bampton").frequencies
    assert np.isfinite(reduced).all()
    np.testing.assert_allclose(reduced, full, rtol=1e-6)


def test_a_folder_of_base_files_only_says_what_would_run(tmp_path):
    """Base files (names starting with '_') are never run alone: a folder holding only those
    is refused naming the folder, the base files and what it should hold instead."""
    from flexlink.scene.load import scene_files

    (tmp_path / "_shared.toml").write_text("")
    with pytest.raises(InputError) as info:
        scene_files([tmp_path])
    assert info.value.source == str(tmp_path) and "_shared.toml" in str(info.value)
    assert info.value.expected and "not starting with '_'" in info.value.expected
