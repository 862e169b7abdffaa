"""What the HTML report shows for one scene, as plain JSON-ready data: the pose and its drawing,
the comparison table, assumptions, mesh, mode shapes ready to animate, the cycle map and the
ParaView files. ``html_report.py`` turns a list of these into the page; keeping the numbers
here, apart from the markup, lets a new section (mode labels, intervals, a Campbell plot) add
one key here and one section there.

Lengths in the page data are in mm (what a person reads on a drawing of a linkage this size);
mode shapes are normalised so that each mode's largest sampled displacement is 1, and the page
scales them by its amplitude slider times the mechanism size.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from flexlink.analysis.modal import CaseResult
from flexlink.output.counts import counted
from flexlink.output.export_vtk import ModeSet, mode_set
from flexlink.output.kinetostatics.outputs import outputs_report_data
from flexlink.output.cycle.rigid_motion import motion_text
from flexlink.output.pose.scene_summary import linkage_summary, summary_document
from flexlink.studies.cycle.modal_map import ModalMap, transmission_angles
from flexlink.studies.cycle.rigid_motion import MotionStudy
from flexlink.studies.running.modes_at_speed import ASSUMPTIONS
from flexlink.studies.report_scene import AtSpeed, ReportScene
from flexlink.units import rev_per_min

MM = 1e3  # m -> mm
DIGITS = 5  # significant digits kept in the page's coordinates: far below a pixel


def _rounded(values: np.ndarray) -> list[float]:
    """Values rounded to DIGITS significant digits of the array's largest magnitude, so the
    page stays small (the full-precision shapes are in the .vtu)."""
    values = np.asarray(values, dtype=float)
    top = float(np.abs(values).max()) if values.size else 0.0
    if top == 0.0:
        return values.tolist()
    decimals = max(0, DIGITS - 1 - math.floor(math.log10(top)))
    return np.round(values, decimals).tolist()


def linkage_drawing(result: CaseResult) -> dict:
    """The posed linkage: each link as its end points [mm], every joint [mm] and which joints
    are grounded."""
    model = result.model
    links = [{"name": link.name,
              "points": _rounded(model.nodes[[link.nodes[0], link.nodes[-1]]] * MM)}
             for link in model.links]
    joints = {name: _rounded(np.asarray(xy) * MM) for name, xy in result.pose.joints.items()}
    ground = sorted(j.name for j in result.scene.joints if j.ground)
    return {"links": links, "joints": joints, "ground": ground}


def mode_shapes(modes: ModeSet) -> dict:
    """Undeformed polylines (one per link, null between links, as a plotting library draws a
    broken line) [mm] and, per mode, the displacement along them normalised to a largest
    magnitude of 1; ``size_mm`` is the mechanism size the page's amplitude fraction refers to."""
    sampled = modes.sampled
    order, start = [], 0
    for link_index in range(len(sampled.link_names)):
        count = int((sampled.cell_link == link_index).sum()) * sampled.subdivisions + 1
        order.extend(range(start, start + count))
        order.append(-1)  # a break between links
        start += count
    index = np.array(order[:-1])
    gap = index < 0
    xy = sampled.points[np.where(gap, 0, index)] * MM
    x = [None if g else v for g, v in zip(gap, _rounded(xy[:, 0]))]
    y = [None if g else v for g, v in zip(gap, _rounded(xy[:, 1]))]
    shapes = []
    for i, (number, frequency) in enumerate(zip(modes.numbers, modes.frequencies)):
        d = sampled.displacement[np.where(gap, 0, index), :, i]
        peak = float(np.linalg.norm(d, axis=1).max())
        d = d / peak if peak > 0 else d
        shapes.append({"number": int(number), "frequency_Hz": float(frequency),
                       "dx": [None if g else v for g, v in zip(gap, _rounded(d[:, 0]))],
                       "dy": [None if g else v for g, v in zip(gap, _rounded(d[:, 1]))]})
    return {"x": x, "y": y, "size_mm": modes.size * MM, "modes": shapes}


def cycle_data(cycle: ModalMap | None, crank_angle: float, reason: str | None = None
               ) -> dict | None:
    """The modal map over the crank cycle (frequencies [Hz] against crank angle [deg]), the
    analysed pose's crank angle and where a transmission angle is 90 deg; None when no map
    was asked for, {"unavailable": reason} when one could not be made; "note": why the map
    was solved on the full model, when it was not reduced as asked."""
    if cycle is None:
        return None if reason is None else {"unavailable": reason}
    order = np.argsort(np.degrees(cycle.q) % 360.0)
    crank = np.degrees(cycle.q)[order] % 360.0
    data = {"crank_deg": _rounded(crank),
            "frequencies_Hz": [_rounded(cycle.frequencies[order, j])
                               for j in range(cycle.frequencies.shape[1])],
            "pose_deg": math.degrees(crank_angle) % 360.0,
            "mu90_deg": {pair: [math.degrees(a) % 360.0 for a in angles]
                         for pair, angles in cycle.mu90.items()}}
    if cycle.note:
        data["note"] = cycle.note
    return data


