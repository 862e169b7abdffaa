"""A scene read once and varied by overrides (the calibration and Monte Carlo path) is the same
scene as one written with those values, and a changed file is read again."""

import os
from pathlib import Path

import pytest

from flexlink.errors import InputError
from flexlink.scene import load_scene
from flexlink.scene.load import load_overridden
from flexlink.scene.source import read_scene_source

from conftest import CASES_DIR as CASES


def copy_case(tmp_path, extra=""):
    (tmp_path / "_table2.toml").write_text((CASES / "_table2.toml").read_text())
    path = tmp_path / "case2.toml"
    path.write_text((CASES / "case2.toml").read_text() + extra)
    return path


def test_override_equals_the_value_written_in_the_file(tmp_path):
    path = copy_case(tmp_path)
    over = {"section.width": "25 mm", "joints.Kt": "3e7 N/m", "linkage.ground": "0.35 m"}
    varied = load_overridden(read_scene_source(path), over)
    text = (tmp_path / "_table2.toml").read_text()
    text = text.replace('width = { value = "20 mm"', 'width = { value = "25 mm"')
    text = text.replace('ground = { value = "300 mm"', 'ground = { value = "0.35 m"')
    (tmp_path / "_table2.toml").write_text(text)
    written = load_scene(path, overrides={"joints.Kt": "3e7 N/m"})  # the file changed: re-read
    assert varied.sections == written.sections
    assert varied.four_bar == written.four_bar
    assert varied.joints == written.joints
    # the overridden values are no longer the file's assumptions
    fields = {a.field for a in varied.assumptions}
    assert "section.width" not in fields and "linkage.ground" not in fields
    assert "section.ply_thickness" in fields


def test_overrides_do_not_leak_into_the_next_load(tmp_path):
    path = copy_case(tmp_path)
    load_scene(path, overrides={"section.width": "40 mm", "material": {"E": "70 GPa",
                                                                      "density": "2700 kg/m^3"}})
    again, fresh = load_scene(path), load_scene(CASES / "case2.toml")
    assert again.sections == fresh.sections


def test_overrides_still_validated(tmp_path):
    path = copy_case(tmp_path)
    with pytest.raises(InputError, match="section.width"):
        load_scene(path, overrides={"section.width": "-3 mm"})
    with pytest.raises(InputError, match="widht"):
        load_scene(path, overrides={"section.widht": "3 mm"})


def test_changed_file_is_read_again(tmp_path):
    path = copy_case(tmp_path)
    before = load_scene(path)
    base = tmp_path / "_table2.toml"
    base.write_text(base.read_text().replace('value = "20 mm"', 'value = "30 mm"'))
    stat = base.stat()
    os.utime(base, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))  # a coarse clock
    after = load_scene(path)
    assert after.sections["crank"].strip[0] == pytest.approx(0.030)  # (width, thickness)
    assert before.sections["crank"].strip[0] == pytest.approx(0.020)


def _read_every_time(path, overrides):
    """The scene as read before files were kept: parse, apply overrides, strip notes."""
    from flexlink.scene import source

    data, origin = source._with_bases(Path(path))
    for field, value in overrides.items():
        source._set_dotted(data, origin, field, value)
    found = []
    plain = source._strip_notes(data, origin, "", found)
    return source.SceneSource(path=Path(path), data=plain, origin=origin,
                              assumptions=tuple({(a.field, a.value): a for a in found}.values()))


def test_same_frequencies_as_reading_every_time():
    """Calibration and Monte Carlo numbers do not change with the read-once path: the same
    scene, so the same frequencies to the round-off of two dense eigen solves (1e-13; a value
    read differently, such as a unit or an override lost, moves them by far more)."""
    import numpy as np

    from flexlink.analysis.families import elastic_modes
    from flexlink.scene.load import BUILDERS, validate

    over = {"model.family": "planar", "section.width": "23.5 mm", "joints.Kr": "0.7 N*m/rad",
            "material": {"E": "61e9 Pa", "G": "4e9 Pa", "density": "1500 kg/m^3"}}
    for case in ("case1.toml", "case3.toml"):
        path = CASES / case
        src = _read_every_time(path, over)
        sf = validate(src)
        before = elastic_modes(BUILDERS[sf.linkage.type](src, sf), 4, 6)[0]
        load_scene(path)  # warm
        after = elastic_modes(load_scene(path, overrides=over), 4, 6)[0]
        np.testing.assert_allclose(after, before, rtol=1e-13, atol=0)
