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
    "response": ["--speed", "300 rev/min", "-e", "4"],
}


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.stem)
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_command_answers_or_refuses_in_one_line(tmp_path, scene, command):
    args = [command, str(scene), *COMMANDS[command], "--out", str(tmp_path)]
    done = CliRunner().invoke(main, [*args, "--json"] if command != "report" else args)
    assert done.exception is None or isinstance(done.exception, SystemExit), (
        f"{' '.join(args)} raised {done.exception!r}")
    assert done.exit_code in (0, 2), done.output
    # which integrator the Floquet multipliers took is for -v, not a warning to the user
    assert "adiabatic steps refused" not in done.output
    if done.exit_code == 2:
        lines = [line for line in done.output.splitlines() if line.startswith("flexlink: error")]
        assert len(lines) == 1 and "Traceback" not in done.output, done.output
    elif command != "report":
        json.loads(done.output[done.output.index("{"):])



def test_an_unstable_speed_is_refused_with_where_to_look(tmp_path):
    """The aluminium four-bar diverges at 1000 rev/min (|mu| ~ 40): response refuses in one
    line that names the multiplier and the stability-map run that shows the unstable range."""
    scene = ROOT / "scenes" / "kineto_aluminium.toml"
    done = CliRunner().invoke(main, ["response", str(scene), "--speed", "1000 rev/min", "-e",
                                     "4", "--out", str(tmp_path)])
    assert done.exit_code == 2, done.output
    [line] = [line for line in done.output.splitlines() if line.startswith("flexlink: error")]
    assert "no steady state at 1000 rev/min" in line and "|mu| =" in line
    assert "stability-map --speeds '500:2000 rev/min'" in line
    assert not (tmp_path / "kineto_aluminium" / "response.json").exists()
