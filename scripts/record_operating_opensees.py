"""Record OpenSeesPy's frequencies of two four-bars under their inertia preload at a crank speed,
for tests/studies/test_operating_opensees.py.

Run when the preload or the frame model is meant to change (the test then fails until this is
re-run):
    PYTHONPATH=. python scripts/record_operating_opensees.py
Needs openseespy (and Debian libblas3, liblapack3; see benchmarks/run.sh). The frame (nodes,
sections, springs) and the d'Alembert nodal loads are flexlink's own; OpenSees takes them as
they are, with its PDelta transformation on every element, runs one linear static step (the
tangent at zero load, so u = K^-1 f) and then ``eigen`` on the tangent stiffness after the step:
K + K_g, with PDelta's K_g = N / L on each element's chord. flexlink's ``modes --speed`` with
the preload alone (no centrifugal, Coriolis or angular-acceleration terms) and the string K_g
solves the same problem, so at the same mesh the two should agree to round-off; with the
consistent cubic K_g it converges to the same limit.
"""

from __future__ import annotations

import datetime
import json
import math
import os
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))

import opensees_frame  # noqa: E402
import openseespy.opensees as ops  # noqa: E402

from flexlink.fe.geometric import GeometricForm  # noqa: E402
from flexlink.scene import load_scene  # noqa: E402
from flexlink.studies.running.modes_at_speed import Terms, operating_modes  # noqa: E402

MESHES = (4, 8, 16, 32)  # elements per link
N_MODES = 4
SOLVER = "-fullGenLapack"
CASES = {  # scene: crank speed [rev/min] (the aluminium rig diverges before 2000 rev/min)
    "cases/case1.toml": 2000.0,
    "scenes/kineto_aluminium.toml": 600.0,
}
PRELOAD_ONLY = Terms(centrifugal=False, coriolis=False, acceleration=False,
                     geometric=GeometricForm.STRING)
OUT = ROOT / "tests" / "data" / "operating_opensees.json"


def main() -> None:
    ops.logFile(os.devnull, "-noEcho")
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    cases = {}
    for path, rpm in CASES.items():
        scene = load_scene(ROOT / path)
        speed = rpm * 2 * math.pi / 60
        meshes = {}
        for elements in MESHES:
            op = operating_modes(scene, speed, N_MODES, elements, terms=PRELOAD_ONLY)
            opensees_frame.build(ops, op.model, "PDelta")
            opensees_frame.preload(ops, op.loads)
            f = opensees_frame.frequencies(ops, N_MODES, SOLVER)
            meshes[str(elements)] = {
                "frequencies_Hz": [float(v) for v in f],
                "flexlink_max_relative_difference_when_recorded":
                    float(max(abs(op.frequencies / f - 1))),
                "largest_axial_force_N": op.largest_axial.value,
                "largest_axial_force_link": op.largest_axial.link}
        cases[path] = {"speed_rev_per_min": rpm, "meshes": meshes}
    record = {
        "what": "lowest natural frequencies [Hz] under the inertia preload at a crank speed "
                "(preload only: no centrifugal, Coriolis or angular-acceleration terms), "
                "solved by OpenSeesPy after one linear static step under flexlink's d'Alembert "
                "nodal loads",
        "openseespy": version("openseespy"),
        "element": "elasticBeamColumn, PDelta geomTransf, -cMass; zeroLength springs, fix / "
                   "equalDOF for rigid ones (benchmarks/opensees_frame.py)",
        "static_step": "algorithm Linear, LoadControl 1.0, one step",
        "eigen_solver": SOLVER,
        "date": datetime.date.today().isoformat(),
        "flexlink_commit": commit,
        "command": "PYTHONPATH=. python scripts/record_operating_opensees.py",
        "cases": cases,
    }
    OUT.write_text(json.dumps(record, indent=2) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
