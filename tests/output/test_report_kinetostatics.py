"""The HTML report's output-torque section: shown for a scene that declares an input torque,
absent for one that does not; its curves leave the samples next to a dead point out (null)
and it names the dead points; its data is strict JSON."""

import json

from conftest import SCENES_DIR
from flexlink.output.html_report import kinetostatics_section
from flexlink.output.kinetostatics.outputs import outputs_report_data
from flexlink.scene import load_scene
from flexlink.studies.kinetostatics.outputs import output_study


def test_section_for_a_scene_with_an_input_torque():
    curve = output_study(load_scene(SCENES_DIR / "wiper.toml"), 0.0, poses=72)
    data = json.loads(json.dumps(outputs_report_data(curve), allow_nan=False))
    near = [i for i, d in enumerate(data["crank_deg"]) if abs(d - 5.0) < 1e-9]
    assert near and data["torques_N_m"]["rocker2"][near[0]] is None  # 0.14 deg from one
    ninety = data["crank_deg"].index(90.0)
    assert data["torques_N_m"]["rocker2"][ninety] == curve.torques[18, 1]
    figures = []
    html = kinetostatics_section({"id": "wiper", "kinetostatics": data}, figures)
    assert "Output torques" in html and "182.30 deg (rocker1, rocker2)" in html
    assert [f["id"] for f in figures] == ["fig-wiper-kineto-outputs", "fig-wiper-kineto-ratios"]


def test_no_section_without_an_input_torque_and_a_reason_when_it_failed():
    assert outputs_report_data(None) is None
    assert kinetostatics_section({"id": "x", "kinetostatics": None}, []) == ""
    html = kinetostatics_section({"id": "x", "kinetostatics": outputs_report_data(None, "why")},
                                 [])
    assert "Not available: why" in html