def at_speed_data(at: AtSpeed | None) -> dict | None:
    """The scene at its declared operating point (``report_scene.AtSpeed``): the driving torque
    over the cycle [N m], the operating-point frequencies at the scene's pose from rest to that
    speed, with the declared crank acceleration at every speed [Hz] (None where a mode
    diverges) and each link's largest tension and compression of the preload there [N]; None
    when the scene declares no speed. A part the scene cannot give is {"unavailable": reason}."""
    if at is None:
        return None
    out = {"rev_per_min": rev_per_min(at.speed), "rad_per_s": at.speed,
           "crank_acceleration_rad_s2": at.crank_acceleration, "assumptions": ASSUMPTIONS}
    if at.torque is None:
        out["torque"] = {"unavailable": at.torque_unavailable}
    else:
        curve = at.torque
        order = np.argsort(np.degrees(curve.q) % 360.0)
        out["torque"] = {"crank_deg": _rounded(np.degrees(curve.q[order]) % 360.0),
                         # a singular pose's torque is not determined: a gap in the curve
                         "torque_N_m": [None if math.isnan(t) else float(t)
                                        for t in curve.torque[order]],
                         "summary": curve.summary()}
    out["response"] = steady_response_data(at)
    if at.points_unavailable is not None:
        out["modes"] = {"unavailable": at.points_unavailable}
        return out
    points = at.points
    lines = []
    for j in range(len(points[0].frequencies)):
        line = []
        for p in points:
            s = p.modes.eigenvalues[j]
            line.append(float(p.frequencies[j]) if s.imag > 1e-9 * abs(s) else None)
        lines.append(line)
    last = points[-1]
    out["modes"] = {"rev_per_min": [float(rev_per_min(w)) for w in at.speeds],
                    "frequencies_Hz": lines,
                    "static_Hz": [float(f) for f in last.static_frequencies],
                    "diverges": bool(last.modes.negative_stiffness),
                    "axial_N": [{"link": name, "tension": float(max(f.max(), 0.0)),
                                 "compression": float(min(f.min(), 0.0))}
                                for name, f in last.axial_forces.items()]}
    return out


def steady_response_data(at: AtSpeed) -> dict:
    """Each strain point's bending strain over one turn at the operating speed in the steady
    state (``AtSpeed.response``), or {"unavailable": reason}."""
    if at.response is None:
        return {"unavailable": at.response_unavailable}
    from flexlink.studies.running.steady_response import SMALL_DEFLECTION, depth_ratio

    result = at.response
    order = np.argsort(np.degrees(result.angles) % 360.0)
    ratio = depth_ratio(at.forced, result.peak_deflection)
    return {"crank_deg": _rounded(np.degrees(result.angles[order]) % 360.0),
            "small_deflection_limit": SMALL_DEFLECTION,
            "points": [{"label": p.label, "strain": [float(x) for x in result.strain[order, k]],
                        "peak_strain": float(result.peak_strain[k]),
                        "peak_deflection_m": float(result.peak_deflection[k]),
                        "deflection_to_depth": float(ratio[k]),
                        "small_deflection": bool(ratio[k] <= SMALL_DEFLECTION)}
                       for k, p in enumerate(at.forced.points)]}


def life_data(scene: ReportScene) -> dict | None:
    """Stress and life at the operating speed (``ReportScene.life``): the ``life`` command's
    document and, per link, the stress over the turn at its peak's point; {"unavailable":
    reason} where it could not be made; None for a scene without a speed or strengths."""
    if scene.life is None:
        return None if scene.life_unavailable is None else {"unavailable": scene.life_unavailable}
    from flexlink.output.life.life import life_document

    study = scene.life
    field = study.field
    order = np.argsort(np.degrees(field.angles) % 360.0)
    curves = []
    for link in study.links:
        index = field.points.of(link.link)
        at = field.points.position[index]
        fibre = np.where(field.points.fibre[index] == 0, 1, -1)
        k = index[np.flatnonzero((np.abs(at - link.peak.position) < 1e-12)
                                 & (fibre == link.peak.fibre))[0]]
        curves.append({"link": link.link,
                       "stress_MPa": [float(x) / 1e6 for x in field.total[order, k]]})
    document = life_document(scene.summary.case.scene, study)
    return {**document, "crank_deg": _rounded(np.degrees(field.angles[order]) % 360.0),
            "curves": curves}


