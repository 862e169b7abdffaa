"""`flexlink kinematics`: its CSV, JSON document and text state the same motion.

At a constant crank speed omega a body turns at K omega and accelerates at L omega^2
(K = dtheta/dq, L = dK/dq), so the CSV's omega and alpha columns follow from its K and L
columns; the JSON's extremes are the CSV columns' and each [[family]] member's row of the
text holds that member's JSON numbers."""

import csv
import io
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import SCENES_DIR

from flexlink.cli import main
from flexlink.scene import load_scene

OMEGA = 2000 * 2 * math.pi / 60  # the scene's crank speed, 2000 rev/min [rad/s]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("kinematics")
    args = ["kinematics", str(SCENES_DIR / "extended_rocker.toml"), "--poses", "12",
            "--out", str(out)]
    as_json = CliRunner().invoke(main, [*args, "--json"])
    assert as_json.exit_code == 0, as_json.output
    text = CliRunner().invoke(main, args)
    assert text.exit_code == 0, text.output
    table = (out / "extended_rocker" / "kinematics.csv").read_text()
    return json.loads(as_json.output), text.output, table


def test_csv_columns_follow_the_document_and_the_chain_rule(run):
    document, _, table = run
    rows = list(csv.reader(io.StringIO(table)))
    bodies = list(document["bodies"])
    assert document["scene"] == load_scene(SCENES_DIR / "extended_rocker.toml").name
    # a body named "crank" has its angle under crank_body_angle_deg: the first column is the
    # input's crank_angle_deg, and two columns of one name cannot both be read by name
    angle = {b: "body_angle_deg" if b == "crank" else "angle_deg" for b in bodies}
    assert rows[0] == ["crank_angle_deg"] + [f"{b}_{q}" for b in bodies for q in
                                             (angle[b], "K", "L", "omega_rad_s",
                                              "alpha_rad_s2")]
    values = np.array(rows[1:], dtype=float)
    assert values[:, 0] == pytest.approx(np.arange(12) * 30.0 + values[0, 0], abs=1e-6)
    for k, name in enumerate(bodies):
        angle, K, L, omega, alpha = values[:, 1 + 5 * k: 6 + 5 * k].T
        assert omega == pytest.approx(K * OMEGA, rel=1e-9)  # 10 digits in the CSV
        assert alpha == pytest.approx(L * OMEGA**2, rel=1e-9, abs=1e-9)
        body = document["bodies"][name]
        # the document's extremes are over the same 12 poses
        assert (body["K"]["min"], body["K"]["max"]) == pytest.approx((K.min(), K.max()),
                                                                     rel=1e-9)


def test_each_family_row_of_the_text_holds_the_members_numbers(run):
    document, text, _ = run
    expected = []
    for member in document["family"]:
        for name, body in member["bodies"].items():
            if body.get("limit_positions"):
                omega, peak = body["omega_rad_s"], body["peak_abs_alpha"]
                expected.append((name, [member["value"]]
                                 + [p["angle_deg"] for p in body["limit_positions"]]
                                 + [body["swing_deg"], body["time_ratio"], omega["min"],
                                    omega["max"], peak["value_rad_s2"], peak["at_deg"]]))
    heads = [line.split() for line in text.splitlines() if line.strip().startswith("value")]
    assert heads and all(h[:6] == ["value", "body", "limits", "[deg]", "swing", "ratio"]
                         for h in heads)
    rows = []
    for line in text.split("value", 1)[1].splitlines():
        cells = line.split()
        if len(cells) > 2 and cells[1] in document["bodies"]:
            numbers = cells[2].split("/") + cells[3:5] + cells[5].split("..") + cells[6:7] \
                + cells[8:9]
            rows.append((cells[1], [float(cells[0])] + [float(x) for x in numbers]))
    assert [name for name, _ in rows] == [name for name, _ in expected]
    for (_, got), (_, want) in zip(rows, expected):
        # printed to 2 or 3 decimals (limits 2, swing 3, ratio 4, omega 2, alpha and angle 1)
        assert got == pytest.approx(want, abs=0.051)
