"""A synthetic modal test of Table II case 3 (Timoshenko) correlated with the unperturbed model.

The test structure is the model perturbed (a 2 g point mass on the coupler, the crank's ground
bearing three times stiffer, a 3 % lower modulus), solved on a three times finer mesh, read at
fine-mesh nodes that are not nodes of the model's mesh, in a test frame turned 30 deg and
shifted, with 2 % noise, and written with pyuff (``scripts/make_synthetic_test.py``, run here
into a temporary file). It reads the perturbed model's nodal values directly: nothing of
``fe.sensors`` or the correlation is used to make it.

The oracle for "correctly paired" is independent of the sensors too: each test mode's partner
is the model mode it matches over the whole linkage (``analysis.mac.compare_models``: the two
models' full fields compared at stations along every link, mass-weighted), one to one.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from flexlink.analysis.correlation import PairQuality
from flexlink.analysis.mac import compare_models
from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene
from flexlink.studies.correlation.correlation import correlate_test
from flexlink.studies.correlation.measured import read_test
ROOT = Path(__file__).resolve().parents[2]

SCENE = ROOT / "scenes" / "tests" / "case3_timoshenko.toml"


def _script():
    spec = importlib.util.spec_from_file_location(
        "make_synthetic_test", ROOT / "scripts" / "make_synthetic_test.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory):
    """(the script module, the test file, its correlation with the model)."""
    script = _script()
    path = tmp_path_factory.mktemp("synthetic") / "case3_synthetic.uff"
    coordinates, readings, freqs = script.synthetic_test(seed=11, scene_path=SCENE)
    script.write_uff(path, coordinates, readings, freqs)
    scene = load_scene(SCENE)
    return script, path, correlate_test(scene, read_test(path))


@pytest.fixture(scope="module")
def oracle(synthetic):
    """Full-field MAC (truth modes x model modes) and its row-wise best partners."""
    script, _, result = synthetic
    truth_model, _, truth_shapes = script.truth_modes(SCENE)
    nominal = analyze(load_scene(SCENE), len(result.model.frequencies), 16)
    shapes = nominal.modes.shapes[:, nominal.modes.elastic[:len(result.model.frequencies)]]
    mac = compare_models(truth_model, truth_shapes, nominal.model, shapes)
    return mac


def test_every_test_mode_pairs_with_its_own_model_mode(synthetic, oracle):
    """Every one of the 8 test modes is paired, each with the model mode the full-field MAC
    says it is (a partner that wins its row by a clear margin, so the oracle is sure)."""
    _, _, result = synthetic
    best = oracle.argmax(axis=1)
    margin = np.sort(oracle, axis=1)[:, -1] - np.sort(oracle, axis=1)[:, -2]
    assert np.all(margin > 0.5)
    assert len(result.correlation.pairs) == result.test.n_modes == 8
    assert result.correlation.unpaired_test == ()
    assert [j for _, j in result.correlation.pairs] == best.tolist()


def test_the_swapped_close_pair_is_found_and_pairing_by_order_gets_it_wrong(synthetic, oracle):
    """The model's rocker bending 2 (776 Hz) and coupler bending 4 (791 Hz) are 2 % apart; the
    test's point mass drops the coupler mode below the rocker mode, so test modes 6 and 7 are
    model modes 7 and 6. MAC pairing finds that; pairing by mode order puts test 6 with model
    6 and test 7 with model 7, shapes whose MAC is below 0.1, and so compares the frequencies
    of different modes."""
    _, _, result = synthetic
    pairs = dict(result.correlation.pairs)
    assert (pairs[5], pairs[6]) == (6, 5)
    assert oracle[5].argmax() == 6 and oracle[6].argmax() == 5
    assert "coupler bending 4" in result.model.labels[6]
    assert "rocker bending 2" in result.model.labels[5]
    by_order = {i: (j, v) for i, j, v in result.by_order}
    assert by_order[5][0] == 5 and by_order[6][0] == 6
    assert by_order[5][1] < 0.1 and by_order[6][1] < 0.1
    accepted = dict(zip(result.correlation.pairs, result.correlation.pair_mac))
    assert accepted[(5, 6)] >= 0.7 and accepted[(6, 5)] >= 0.9


def test_pair_errors_are_the_model_against_the_test_frequencies(synthetic):
    """error % = model / test - 1 of the paired frequencies; the test's frequencies are the
    perturbed model's, written with six significant digits (UFF 55)."""
    script, _, result = synthetic
    _, truth, _ = script.truth_modes(SCENE)
    np.testing.assert_allclose(result.test.frequencies, truth, rtol=5e-6)
    for (i, j), e in zip(result.correlation.pairs, result.errors_pct()):
        assert e == pytest.approx(100 * (result.model.frequencies[j] / truth[i] - 1), abs=1e-3)


def test_good_pairs_and_no_aliasing_with_these_sensors(synthetic):
    """All pairs but the shifted coupler mode (whose shape the 2 g mass changes most) are
    good; 20 sensors in two directions tell the 8 test modes apart (no autoMAC >= 0.7)."""
    _, _, result = synthetic
    quality = dict(zip(result.correlation.pairs, result.correlation.pair_quality))
    assert sum(q is PairQuality.GOOD for q in quality.values()) >= 7
    assert result.correlation.aliased == ()


def test_sensors_sit_on_the_links_they_were_taken_from(synthetic):
    """The script takes 4, 10 and 6 sensors from the crank, coupler and rocker; placed by
    the scene's [test] frame (30 deg, offset, mm) they land on those links, on the axis
    (within the UFF 15 coordinates' six digits: 1e-4 mm of 300 mm)."""
    _, _, result = synthetic
    links = [result.model.solved[0].model.links[k].name for k in result.sensors.placement.link]
    assert links == ["crank"] * 4 + ["coupler"] * 10 + ["rocker"] * 6
    assert result.sensors.placement.distance.max() < 2e-6
