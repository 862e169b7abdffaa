"""The editor schema (docs/scene.schema.json, from ``flexlink schema``) as an editor uses it:
taplo, the checker behind Even Better TOML, accepts every shipped scene (whose keys may come
from a base file it cannot follow) and flags typos, unit slips and misspelt link names with a
message naming the offending key or value."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT

SCHEMA = ROOT / "docs" / "scene.schema.json"


def _taplo() -> str:
    found = shutil.which("taplo") or shutil.which("taplo", path=str(Path(sys.executable).parent))
    if found is None:
        pytest.skip("taplo is not installed: pip install -e '.[test]' (scripts/test.sh does), "
                    "or bash scripts/taplo-check.sh")
    return found


def check(*args, cwd=ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([_taplo(), "check", "--colors", "never", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=120)


SHIPPED = sorted(str(p.relative_to(ROOT)) for d in ("cases", "scenes") for p in (ROOT / d).glob("*.toml"))


def test_every_shipped_scene_passes_with_the_repository_config():
    run = check(*SHIPPED)  # .taplo.toml applies the schema to all but the base files
    assert run.returncode == 0, run.stderr
    assert f"found files total={len(SHIPPED)}" in run.stderr, run.stderr


def test_the_repository_config_applies_the_schema_to_scene_folders(tmp_path):
    """A typo in a copy of a shipped scene under cases/ is flagged with the repository's own
    .taplo.toml: the config's rule reaches the shipped scenes (not only a clean run)."""
    (tmp_path / "docs").mkdir()
    (tmp_path / "cases").mkdir()
    (tmp_path / ".taplo.toml").write_bytes((ROOT / ".taplo.toml").read_bytes())
    (tmp_path / "docs" / "scene.schema.json").write_bytes(SCHEMA.read_bytes())
    for name in ("_table2.toml", "case1.toml"):
        text = (ROOT / "cases" / name).read_text()
        (tmp_path / "cases" / name).write_text(text.replace("R4 = 0.667", "R44 = 0.667"))
    run = check("cases/case1.toml", "cases/_table2.toml", cwd=tmp_path)
    assert run.returncode != 0 and "'R44' was unexpected" in run.stderr, run.stderr


# a scene whose every other key comes from the Table II base file: the editor cannot follow
# `base`, so nothing it would supply may be required
BASED = 'base = "_table2.toml"\n[linkage]\nR2 = 0.267\nR3 = 0.8\nR4 = 0.667\n'
FOUR_BAR = '[linkage]\nground = "300 mm"\ncrank = "100 mm"\ncoupler = "250 mm"\nrocker = "150 mm"\n'

TYPOS = {
    "misspelt key": (BASED + '[section]\nwidht = "3 mm"\n', "'widht' was unexpected"),
    "negative length": (FOUR_BAR.replace('"100 mm"', '"-5 mm"'), '"-5 mm" does not match'),
    "unit without a number": (FOUR_BAR.replace('"100 mm"', '"mm"'), '"mm" does not match'),
    "wrong unit kind": (FOUR_BAR.replace('"100 mm"', '"5 kg"'), '"5 kg" does not match'),
    "misspelt link": (FOUR_BAR + '[links.cranck.section]\nwidth = "3 mm"\n',
                      '"cranck" is not one of ["crank","coupler","rocker"]'),
    "misspelt drive link": (FOUR_BAR + '[drive]\nlink = "cranck"\n',
                            '"cranck" is not one of ["crank","coupler","rocker"]'),
    "misspelt joint": (FOUR_BAR + '[joints.O5]\nmass = "1 g"\n', '"O5" is not one of'),
    "key of the other kind": (FOUR_BAR + 'grond = "1 m"\n', "'grond' was unexpected"),
    "typo inside a noted value": (BASED + '[section]\nwidth = { value = "3 mm", nte = "x" }\n',
                                  "'nte' was unexpected"),
    # flexlink refuses a zero where the schema says > 0: so does the editor
    "zero crank speed": (FOUR_BAR + '[operation]\ncrank_speed = "0 rev/min"\n',
                         '"0 rev/min" does not match'),
    "zero length": (FOUR_BAR.replace('"100 mm"', '"0.0 mm"'), '"0.0 mm" does not match'),
    "pair of the wrong kind": ('[linkage]\ntype = "general"\n[linkage.guess]\na = ["1 mm", "2 kg"]\n',
                               '"2 kg" does not match'),
}


@pytest.mark.parametrize("name", sorted(TYPOS))
def test_taplo_names_the_offending_key_or_value(tmp_path, name):
    text, message = TYPOS[name]
    (tmp_path / "_table2.toml").write_bytes((ROOT / "cases" / "_table2.toml").read_bytes())
    path = tmp_path / "typo.toml"
    path.write_text(text)
    run = check("--no-auto-config", "--schema", SCHEMA.as_uri(), str(path), cwd=tmp_path)
    assert run.returncode != 0, run.stderr
    errors = [line for line in run.stderr.splitlines() if line.startswith("error:")]
    assert errors and all(message in line for line in errors), run.stderr


def test_the_untouched_scenes_of_the_typo_files_pass(tmp_path):
    """The typo files' bases are valid: each message above comes from the typo alone."""
    (tmp_path / "_table2.toml").write_bytes((ROOT / "cases" / "_table2.toml").read_bytes())
    for i, text in enumerate((BASED, FOUR_BAR, '[linkage]\ntype = "general"\n')):
        (tmp_path / f"ok{i}.toml").write_text(text)
    run = check("--no-auto-config", "--schema", SCHEMA.as_uri(), "ok0.toml", "ok1.toml",
                "ok2.toml", cwd=tmp_path)
    assert run.returncode == 0, run.stderr


def test_schema_command_advice_points_at_the_file_it_wrote(tmp_path):
    from click.testing import CliRunner

    from flexlink.cli import main

    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["schema", "--out", str(out)])
    assert result.exit_code == 0, result.output
    written = out / "scene.schema.json"
    assert written.is_file()
    assert f"#:schema {written.resolve()}" in result.output, result.output
    # and the advice works: taplo follows that directive
    scene = tmp_path / "s.toml"
    scene.write_text(f"#:schema {written.resolve()}\n" + FOUR_BAR.replace('"100 mm"', '"mm"'))
    run = check("--no-auto-config", str(scene), cwd=tmp_path)
    assert run.returncode != 0 and '"mm" does not match' in run.stderr, run.stderr
