"""The report's "Stress and life" section: present for a scene that declares a speed and whose
materials give strengths (Table II case 3 with a speed: composite links, strength ratios and no
life), absent for one without a speed."""

import re

import pytest
from click.testing import CliRunner

from conftest import CASES_DIR
from flexlink.cli import main


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    folder = tmp_path_factory.mktemp("scenes")
    text = (CASES_DIR / "case3.toml").read_text()
    text = text.replace('base = "_table2.toml"',
                        f'base = "{(CASES_DIR / "_table2.toml").as_posix()}"')
    (folder / "case3_speed.toml").write_text(
        text + '\n[operation]\ncrank_speed = "600 rev/min"\n')
    out = tmp_path_factory.mktemp("report")
    result = CliRunner().invoke(main, ["report", str(folder / "case3_speed.toml"),
                                       str(CASES_DIR / "case1.toml"), "-e", "2", "-n", "2",
                                       "--cycle-poses", "0", "--out", str(out)])
    assert result.exit_code == 0, result.output
    return (out / "report.html").read_text()


def _scene(html: str, stem: str) -> str:
    return re.search(rf'<section class="scene" id="scene-{stem}">(.*?)</section>', html,
                     re.S).group(1)


def test_stress_and_life_for_the_scene_with_a_speed_and_strengths(page):
    section = _scene(page, "case3_speed")
    assert "<h3>Stress and life</h3>" in section
    assert 'id="fig-case3_speed-life"' in page
    table = section[section.index("link (worst first)"):]
    assert table.count("none*") == 3  # three composite links, no life without a curve
    assert "no life is given without a measured fatigue curve" in section
    assert "Stress and life" not in _scene(page, "case1")