def scene_page(scene: ReportScene, files: dict, out: Path, correlation: dict | None = None
               ) -> dict:
    """Everything the report shows for one scene (``studies.report_scene``), its modes drawn
    on the mesh they were solved on; ``files``: ``export.export_case``'s answer, linked
    relative to ``out``; ``correlation``: a modal test's correlation with the scene
    (``output.correlation.correlation.correlation_json``), or None."""
    def relative(paths):
        return [Path(p).relative_to(out).as_posix() for p in paths]

    if scene.summary is None:
        return kinematics_page(scene.motion)
    summary = scene.summary
    result, mesh = summary.case, summary.mesh
    return {"id": Path(result.scene.path).stem, "summary": summary_document(summary),
            "mesh": {**mesh.as_dict(), "describe": mesh.describe(), "history": list(mesh.history)},
            "drawing": linkage_drawing(result),
            "shapes": mode_shapes(mode_set(result, len(summary.frequencies))),
            "cycle": cycle_data(scene.cycle, result.pose.crank_angle, scene.cycle_unavailable),
            "at_speed": at_speed_data(scene.at_speed),
            "life": life_data(scene),
            "kinetostatics": outputs_report_data(scene.kinetostatics,
                                                 scene.kinetostatics_unavailable),
            "correlation": correlation,
            "files": {"vtu": relative(files.get("vtu", [])),
                      "pvd": relative(files.get("pvd", []))}}


def kinematics_page(study: MotionStudy) -> dict:
    """The page of a scene without beams (kinematics only): its pose and drawing (each body
    as lines from its first joint to the others), its rigid motion as ``flexlink
    kinematics`` prints it, and its transmission angles over the cycle [deg]."""
    scene = study.scene
    pose = scene.rigid_pose()
    links = [{"name": b.name, "points": _rounded(np.array(
        [pose.joints[j] for j in (b.joints[0], b.joints[k])]) * MM)}
        for b in scene.linkage.bodies for k in range(1, len(b.joints))]
    mu = transmission_angles(scene, study.cycle)
    return {"id": Path(scene.path).stem,
            "summary": {"scene": scene.name, "file": scene.path,
                        "linkage": linkage_summary(scene),
                        "pose": {"theta2_deg": math.degrees(pose.crank_angle),
                                 "mu_deg": None if pose.mu is None else math.degrees(pose.mu),
                                 "branch": pose.branch}},
            "kinematics": {"note": "the scene has no [links] beams: kinematics only, no modes",
                           "text": motion_text(study),
                           "crank_deg": _rounded(np.degrees(study.cycle.q)),
                           "transmission_deg": {pair: _rounded(np.degrees(v))
                                                for pair, v in mu.items()}},
            "drawing": {"links": links,
                        "joints": {n: _rounded(np.asarray(xy) * MM)
                                   for n, xy in pose.joints.items()},
                        "ground": sorted(scene.linkage.ground)},
            "mesh": None, "shapes": {"modes": []}, "cycle": None, "at_speed": None,
            "files": {"vtu": [], "pvd": []}}


def report_document(report: Path, page: str, pages: list[dict], out: Path,
                    failures: list[dict]) -> dict:
    """The JSON document of ``flexlink report``: the page written to ``report`` and its size,
    per scene (``scene_page`` each, its files in ``out``) its mesh, frequencies [Hz] and
    whether it has a cycle map, every file written, and the scenes that failed."""
    def scene(p: dict) -> dict:
        summary, cycle = p["summary"], p["cycle"]
        if "kinematics" in p:
            return {"scene": summary["scene"], "file": summary["file"], "mesh": None,
                    "frequencies_Hz": [], "cycle_map": False,
                    "note": p["kinematics"]["note"]}
        entry = {"scene": summary["scene"], "file": summary["file"],
                 "mesh": p["mesh"]["elements_per_link"],
                 "frequencies_Hz": [r["computed_Hz"] for r in summary["modes"]],
                 "cycle_map": cycle is not None and "unavailable" not in cycle}
        if "note" in summary:
            entry["note"] = summary["note"]
        if cycle and "note" in cycle:
            entry["cycle_map_note"] = cycle["note"]
        return entry

    return {"command": "report", "report": str(report), "bytes": len(page.encode()),
            "scenes": [scene(p) for p in pages],
            "files": [str(report)] + [str(out / f) for p in pages
                                      for f in p["files"]["vtu"] + p["files"]["pvd"]],
            "failures": failures}


def report_html(pages: list[dict], failures: list[dict], n_modes: int) -> str:
    """The self-contained page of ``pages`` (``scene_page`` each) with plotly.js inlined, the
    scenes that failed listed at the top, and under the title flexlink's version, when, and
    what the page holds."""
    import datetime
    import importlib.metadata

    import plotly.offline

    from flexlink.output.html_report import render_page

    stamp = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    version = importlib.metadata.version("flexlink")
    subtitle = (f"flexlink {version}, {stamp}: {counted(len(pages), 'scene')}, first "
                f"{counted(n_modes, 'elastic mode')}")
    return render_page(pages, plotly.offline.get_plotlyjs(), subtitle=subtitle,
                       failures=[f["error"] for f in failures])


def report_text(document: dict) -> str:
    """The line ``flexlink report`` prints: how many scenes, how large, where."""
    return (f"report: {counted(len(document['scenes']), 'scene')}, "
            f"{document['bytes'] / 1e6:.1f} MB -> {document['report']}")
