"""The README's scene written from scratch is a working scene, and says what it shows."""

import re
from pathlib import Path

import pytest

from flexlink.analysis.modal import analyze
from flexlink.scene import load_scene

from conftest import ROOT


def readme_scene(tmp_path) -> Path:
    text = (ROOT / "README.md").read_text()
    section = text[text.index("## Writing a scene"):]
    block = re.search(r"```toml\n(.*?)```", section, re.S).group(1)
    path = tmp_path / "from_scratch.toml"
    path.write_text(block)
    return path


def test_readme_scene_loads_and_solves(tmp_path):
    scene = load_scene(readme_scene(tmp_path))
    assert scene.kind == "four-bar" and scene.four_bar.lengths == pytest.approx((0.3, 0.075, 0.27, 0.18))
    assert scene.rigid_pose().mu == pytest.approx(1.5707963267948966, abs=1e-12)
    sections = scene.sections
    assert sections["coupler"].depth == pytest.approx(0.008)  # the per-link override
    assert sections["crank"].depth == pytest.approx(0.012)  # the shared section
    assert sections["crank"].E == pytest.approx(210e9)  # shipped steel
    masses = {j.name: j.mass for j in scene.joints}
    assert masses == {"O2": 0.0, "A": 0.012, "B": 0.0, "O4": 0.0}
    # the loss factor comes from the steel file, not the scene: listed as assumed
    assert {a.field for a in scene.assumptions} == {"pose.branch", "joints.Kt",
                                                    "material.loss_factor"}
    result = analyze(scene, 3, 8)
    assert len(result.elastic_frequencies(3)) == 3
