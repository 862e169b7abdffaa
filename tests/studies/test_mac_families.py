"""MAC within one model family: the out-of-plane stations sample the strip model's exact
fields, `flexlink mac --family out-of-plane` pairs two meshes, and a comparison across
families is refused with a clear InputError."""

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.analysis.mac import compare_models, out_of_plane_stations
from flexlink.cli import main
from flexlink.errors import InputError
from flexlink.fe.motions import Part
from flexlink.fe.strip import StripProperties
from flexlink.scene import load_scene
from flexlink.studies.pose.mac_comparison import mac_part

from helpers import single_beam

from conftest import ROOT
CASE3 = ROOT / "cases" / "case3.toml"


def test_out_of_plane_stations_sample_the_exact_fields():
    # nodal values of w = cubic (with ty = -dw/dx) and twist = linear on an inclined beam, in
    # global (w, rx, ry): the stations must return the fields themselves
    angle, L, per_link = 0.6, 1.0, 10
    model = single_beam("free-free", 4, angle=angle)
    x = np.linspace(0, L, 5)
    w = lambda s: 2e-3 - 1e-3 * s + 3e-3 * s**2 - 4e-3 * s**3  # noqa: E731
    dw = lambda s: -1e-3 + 6e-3 * s - 12e-3 * s**2  # noqa: E731
    tx = lambda s: 5e-3 - 2e-3 * s  # noqa: E731
    ty = -dw(x)
    c, s = math.cos(angle), math.sin(angle)
    # local (tx, ty) = R (rx, ry) with R = [[c, s], [-s, c]]: global = R^T local
    rx, ry = c * tx(x) - s * ty, s * tx(x) + c * ty
    shapes = np.column_stack([w(x), rx, ry]).ravel()[:, None]
    values, weights, names = out_of_plane_stations(model, shapes, per_link)
    where = np.linspace(0, L, per_link + 1)
    np.testing.assert_allclose(values[:per_link + 1, 0], w(where), rtol=0, atol=1e-17)
    np.testing.assert_allclose(values[per_link + 1:, 0], tx(where), rtol=0, atol=1e-17)
    # the weights add up to the link's mass and its rotary inertia about its axis
    strip = StripProperties.of(model.links[0].section)
    assert weights[:per_link + 1].sum() == pytest.approx(strip.rhoA * L, rel=1e-14)
    assert weights[per_link + 1:].sum() == pytest.approx(strip.rhoIp * L, rel=1e-14)
    assert names == ("beam",)
    # a shape compared with itself: MAC 1
    assert compare_models(model, shapes, model, shapes, part=Part.OUT_OF_PLANE)[0, 0] == \
        pytest.approx(1.0, rel=1e-14)


def test_mac_part_resolves_auto_and_refuses_across_families():
    planar = load_scene(CASE3)
    strip = load_scene(CASE3, overrides={"model.family": "out-of-plane"})
    both = load_scene(CASE3, overrides={"model.family": "3d"})
    assert mac_part(planar, planar) is Part.IN_PLANE
    assert mac_part(strip, strip) is Part.OUT_OF_PLANE
    assert mac_part(planar, strip, Part.OUT_OF_PLANE) is Part.OUT_OF_PLANE  # asked: both have it
    with pytest.raises(InputError, match="different model families.*means nothing"):
        mac_part(planar, strip)
    with pytest.raises(InputError, match="model.family.*3d.*--part in-plane") as refused:
        mac_part(both, planar)
    # the refusal names the file and the key that hold the family, not only its text
    assert (refused.value.source, refused.value.field) == (both.path, "model.family")


def test_mac_command_compares_out_of_plane_modes_of_two_meshes(tmp_path):
    result = CliRunner().invoke(main, ["mac", str(CASE3), str(CASE3), "-e", "8", "--elements-b",
                                       "16", "-n", "3", "--part", "out-of-plane", "--json",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["part"] == "out-of-plane"
    assert [(p["a"], p["b"]) for p in doc["pairs"]] == [(1, 1), (2, 2), (3, 3)]
    assert min(p["mac"] for p in doc["pairs"]) > 0.99
    mac = np.array(doc["mac"])
    assert np.abs(mac - np.diag(np.diag(mac))).max() < 0.01
    # the frequencies are the strip model's, not the frame's (case 3's first in-plane mode is
    # near 668 Hz, its first out-of-plane one near 35 Hz)
    assert doc["a"]["modes"][0]["Hz"] < 100


def test_mac_command_still_takes_the_old_family_spelling_with_a_deprecation_note(tmp_path):
    args = ["mac", str(CASE3), str(CASE3), "-e", "4", "-n", "2", "--json", "--out", str(tmp_path)]
    new = CliRunner().invoke(main, args + ["--part", "out-of-plane"])
    old = CliRunner().invoke(main, args + ["--family", "out-of-plane"])
    assert new.exit_code == old.exit_code == 0, old.output
    assert "deprecated" in old.stderr and "--part" in old.stderr and "deprecated" not in new.stderr
    strip = json.loads(old.stdout)
    assert strip["part"] == "out-of-plane"
    assert strip["mac"] == json.loads(new.stdout)["mac"]


def test_mac_command_refuses_a_cross_family_comparison(tmp_path):
    other = tmp_path / "strip.toml"
    other.write_text(f'base = "{CASE3.as_posix()}"\n[model]\nfamily = "out-of-plane"\n')
    result = CliRunner().invoke(main, ["mac", str(CASE3), str(other), "-e", "4",
                                       "--out", str(tmp_path)])
    assert result.exit_code == 2, result.output
    assert "different model families" in result.output
