"""A caller's mesh tolerance (--tol) reaches the mesh rule of every command that takes it, and
is not replaced by the default (1e-6): the mesh is the coarsest of 8, 16, 32, ... elements per
link whose Richardson estimate meets the tolerance asked for, worked out here from the
frequencies at each mesh, and the document says so.

On case 1 the estimate is 7.7e-5 at 8 elements/link, 4.8e-6 at 16 and 3.2e-7 at 32: 1e-5 asks
for 16, the default 1e-6 for 32, so a tolerance lost on the way shows as another mesh.
"""

import json

import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.analysis.mesh import DEFAULT_TOL, ORDER
from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.scene import load_scene

from conftest import CASES_DIR

CASE1 = CASES_DIR / "case1.toml"
TOL, N_MODES = 1e-5, 2
COMMANDS = {
    "modes": ["modes"],
    "export": ["export", "--no-pictures", "--phases", "2"],
    "report": ["report", "--cycle-poses", "0"],
    "cycle": ["cycle", "--poses", "6"],
    "campbell": ["campbell", "--poses", "6", "--speeds", "0:3000 rev/min"],
    "modes at speed": ["modes", "--speed", "1000 rev/min"],
}


def coarsest(tol: float) -> int:
    """The coarsest of 8, 16, ... elements/link whose Richardson estimate max |f_e - f_(e/2)|
    / (2^ORDER - 1) / f_e over the lowest N_MODES modes meets ``tol``."""
    scene = load_scene(CASE1)
    previous = analyze(scene, N_MODES, 4).elastic_frequencies(N_MODES)
    for elements in (8, 16, 32, 64):
        current = analyze(scene, N_MODES, elements).elastic_frequencies(N_MODES)
        if np.max(np.abs(current - previous) / (2**ORDER - 1) / current) <= tol:
            return elements
        previous = current
    raise AssertionError(f"no mesh up to 64 elements/link meets {tol:g}")


@pytest.fixture(scope="module")
def expected() -> int:
    asked, default = coarsest(TOL), coarsest(DEFAULT_TOL)
    assert asked < default  # the check below can tell the two apart
    return asked


def mesh_of(document: dict):
    """The mesh record of a command's document: (elements per link, its rule's record or None
    where the document gives the count alone)."""
    case = (document.get("cases") or document.get("scenes") or [document])[0]
    mesh = case.get("mesh", document.get("mesh"))
    if isinstance(mesh, dict):
        return mesh["elements_per_link"], mesh
    return (mesh if mesh is not None else case["elements_per_link"]), None


@pytest.mark.parametrize("command", list(COMMANDS))
def test_the_tolerance_asked_for_sets_the_mesh(command, expected, tmp_path):
    name, *options = COMMANDS[command]
    result = CliRunner().invoke(main, [name, str(CASE1), *options, "-n", str(N_MODES), "--tol",
                                       str(TOL), "--json", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    elements, rule = mesh_of(json.loads(result.stdout))
    assert elements == expected
    if rule is not None:  # the record says which rule and which tolerance chose it
        assert rule["rule"] == "tolerance" and rule["tolerance"] == TOL  # the option's value
        assert rule["estimated_relative_error"] <= TOL
