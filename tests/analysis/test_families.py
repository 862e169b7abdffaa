"""Model families from their contract: the 3D spectrum is the sorted union of the in-plane and
out-of-plane ones, each part's modes obey the Rayleigh quotient on the model ``part_model``
builds, and ``paired`` merges parts by frequency with NaN where modes run out."""

import math

import numpy as np
import pytest

from flexlink.analysis.families import (PartModes, elastic_modes, in_plane_only_note,
                                        paired, part_model, part_modes, quadratic_forms)
from flexlink.fe.motions import Part
from flexlink.scene import load_scene

from conftest import CASES_DIR

CASE3 = CASES_DIR / "case3.toml"
ELEMENTS = 6  # coarse: the claims hold on any mesh


def family_scene(family):
    return load_scene(CASE3, overrides={"model.family": family})


def test_paired_merges_parts_in_frequency_order():
    parts = (PartModes(Part.IN_PLANE, None, np.array([10.0, 30.0]), np.zeros((3, 2))),
             PartModes(Part.OUT_OF_PLANE, None, np.array([5.0, 20.0, 40.0]), np.zeros((3, 3))))
    freqs, pairs = paired(parts, 4)
    np.testing.assert_array_equal(freqs, [5.0, 10.0, 20.0, 30.0])  # merged, not computed
    assert pairs == ((1, 0), (0, 0), (1, 1), (0, 1))
    # more asked than the parts hold: NaN for the missing ones, one pair per mode found
    freqs, pairs = paired(parts, 7)
    np.testing.assert_array_equal(freqs[:5], [5.0, 10.0, 20.0, 30.0, 40.0])
    assert np.isnan(freqs[5:]).all() and len(pairs) == 5


def test_three_d_spectrum_is_the_union_of_the_parts():
    n = 4
    planar, _ = elastic_modes(family_scene("planar"), n, ELEMENTS)
    strip, _ = elastic_modes(family_scene("out-of-plane"), n, ELEMENTS)
    both, kinds = elastic_modes(family_scene("3d"), n, ELEMENTS)
    union = sorted([(f, Part.IN_PLANE) for f in planar] + [(f, Part.OUT_OF_PLANE) for f in strip])
    # the same eigen solves: equal to round-off
    np.testing.assert_allclose(both, [f for f, _ in union[:n]], rtol=1e-12)
    assert kinds == tuple(p for _, p in union[:n])
    assert Part.IN_PLANE in kinds and Part.OUT_OF_PLANE in kinds  # case 3 interleaves them


@pytest.mark.parametrize("part", [Part.IN_PLANE, Part.OUT_OF_PLANE])
def test_each_mode_is_a_rayleigh_quotient_on_the_part_model(part):
    scene = family_scene("3d")
    (found,) = [p for p in part_modes(scene, 3, ELEMENTS) if p.part is part]
    assert len(found.frequencies) == 3 and found.shapes.shape[1] == 3  # the lowest 3, no more
    assert np.all(np.diff(found.frequencies) > 0)  # ascending elastic modes
    model = part_model(scene, part, ELEMENTS)
    q_K, q_M = quadratic_forms(part, model, found.shapes)
    # s^T K s / s^T M s = omega^2 for an eigenvector; the solve's residual is ~1e-10 relative
    np.testing.assert_allclose(q_K / q_M, (2 * math.pi * found.frequencies) ** 2, rtol=1e-8)


def test_in_plane_only_note_names_the_family():
    assert in_plane_only_note(family_scene("planar"), "the map") is None
    note = in_plane_only_note(family_scene("3d"), "the map")
    assert note.startswith("model.family = '3d': the map holds the in-plane modes only")


def test_out_of_plane_modes_are_the_same_by_either_solver_path():
    # small models go straight into dense reduced matrices, others through sparse assembly:
    # the same K and M, so the same spectrum to the eigen solvers' round-off
    from flexlink.analysis.eigensolver import EigenSolver
    from flexlink.analysis.outofplane import analyze_out_of_plane

    scene = family_scene("out-of-plane")
    dense = analyze_out_of_plane(scene, 4, ELEMENTS, EigenSolver("dense"))
    sparse = analyze_out_of_plane(scene, 4, ELEMENTS, EigenSolver("sparse"))
    assert not EigenSolver("sparse").assembles_dense(1)  # the sparse path was taken
    np.testing.assert_allclose(sparse.elastic_frequencies[:4], dense.elastic_frequencies[:4],
                               rtol=1e-10)
    assert sparse.kinds == dense.kinds
