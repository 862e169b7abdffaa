"""Every shipped scene through the commands that take any scene: an answer (exit 0) or a
one-line refusal (exit 2) naming the reason, never a traceback. Small meshes and few poses."""

import json

import pytest
from click.testing import CliRunner

from conftest import ROOT
from flexlink.cli import main

SCENES = sorted([*ROOT.glob("cases/case*.toml"), *ROOT.glob("scenes/*.toml")])
COMMANDS = {
    "modes": ["-e", "4"],
    "export": ["-e", "4", "--no-pictures", "--phases", "2"],
    "report": ["-e", "4", "--cycle-poses", "4"],
    "outputs": ["--poses", "12"],
}


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.stem)
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_command_answers_or_refuses_in_one_line(tmp_path, scene, command):
    args = [command, str(scene), *COMMANDS[command], "--out", str(tmp_path)]
    done = CliRunner().invoke(main, [*args, "--json"] if command != "report" else args)
    assert done.exception is None or isinstance(done.exception, SystemExit), (
        f"{' '.join(args)} raised {done.exception!r}")
    assert done.exit_code in (0, 2), done.output
    if done.exit_code == 2:
        lines = [line for line in done.output.splitlines() if line.startswith("flexlink: error")]
        assert len(lines) == 1 and "Traceback" not in done.output, done.output
    elif command != "report":
        json.loads(done.output[done.output.index("{"):])

