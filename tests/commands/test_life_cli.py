"""``flexlink life``: bad input is one line naming the file or field, exit 2, and nothing
already written is lost; a run writes its files and one JSON document, worst link first."""
import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import CASES_DIR

from flexlink.cli import main

ROOT = Path(__file__).resolve().parents[2]
CASE3 = str(CASES_DIR / "case3.toml")


def _rotor(tmp_path, material='isotropic = "aisi_1020_cd"') -> str:
    text = (ROOT / "scenes/rotor.toml").read_text()
    text = text.replace("elements_per_link = 32", "elements_per_link = 6")
    text = text.replace('[material]\nE = "200 GPa"\ndensity = "7800 kg/m^3"',
                        f"[material]\n{material}")
    text += ('\n[[loads]]\nkind = "force"\nlink = "rotor"\nforce = ["0 N", "40 N"]\n'
             'at = ["1 m", "0 m"]\nframe = "global"\n')
    path = tmp_path / "rotor.toml"
    path.write_text(text)
    return str(path)


def _run(args):
    return CliRunner().invoke(main, ["life", *args])


def _one_line(result, words):
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    for word in words:
        assert word in lines[0], lines[0]


@pytest.mark.parametrize("args, words", [
    (["--reliability", "1.5"], ["--reliability"]),
    (["--reliability", "0"], ["--reliability"]),
    (["--hours", "-3"], ["--hours"]),
    (["--hours", "nan"], ["--hours"]),
    (["--speed", "600 m"], ["--speed"]),
])
def test_bad_options_are_one_line_and_lose_nothing(tmp_path, args, words):
    out = tmp_path / "out"
    folder = out / "rotor"
    folder.mkdir(parents=True)
    (folder / "life.json").write_text("earlier")
    _one_line(_run([_rotor(tmp_path), "--speed", "60 rev/min", *args, "--out", str(out)]),
              words)
    assert (folder / "life.json").read_text() == "earlier"


def test_a_material_without_strength_is_refused_naming_file_and_key(tmp_path):
    scene = _rotor(tmp_path, material='E = "200 GPa"\ndensity = "7800 kg/m^3"')
    _one_line(_run([scene, "--out", str(tmp_path / "out")]), ["rotor.toml", "material",
                                                              "strength"])
    bare = tmp_path / "bare.toml"
    bare.write_text('name = "bare"\nE = { mean = "200 GPa" }\nG = { mean = "80 GPa" }\n'
                    'density = { mean = "7800 kg/m^3" }\npoisson = { mean = 0.3 }\n'
                    '[strength]\nSut = { mean = "600 MPa" }\nSy = { mean = "700 MPa" }\n'
                    'endurance_limit = { mean = "300 MPa" }\n'
                    'fatigue_coefficient = { mean = "900 MPa" }\n')
    scene = _rotor(tmp_path, material=f'isotropic = "{bare}"')
    _one_line(_run([scene, "--out", str(tmp_path / "out")]), ["bare.toml", "strength.Sy"])
    bare.write_text(bare.read_text().replace('"700 MPa"', '"500 MPa", low = "520 MPa"'))
    _one_line(_run([scene, "--out", str(tmp_path / "out")]), ["bare.toml", "strength.Sy"])


def test_a_speed_without_steady_state_names_the_unstable_range(tmp_path):
    """Table II case 3 at 3000 rev/min: the stability map's range starts at 2900 rev/min
    (docs/critical-speeds.md); the refusal names the run of unstable speeds around it."""
    result = _run([CASE3, "--speed", "3000 rev/min", "--no-estimate", "--out", str(tmp_path)])
    _one_line(result, ["no steady state at 3000 rev/min", "unstable range"])
    low = float(result.output.split("unstable range ")[1].split(" to ")[0])
    assert 2850 < low < 3000
    assert not (tmp_path / "case3" / "life.json").exists()


def test_a_run_writes_the_field_and_orders_links(tmp_path):
    result = _run([_rotor(tmp_path), "--speed", "60 rev/min", "--hours", "1000", "--json",
                   "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    [link] = document["links"]
    assert link["kind"] == "metal" and link["safety_factor"] > 0
    assert document["conditions"]["required_hours"] == 1000
    assert "mode acceleration" in document["included"]
    assert document["peak_stress_error"]["met"] in (True, False)
    folder = tmp_path / "out" / "rotor"
    for name in ("life.csv", "life.pvd", "life_haigh.png", "life_stress.png", "life.json"):
        assert (folder / name).stat().st_size > 0
    rows = (folder / "life.csv").read_text().splitlines()
    assert len(rows) == 1 + 180 * 6 * 2 * 2  # angles x elements x ends x fibres
    pvd = (folder / "life.pvd").read_text()
    assert pvd.count("<DataSet") == 180


def test_an_all_composite_scene_gets_no_haigh_diagram(tmp_path):
    """A composite link has no Goodman line: no empty Haigh picture is written for Table II
    case 3 (all three links carbon/polyester), and the stress maps still are."""
    result = _run([CASE3, "--speed", "600 rev/min", "--no-estimate", "--json",
                   "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    files = {Path(f).name for f in json.loads(result.stdout)["files"]}
    assert "life_stress.png" in files and "life_haigh.png" not in files
    assert not (tmp_path / "out" / "case3" / "life_haigh.png").exists()


def test_speeds_give_the_margin_against_speed(tmp_path):
    result = _run([CASE3, "--speeds", "300:3000 rev/min", "--count", "4", "--json", "--out",
                   str(tmp_path)])
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    margins = document["smallest_margin"]
    assert len(margins) == 4 and margins[-1] is None  # 3000 rev/min: no steady state
    assert all(m > 1 for m in margins[:3])
    assert document["unstable_ranges_rev_per_min"]
