"""Variants compose: every command on a scene of each beam theory and model family gives an
answer (a JSON document) or a one-line refusal with a reason (exit 2), never a traceback; and
where a command cannot do for a variant what it does for the default one (the Craig-Bampton
map for Timoshenko links, the in-plane-only maps and exports for the other families), its JSON
says so.

Small meshes (2 elements per link), few poses and modes: the matrix is about composing, not
accuracy, and costs about half a minute in-process.
"""

import json

import pytest
from click.testing import CliRunner
from conftest import CASES_DIR, SCENES_DIR

from flexlink.cli import main

BEAMS = ("euler-bernoulli", "timoshenko")
FAMILIES = ("planar", "out-of-plane", "3d")
SMALL = ["-n", "2", "-e", "2"]
def _correlate(scene: str) -> list[str]:
    """``correlate`` on a small CSV test written beside the scene: one sensor at each link's
    middle (its pose from the scene), read in y and z, two made-up modes."""
    from flexlink.scene import load_scene

    loaded = load_scene(scene)
    joints = loaded.rigid_pose().joints
    rows = ["sensor,x [mm],y [mm],z [mm],dx,dy,dz,mode 1,mode 2", "frequency [Hz],,,,,,,50,120"]
    for k, link in enumerate(loaded.links):
        x, y = ((a + b) / 2 * 1e3 for a, b in zip(joints[link.start], joints[link.end]))
        rows += [f"s{k},{x},{y},0,0,1,0,{k + 1},{(-1) ** k}",
                 f"s{k},{x},{y},0,0,0,1,{0.1 * k},1"]
    path = scene + ".csv"
    with open(path, "w") as f:
        f.write("\n".join(rows) + "\n")
    return ["correlate", scene, path, "-n", "2", "-e", "2", "--no-pictures"]


COMMANDS = {
    "modes": lambda s: ["modes", s, *SMALL],
    "correlate": _correlate,
    "sensors": lambda s: ["sensors", s, "-e", "2", "--modes", "2", "--count", "3",
                          "--no-pictures"],
    "export": lambda s: ["export", s, *SMALL, "--no-pictures", "--phases", "2"],
    "cycle": lambda s: ["cycle", s, *SMALL, "--poses", "6"],
    "cycle-sorted": lambda s: ["cycle", s, "--sorted", *SMALL, "--poses", "6"],
    "campbell": lambda s: ["campbell", s, *SMALL, "--poses", "6", "--speeds", "0:3000 rev/min"],
    "mac": lambda s: ["mac", s, s, *SMALL],
    "converge": lambda s: ["converge", s, "-n", "2", "--max-elements", "4", "--repeats", "1"],
    "report": lambda s: ["report", s, *SMALL, "--cycle-poses", "4"],
    "prb": lambda s: ["prb", s, *SMALL],
    # one scene: the study cross-validates leaving one out, so it refuses (a full fit of two
    # scenes costs tens of seconds: tests/commands/test_calibrate_cli.py runs those)
    "calibrate": lambda s: ["calibrate", s, "--starts", "1", "--samples", "2", "-e", "2"],
    "verify": lambda s: ["verify", s],
}
# (command, family) pairs refused by design, with a word of the reason
REFUSED = {("mac", "3d"): "cannot compare", ("calibrate", "planar"): "at least two scenes",
           ("calibrate", "out-of-plane"): "at least two scenes",
           ("calibrate", "3d"): "at least two scenes"}
# the stability checks vary the in-plane model only: one family is enough (5 s each)
CELLS = [(beam, family, name) for beam in BEAMS for family in FAMILIES for name in COMMANDS
         if name != "verify" or family == "planar"]


def variant(tmp_path, beam: str, family: str, base) -> str:
    path = tmp_path / f"{base.stem}-{beam}-{family}.toml"
    path.write_text(f'base = "{base.as_posix()}"\nname = "{base.stem} {beam} {family}"\n'
                    f'[model]\nbeam = "{beam}"\nfamily = "{family}"\n')
    return str(path)


@pytest.mark.parametrize("beam, family, name", CELLS)
def test_command_answers_or_refuses_in_one_line(tmp_path, beam, family, name):
    base = SCENES_DIR / "compliant_wiper.toml" if name == "prb" else CASES_DIR / "case1.toml"
    scene = variant(tmp_path, beam, family, base)
    result = CliRunner().invoke(main, COMMANDS[name](scene) + ["--json", "--out",
                                                               str(tmp_path / "out")])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    assert "Traceback" not in result.output
    if (name, family) in REFUSED:
        assert result.exit_code == 2, result.output
        lines = [line for line in result.output.splitlines() if "error" in line.lower()]
        assert len(lines) == 1 and REFUSED[name, family] in lines[0], result.output
        return
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    notes = json.dumps(document)
    in_plane_only = (name in ("cycle", "cycle-sorted", "campbell", "export", "report")
                     and family != "planar")
    assert ("holds the in-plane modes only" in notes) == in_plane_only
    # the report's cycle map is a sorted (Craig-Bampton) one
    falls_back = name in ("cycle-sorted", "report") and beam == "timoshenko"
    assert ("the full model was solved" in notes) == falls_back
