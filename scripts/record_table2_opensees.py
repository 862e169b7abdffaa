"""Record the four Table II cases' frequencies as computed by OpenSeesPy, for tests/analysis/test_table2_pin.py.

Run when the default model is meant to change (the pin test then fails until this is re-run):
    PYTHONPATH=. python scripts/record_table2_opensees.py
Needs openseespy (and Debian libblas3, liblapack3; see benchmarks/run.sh). The frame (nodes,
sections, springs) is flexlink's own model of each case at its pose; OpenSees solves it with
its own elasticBeamColumn element (consistent mass) and its own eigen solver, so the recorded
frequencies check flexlink's element matrices, assembly, constraints and solver, and pin the
model's inputs (materials, sections, joints) as they were on the recording date.
"""

from __future__ import annotations

import datetime
import json
import os
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))

import opensees_frame  # noqa: E402
import openseespy.opensees as ops  # noqa: E402

from flexlink.analysis.modal import analyze  # noqa: E402
from flexlink.scene import load_scene  # noqa: E402

ELEMENTS = 8  # per link: the mesh both programs use
N_MODES = 6
SOLVER = "-fullGenLapack"
OUT = ROOT / "tests" / "data" / "table2_opensees.json"


def main() -> None:
    ops.logFile(os.devnull, "-noEcho")
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    cases = {}
    for i in (1, 2, 3, 4):
        path = f"cases/case{i}.toml"
        result = analyze(load_scene(ROOT / path), N_MODES, ELEMENTS)
        model = result.model
        opensees_frame.build(ops, model)
        f = opensees_frame.frequencies(ops, N_MODES, SOLVER)
        ours = result.modes.frequencies[:N_MODES]
        section = model.links[0].section
        cases[path] = {
            "frequencies_Hz": [float(v) for v in f],
            "flexlink_max_relative_difference_when_recorded": float(max(abs(ours / f - 1))),
            "model": {"nodes": len(model.nodes), "E_Pa": section.E, "area_m2": section.area,
                      "I_m4": section.second_moment, "density_kg_m3": section.density,
                      "joints_m": {k: [float(c) for c in v] for k, v in
                                   load_scene(ROOT / path).rigid_pose().joints.items()}},
        }
    record = {
        "what": "lowest natural frequencies [Hz] of the Table II cases at mu = 90 deg, default "
                "scene inputs, solved by OpenSeesPy",
        "openseespy": version("openseespy"),
        "elements_per_link": ELEMENTS,
        "element": "elasticBeamColumn, Linear geomTransf, -cMass (consistent mass); "
                   "zeroLength springs, fix / equalDOF for rigid ones (benchmarks/opensees_frame.py)",
        "eigen_solver": SOLVER,
        "date": datetime.date.today().isoformat(),
        "flexlink_commit": commit,
        "command": "PYTHONPATH=. python scripts/record_table2_opensees.py",
        "cases": cases,
    }
    OUT.write_text(json.dumps(record, indent=2) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
