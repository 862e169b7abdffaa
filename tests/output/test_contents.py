"""The content comparison the export tests rely on (`tests/contents.py`) sees a change of a
number past round-off, a changed picture, a changed VTK array and a missing file, and lets a
change within round-off through."""

import json
import shutil

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from flexlink.cli import main

from conftest import ROOT
from contents import RTOL, content_mismatches, folder_contents, mismatches

CASE3 = ROOT / "cases" / "case3.toml"


@pytest.fixture(scope="module")
def exports(tmp_path_factory):
    """An export of case 3 (pictures included) in a folder of its own (one-item list)."""
    out = tmp_path_factory.mktemp("first")
    done = CliRunner().invoke(main, ["export", str(CASE3), "-e", "2", "-n", "1",
                                     "--phases", "2", "--out", str(out)])
    assert done.exit_code == 0, done.output
    return [out]


def contents_of(out, copied_from=None):
    """``out``'s contents with its folder (or the one it was copied from) named OUT."""
    return folder_contents(out, {str(out): "OUT", str(copied_from or out): "OUT"})


def test_a_copy_agrees_and_names_every_kind_of_file(exports, tmp_path):
    # two whole runs agreeing is test_export_interrupted's; here the parsing of each kind
    copy = shutil.copytree(exports[0], tmp_path / "copy")
    first = contents_of(exports[0])
    assert {name.rsplit(".", 1)[1] for name in first} == {"json", "png", "pvd", "vtu"}
    assert not content_mismatches(first, contents_of(copy, exports[0]))


def test_a_number_moved_past_round_off_is_seen(exports, tmp_path):
    copy = shutil.copytree(exports[0], tmp_path / "copy")
    path = copy / "case3" / "export.json"
    document = json.loads(path.read_text())
    document["cases"][0]["frequencies_Hz"][0] *= 1 + 100 * RTOL
    path.write_text(json.dumps(document))
    found = content_mismatches(contents_of(exports[0]), contents_of(copy, exports[0]))
    assert len(found) == 1 and "frequencies_Hz" in found[0]
    # a change within round-off (a few units in the last place) is not one
    document["cases"][0]["frequencies_Hz"][0] *= (1 + 4e-16) / (1 + 100 * RTOL)
    path.write_text(json.dumps(document))
    assert not content_mismatches(contents_of(exports[0]), contents_of(copy, exports[0]))


def test_a_changed_picture_array_or_file_list_is_seen(exports, tmp_path):
    copy = shutil.copytree(exports[0], tmp_path / "copy")
    picture = copy / "case3" / "case3_mode1.png"
    with Image.open(picture) as image:
        pixels = np.asarray(image.convert("RGB")).copy()
    pixels[: pixels.shape[0] // 4] = 255 - pixels[: pixels.shape[0] // 4]  # a quarter inverted
    Image.fromarray(pixels).save(picture)
    (copy / "case3" / "case3_modes.png").unlink()
    found = content_mismatches(contents_of(exports[0]), contents_of(copy, exports[0]))
    assert len(found) == 1 and "case3_modes.png" in found[0]  # the file list first
    (copy / "case3" / "case3_modes.png").write_bytes(
        (exports[0] / "case3" / "case3_modes.png").read_bytes())
    changed = contents_of(copy, exports[0])
    grid = changed["case3/case3.vtu"]["point_data"]
    name = next(iter(grid))
    grid[name] = grid[name] * (1 + 1e-6)
    found = content_mismatches(contents_of(exports[0]), changed)
    assert sorted(f.split(":")[0] for f in found) == ["case3/case3.vtu/point_data/" + name,
                                                      "case3/case3_mode1.png"]


def test_text_integers_and_non_finite_numbers_compare_exactly():
    assert mismatches({"n": 3, "kind": "elastic"}, {"n": 4, "kind": "elastic"})
    assert mismatches({"kind": "elastic"}, {"kind": "rigid"})
    assert mismatches([1.0, float("nan")], [1.0, 2.0])
    assert not mismatches([1.0, float("nan")], [1.0, float("nan")])
    # relative to the array's scale: a round-off zero beside large entries is no difference
    assert not mismatches([1e3, 1e-14], [1e3, -2e-14])
    assert mismatches([1e3, 1e-3], [1e3, 2e-3])
