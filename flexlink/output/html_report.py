"""The report as one self-contained HTML page: every script, style and number inline, so the
file can be mailed and opened offline; nothing is fetched when it is viewed.

Plotting library: plotly.js, inlined from the ``plotly`` Python package (``plotly.offline.
get_plotlyjs()``). Chosen because it is widely used and maintained, ships its whole browser
bundle inside a PyPI wheel (nothing to download at build or view time), draws zoomable,
hoverable 2D plots with equal-aspect axes, and lets a few lines of JavaScript restyle a trace
per animation frame; vtk.js through pyvista/trame would bring 3D machinery a planar linkage
does not need and a much larger page.

Each scene is a list of sections, each a function of that scene's ``report_data.scene_page``
that returns its HTML, or "" when the scene has no data for it (SECTIONS): a new section (mode
labels, intervals, a Campbell plot) is one function added there. Figures are plotly specs put
in the page's JSON data and drawn by ``html_assets.SCRIPT``.
"""

from __future__ import annotations

import html
import json
import math
import re

from flexlink.output.counts import counted
from flexlink.output.html_assets import SCRIPT, STYLE

LINK_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf")


def _e(text) -> str:
    return html.escape(str(text), quote=True)


def _number(value: float, digits: int = 2) -> str:
    return f"{value:,.{digits}f}" if value is not None and math.isfinite(value) else "-"


def _table(header: list[str], rows: list[list[str]], numeric_from: int = 0) -> str:
    """A table in a scrolling box (a phone shows wide tables by scrolling them, not the page);
    cells are already-escaped HTML; columns from ``numeric_from`` on are right-aligned."""
    head = "".join(f"<th>{h}</th>" for h in header)
    body = "".join("<tr>" + "".join(
        f'<td class="num">{c}</td>' if i >= numeric_from else f"<td>{c}</td>"
        for i, c in enumerate(row)) + "</tr>" for row in rows)
    return f'<div class="scroll"><table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table></div>'


def _figure(page: dict, figures: list, name: str, data: list, layout: dict, css: str = "plot") -> str:
    figure_id = f"fig-{page['id']}-{name}"
    figures.append({"id": figure_id, "data": data, "layout": {**BASE_LAYOUT, **layout}})
    return f'<div class="{css}" id="{figure_id}"></div>'


BASE_LAYOUT = {"margin": {"l": 55, "r": 15, "t": 30, "b": 45}, "height": 360,
               "font": {"family": "DejaVu Sans, Arial, sans-serif", "size": 12},
               "paper_bgcolor": "#ffffff", "plot_bgcolor": "#fbfbfb"}


def equal_axes(x_title: str = "x [mm]", y_title: str = "y [mm]") -> dict:
    return {"xaxis": {"title": {"text": x_title}, "zeroline": False},
            "yaxis": {"title": {"text": y_title}, "zeroline": False, "scaleanchor": "x",
                      "scaleratio": 1},
            "showlegend": False}


# --- sections: each (page, figures) -> HTML or "" -------------------------------------------

def pose_section(page: dict, figures: list) -> str:
    pose = page["summary"]["pose"]
    drawing = page["drawing"]
    facts = [f"crank angle &theta;<sub>2</sub> = {_number(pose['theta2_deg'], 3)} deg"]
    if pose.get("mu_deg") is not None:
        facts.append(f"transmission angle &mu; = {_number(pose['mu_deg'], 3)} deg")
    facts.append(f"{_e(pose['branch'])} branch")
    lengths = page["summary"].get("linkage", {})
    sizes = [f"{_e(k.removesuffix('_m'))} {_number(1e3 * v, 1)} mm"
             for k, v in lengths.items() if k.endswith("_m")]
    if "grashof" in lengths:
        sizes.append(f"Grashof class: {_e(lengths['grashof'])}")
    data = [{"type": "scatter", "mode": "lines", "x": [p[0] for p in link["points"]],
             "y": [p[1] for p in link["points"]], "name": link["name"],
             "line": {"width": 6, "color": LINK_COLOURS[i % len(LINK_COLOURS)]},
             "hovertemplate": f"{_e(link['name'])}<extra></extra>"}
            for i, link in enumerate(drawing["links"])]
    names = list(drawing["joints"])
    data.append({"type": "scatter", "mode": "markers+text", "name": "joints",
                 "x": [drawing["joints"][n][0] for n in names],
                 "y": [drawing["joints"][n][1] for n in names], "text": names,
                 "textposition": "top center", "hovertemplate": "%{text}: (%{x}, %{y}) mm<extra></extra>",
                 "marker": {"size": [14 if n in drawing["ground"] else 9 for n in names],
                            "symbol": ["triangle-up" if n in drawing["ground"] else "circle"
                                       for n in names],
                            "color": "#222222"}})
    figure = _figure(page, figures, "pose", data, {**equal_axes(), "height": 320})
    return (f"<h3>Pose</h3><p>{'; '.join(facts)}.</p>"
            + (f"<p>{'; '.join(sizes)}.</p>" if sizes else "") + figure
            + '<p class="note">Links drawn between their end joints; triangles are ground '
              "joints.</p>")


KNOWN_ROW_KEYS = {"mode", "computed_Hz"}
SHOWN_PARTS = 2  # parts named in an energy cell; all of them are in its tooltip


def _percent(fraction: float) -> str:
    """A share as a person reads it: whole percent, finer only below 1 % (and where rounding
    would claim all of it)."""
    pct = 100 * fraction
    if pct == 0:
        return "0 %"
    if pct < 1:
        return f"{pct:.2g} %"
    if round(pct) == 100 and pct < 100:  # not all of it: 99.9 %, never 100 %
        return f"{math.floor(10 * pct) / 10:.1f} %"
    return f"{pct:.0f} %"


def _shares(parts: dict) -> str:
    """An energy distribution ({part: fraction}) as its two largest parts, e.g. "crank 85 %,
    coupler 9 %", with every part in the tooltip."""
    ranked = sorted(parts.items(), key=lambda kv: -kv[1])
    shown = ", ".join(f'<span class="share">{_e(k)} {_percent(v)}</span>'
                      for k, v in ranked[:SHOWN_PARTS])
    everything = ", ".join(f"{k} {100 * v:.3g} %" for k, v in ranked)
    return f'<span class="shares" title="{_e(everything)}">{shown}</span>'


def _cell(value) -> str:
    """An extra column's value: distributions as shares, lists joined, text escaped."""
    if isinstance(value, dict):
        return _shares(value)
    if isinstance(value, (list, tuple)):
        return ", ".join(_e(v) for v in value)
    return _e(value)


def _mode_labels(summary: dict) -> dict[int, str]:
    return {row["mode"]: row["label"] for row in summary.get("modes", []) if row.get("label")}


def headline(summary: dict) -> str:
    """One line for the top of the page: the scene's mean |error| against each reference."""
    errors = summary.get("mean_abs_error_pct") or {}
    if not errors:
        return "no reference frequencies"
    return "mean |error| " + ", ".join(f"vs {_e(k)} {v:.1f} %" for k, v in sorted(errors.items()))


def frequency_section(page: dict, figures: list) -> str:
    summary = page["summary"]
    rows = summary["modes"]
    if not rows:
        return ""
    refs = [k[:-3] for k in rows[0] if k.endswith("_Hz") and k != "computed_Hz"]
    known = KNOWN_ROW_KEYS | {f"{r}_Hz" for r in refs} | {f"error_vs_{r}_pct" for r in refs}
    extra = [k for k in rows[0] if k not in known]  # e.g. "kind", or a later label/interval
    masses = "effective_mass_kg" in extra
    extra = [k for k in extra if k != "effective_mass_kg"]
    header = ["mode", "computed [Hz]"] + [h for r in refs for h in (f"{_e(r)} [Hz]", "error")] \
        + (["m<sub>x</sub> [g]", "m<sub>y</sub> [g]"] if masses else []) \
        + [_e(k.replace("_", " ")) for k in extra]
    body = []
    for row in rows:
        cells = [str(row["mode"]), _number(row["computed_Hz"])]
        for r in refs:
            if f"{r}_Hz" in row:
                cells += [_number(row[f"{r}_Hz"], 1), f"{row[f'error_vs_{r}_pct']:+.1f} %"]
            else:
                cells += ["-", "-"]
        if masses:
            mass = row.get("effective_mass_kg") or {}
            cells += [_number(1e3 * mass[a], 3) if a in mass else "-" for a in ("x", "y")]
        cells += [_cell(row.get(k, "")) for k in extra]
        body.append(cells)
    parts = [f"<h3>Natural frequencies</h3><p>{_e(summary.get('family', 'planar'))} model, "
             f"{summary['elements_per_link']} elements/link, {summary['dofs']} DOFs, "
             f"{_e(summary['solver'])} solver, largest residual "
             f"{summary['max_residual']:.1e}.</p>", _table(header, body, 1)]
    if summary.get("mean_abs_error_pct"):
        parts.append("<p>Mean |error|: " + ", ".join(
            f"vs {_e(k)} {v:.1f} %" for k, v in sorted(summary["mean_abs_error_pct"].items()))
            + ". Errors are (computed - reference) / reference, modes paired by order.</p>")
    if summary.get("reference_source"):
        parts.append(f'<p class="note">Reference: {_e(summary["reference_source"])}</p>')
    if summary.get("mechanism_modes_Hz"):
        parts.append("<p>Rigid-body/mechanism modes (not paired): " + ", ".join(
            f"{f:.3g} Hz" for f in summary["mechanism_modes_Hz"]) + ".</p>")
    if summary.get("warnings"):
        parts.append('<div class="warnings"><strong>Warnings</strong><ul>' + "".join(
            f"<li>{_e(w)}</li>" for w in summary["warnings"]) + "</ul></div>")
    return "".join(parts)


def assumptions_section(page: dict, figures: list) -> str:
    assumptions = page["summary"].get("assumptions") or []
    if not assumptions:
        return ""
    rows = [[f"<code>{_e(a['field'])}</code>", _e(a["value"]), _e(a["note"])] for a in assumptions]
    return "<h3>Assumptions</h3>" + _table(["field", "value", "note"], rows, 99)


def sensitivity_section(page: dict, figures: list) -> str:
    """Each assumed input at both ends of its range, and the Monte Carlo 95 % interval with the
    reference values inside it marked (``flexlink report --sensitivity``)."""
    data = page["summary"].get("sensitivity")
    if not data:
        return ""
    n = len(data["nominal_Hz"])
    modes = [f"f{i + 1} [Hz]" for i in range(n)]
    rows = [["nominal", "", *[_number(f) for f in data["nominal_Hz"]]]]
    for row in data["inputs"]:
        for end in ("low", "high"):
            rows.append([_e(row["field"]) if end == "low" else "", _e(row[end]),
                         *[_number(f) for f in row[f"{end}_Hz"]]])
    mc = data["monte_carlo"]
    interval = [["95 % interval", "", *[f"{lo:.1f} - {hi:.1f}"
                                        for lo, hi in zip(mc["low_Hz"], mc["high_Hz"])]]]
    for column, inside in mc["inside"].items():
        values = page["summary"]["modes"]
        interval.append([f"{_e(column)} inside?", "", *[
            ("yes" if flag else "no") + f" ({row.get(f'{column}_Hz', float('nan')):.0f})"
            for flag, row in zip(inside, values)]])
    reasons = "".join(f"<li><code>{_e(r['field'])}</code>: {_e(r['low'])} to {_e(r['high'])}: "
                      f"{_e(r['reason'])}</li>" for r in data["inputs"])
    return ("<h3>Sensitivity to the assumptions</h3>"
            f"<p>Each assumed input at both ends of its range, the others nominal "
            f"({data['elements_per_link']} elements/link).</p>"
            + _table(["input", "end", *modes], rows, 2)
            + f"<p>Monte Carlo over every range together with the Table I spreads "
            f"({mc['samples']} samples, seed {mc['seed']}, {mc['failed']} failed):</p>"
            + _table(["", "", *modes], interval, 2)
            + f'<details><summary>Ranges and their reasons</summary><ul>{reasons}</ul></details>')


def mesh_section(page: dict, figures: list) -> str:
    mesh = page["mesh"]
    parts = [f"<h3>Mesh</h3><p>{_e(mesh['describe'])}.</p>"]
    if mesh.get("history"):
        rows = [[str(n), f"{e:.2e}"] for n, e in mesh["history"]]
        parts.append(_table(["elements/link", "estimated relative error"], rows, 0))
    return "".join(parts)


def modes_section(page: dict, figures: list) -> str:
    shapes = page["shapes"]
    if not shapes["modes"]:
        return ""
    pid = _e(page["id"])
    labels = _mode_labels(page["summary"])
    options = "".join(f'<option value="{i}">mode {m["number"]}: {m["frequency_Hz"]:.1f} Hz'
                      + (f", {_e(labels[m['number']])}" if m["number"] in labels else "")
                      + "</option>" for i, m in enumerate(shapes["modes"]))
    return (f'<h3>Mode shapes</h3><div class="player" id="player-{pid}" data-scene="{pid}">'
            f'<div class="controls"><label>Mode <select aria-label="mode">{options}</select></label>'
            '<button type="button" class="play" aria-label="pause">Pause</button>'
            '<label class="amp">Amplitude <input type="range" min="0" max="25" step="0.5" '
            'value="10" aria-label="amplitude"> <span class="amp-value">10 %</span></label></div>'
            f'<div class="plot mode-plot" id="modeplot-{pid}"></div></div>'
            '<p class="note">Largest displacement drawn as the slider\'s fraction of the '
            "mechanism size; grey: the undeformed pose. Mass-normalised shapes as solved "
            "(sampled with each element's own shape functions).</p>")


def cycle_section(page: dict, figures: list) -> str:
    cycle = page.get("cycle")
    if cycle is None:
        return ""
    if "unavailable" in cycle:
        return f"<h3>Cycle map</h3><p>Not available: {_e(cycle['unavailable'])}</p>"
    # the map lists the j-th lowest frequency at each pose, so a label holds at the analysed
    # pose and is named as such
    labels = _mode_labels(page["summary"])
    data = [{"type": "scatter", "mode": "lines", "x": cycle["crank_deg"], "y": f,
             "name": f"mode {j + 1}" + (f" ({labels[j + 1]} at the pose)" if j + 1 in labels
                                         else ""),
             "hovertemplate": "%{x:.1f} deg: %{y:.1f} Hz<extra></extra>"}
            for j, f in enumerate(cycle["frequencies_Hz"])]
    shapes = [{"type": "line", "x0": cycle["pose_deg"], "x1": cycle["pose_deg"], "yref": "paper",
               "y0": 0, "y1": 1, "line": {"color": "#444", "dash": "dash", "width": 1}}]
    for angles in cycle["mu90_deg"].values():
        shapes += [{"type": "line", "x0": a, "x1": a, "yref": "paper", "y0": 0, "y1": 1,
                    "line": {"color": "#bbb", "dash": "dot", "width": 1}} for a in angles]
    layout = {"xaxis": {"title": {"text": "crank angle [deg]"}, "range": [0, 360], "dtick": 60},
              "yaxis": {"title": {"text": "natural frequency [Hz]"}},
              "legend": {"orientation": "h", "y": -0.25}, "shapes": shapes, "height": 380}
    return ("<h3>Cycle map</h3>" + _figure(page, figures, "cycle", data, layout)
            + f'<p class="note">The first '
              f"{counted(len(data), 'elastic frequency', 'elastic frequencies')} over one crank "
              f"revolution ({counted(len(cycle['crank_deg']), 'pose')}); dashed: the analysed "
              "pose, dotted: transmission angle 90 deg.</p>")


def at_speed_section(page: dict, figures: list) -> str:
    """The scene at its declared operating speed: torque curve, frequencies against speed at
    the pose, and the preload's axial forces per link; "" (no section) without a speed."""
    at = page.get("at_speed")
    if at is None:
        return ""
    acc = at.get("crank_acceleration_rad_s2") or 0.0
    parts = [f"<h3>At speed</h3><p>Crank speed {_number(at['rev_per_min'], 1)} rev/min "
             f"({_number(at['rad_per_s'], 3)} rad/s)"
             + (f", crank acceleration {_number(acc, 4)} rad/s^2 (at every speed below)"
                if acc else "") + ", as the scene declares. Assumptions: "
             + "; ".join(_e(a) for a in at["assumptions"]) + ".</p>"]
    torque = at["torque"]
    if "unavailable" in torque:
        parts.append(f"<p>Driving torque not available: {_e(torque['unavailable'])}</p>")
    else:
        s = torque["summary"]
        data = [{"type": "scatter", "mode": "lines", "x": torque["crank_deg"],
                 "y": torque["torque_N_m"], "name": "driving torque",
                 "hovertemplate": "%{x:.1f} deg: %{y:.4g} N m<extra></extra>"}]
        layout = {"xaxis": {"title": {"text": "crank angle [deg]"}, "range": [0, 360],
                            "dtick": 60},
                  "yaxis": {"title": {"text": "driving torque [N m]"}}, "showlegend": False}
        parts.append(_figure(page, figures, "torque", data, layout)
                     + f'<p class="note">Driving torque on the crank over one turn: peak '
                       f"{s['peak_torque_N_m']:.4g} N m at {s['peak_torque_at_deg']:.0f} deg, "
                       f"mean {s['mean_torque_N_m']:.4g} N m, mean power "
                       f"{s['mean_power_W']:.4g} W.</p>")
    parts.append(_steady_response_part(page, figures, at.get("response")))
    modes = at["modes"]
    if "unavailable" in modes:
        parts.append(f"<p>Modes at speed not available: {_e(modes['unavailable'])}</p>")
        return "".join(parts)
    data = [{"type": "scatter", "mode": "lines+markers", "x": modes["rev_per_min"], "y": f,
             "name": f"mode {j + 1}",
             "hovertemplate": "%{x:.0f} rev/min: %{y:.2f} Hz<extra></extra>"}
            for j, f in enumerate(modes["frequencies_Hz"])]
    layout = {"xaxis": {"title": {"text": "crank speed [rev/min]"}},
              "yaxis": {"title": {"text": "frequency at speed [Hz]"}},
              "legend": {"orientation": "h", "y": -0.25}, "height": 380}
    rows = [[_e(a["link"]), _number(a["tension"], 3), _number(a["compression"], 3)]
            for a in modes["axial_N"]]
    return "".join(parts) + (
        _figure(page, figures, "speed", data, layout)
        + '<p class="note">Frequencies at the analysed pose from rest to the operating speed '
          "(inertia preload, centrifugal softening, Coriolis coupling), in frequency order"
        + ("; the frame diverges at the operating speed" if modes["diverges"] else "")
        + ".</p><h4>Axial preload at the operating speed</h4>"
        + _table(["link", "largest tension [N]", "largest compression [N]"], rows,
                 numeric_from=1))


def kinetostatics_section(page: dict, figures: list) -> str:
    """Output torques and transmission ratios over the turn for the input torque the scene
    declares, its dead points and peaks; "" (no section) for a scene that declares none."""
    k = page.get("kinetostatics")
    if k is None:
        return ""
    if "unavailable" in k:
        return f"<h3>Output torques</h3><p>Not available: {_e(k['unavailable'])}</p>"
    t = k["input_torque_N_m"]
    torque = (f"{t['min']:.4g} N m" if t["min"] == t["max"]
              else f"{t['min']:.4g} to {t['max']:.4g} N m")
    dead = "; ".join(f"{d['crank_deg']:.2f} deg ({', '.join(map(_e, d['outputs']))})"
                     for d in k["dead_points"])
    parts = [f"<h3>Output torques</h3><p>Input torque {torque} at the driver, crank speed "
             f"{_number(k['rev_per_min'], 1)} rev/min, {_e(k['sharing'])} sharing, friction m = "
             f"{k['friction_m']:g}, bearing efficiency eta = {k['efficiency_eta']:g}."
             + (f" Dead points (torques and pin forces unbounded): {dead}." if dead else "")
             + "</p>"]
    for name, curves, title in (("outputs", k["torques_N_m"], "output torque [N m]"),
                                ("ratios", k["ratios"], "transmission ratio [-]")):
        data = [{"type": "scatter", "mode": "lines", "x": k["crank_deg"], "y": y, "name": n,
                 "hovertemplate": "%{x:.1f} deg: %{y:.4g}<extra></extra>"}
                for n, y in curves.items()]
        layout = {"xaxis": {"title": {"text": "crank angle [deg]"}, "range": [0, 360],
                            "dtick": 60}, "yaxis": {"title": {"text": title}},
                  "legend": {"orientation": "h", "y": -0.25},
                  "shapes": [{"type": "line", "x0": d["crank_deg"], "x1": d["crank_deg"],
                              "yref": "paper", "y0": 0, "y1": 1,
                              "line": {"color": "#c0392b", "width": 1}}
                             for d in k["dead_points"]]}
        parts.append(_figure(page, figures, f"kineto-{name}", data, layout))
    names = list(k["ratios"])
    rows = [[_number(r["crank_deg"], 1)]
            + [_number(v, 1) for v in r["torques_N_m"].values()]
            + [_number(r["ratios"][n], 4) for n in names]
            + ["near a dead point" if r["near_dead_point"] else ""] for r in k["rows"]]
    header = (["crank [deg]"] + [f"T[{_e(o)}] [N m]" for o in k["torques_N_m"]]
              + [_e(n) for n in names] + [""])
    peaks = "; ".join(
        f"{_e(p['name'])} {p['peak']:.4g} {_e(p['unit'])} at {p['at_deg']:.0f} deg"
        + (" (still rising towards a dead point)" if p["rises_towards_dead_point"] else "")
        for p in k["peaks"])
    return "".join(parts) + _table(header, rows, numeric_from=0) + (
        '<p class="note">Gaps and red lines: next to a dead point every torque and pin force '
        "grows without bound, so no sample there is a result. Peaks away from them: "
        f"{peaks}.</p>")


def _steady_response_part(page: dict, figures: list, response: dict | None) -> str:
    """Midspan bending strain over the turn at the operating speed, with each peak."""
    if response is None:
        return ""
    if "unavailable" in response:
        return f"<p>Steady response not available: {_e(response['unavailable'])}</p>"
    data = [{"type": "scatter", "mode": "lines", "x": response["crank_deg"],
             "y": [x * 1e6 for x in p["strain"]], "name": p["label"],
             "hovertemplate": "%{x:.1f} deg: %{y:.4g} microstrain<extra></extra>"}
            for p in response["points"]]
    layout = {"xaxis": {"title": {"text": "crank angle [deg]"}, "range": [0, 360], "dtick": 60},
              "yaxis": {"title": {"text": "bending strain [1e-6]"}},
              "legend": {"orientation": "h", "y": -0.25}}
    rows = [[_e(p["label"]), _number(p["peak_strain"] * 1e6, 3),
             _number(p["peak_deflection_m"] * 1e3, 4), _number(p["deflection_to_depth"], 3)]
            for p in response["points"]]
    beyond = [p for p in response["points"] if not p["small_deflection"]]
    warning = ('<div class="warnings"><strong>Beyond small deflection</strong><ul>' + "".join(
        f"<li>{_e(p['label'])}: peak deflection {p['deflection_to_depth']:.3g} times the "
        f"link's depth (limit {response['small_deflection_limit']:g}): the linear model does "
        "not hold there</li>" for p in beyond) + "</ul></div>") if beyond else ""
    return ("<h4>Steady response</h4>" + warning
            + _figure(page, figures, "response", data, layout)
            + '<p class="note">Bending strain at each link\'s midspan (outer fibre) over one '
              "turn once the start-up transient has died out (6 modes, damping ratio 0.01; "
              "docs/steady-response.md).</p>"
            + _table(["point", "peak strain [1e-6]", "peak deflection [mm]",
                      "deflection / depth"], rows, numeric_from=1))


def life_section(page: dict, figures: list) -> str:
    """Stress and life at the operating speed (``flexlink life`` with its default conditions),
    for a scene that declares a speed and whose materials give strengths; "" otherwise."""
    life = page.get("life")
    if life is None:
        return ""
    if "unavailable" in life:
        return f"<h3>Stress and life</h3><p>Not available: {_e(life['unavailable'])}</p>"
    data = [{"type": "scatter", "mode": "lines", "x": life["crank_deg"], "y": c["stress_MPa"],
             "name": c["link"], "hovertemplate": "%{x:.1f} deg: %{y:.4g} MPa<extra></extra>"}
            for c in life["curves"]]
    layout = {"xaxis": {"title": {"text": "crank angle [deg]"}, "range": [0, 360], "dtick": 60},
              "yaxis": {"title": {"text": "stress at the link's peak point [MPa]"}},
              "legend": {"orientation": "h", "y": -0.25}}
    rows = []
    for link in life["links"]:
        p = link["peak"]
        if link["kind"] == "metal":
            margin = _number(link["safety_factor"], 3) if link["safety_factor"] else "inf"
            hours = ("unlimited" if link["unlimited_life"]
                     else _number(link["life_hours"], 3))
        else:
            margin = _number(min(link["max_stress_ratio"], link["tsai_wu_ratio"]), 3) + "*"
            hours = "none*"
        rows.append([_e(link["link"]), _number(p["stress_MPa"], 4),
                     f"{_number(p['position_m'] * 1e3, 4)} mm, {_e(p['fibre'])}, "
                     f"{_number(p['crank_deg'], 1)} deg",
                     _number(link["range"]["stress_MPa"], 4), _number(link["range_mean_MPa"], 4),
                     margin, hours])
    c = life["conditions"]
    composite = any(link["kind"] == "composite" for link in life["links"])
    return ("<h3>Stress and life</h3>"
            + f"<p>At {_number(life['speed_rev_per_min'], 1)} rev/min. Included: "
              f"{_e(life['included'])}. Assumed: {_e(life['assumptions'])}. Parts: "
              f"{_e(c['surface'])} surface, {_number(c['temperature_C'], 1)} C, reliability "
              f"{_number(c['reliability'], 3)}, {_e(c['mean_stress'])} mean-stress correction "
              "(docs/life.md).</p>"
            + _figure(page, figures, "life", data, layout)
            + _table(["link (worst first)", "peak [MPa]", "where, when", "range [MPa]",
                      "mean [MPa]", "safety factor", "life [h]"], rows, numeric_from=1)
            + (f'<p class="note">* composite: the smaller ply strength ratio (maximum stress, '
               f"Tsai-Wu); {_e(next(k['note'] for k in life['links'] if k['kind'] == 'composite'))}</p>"
               if composite else ""))


def correlation_section(page: dict, figures: list) -> str:
    """A modal test correlated with the scene (``flexlink report --test``): the MAC heat map,
    the pairs with their frequency errors, the unpaired modes and aliasing warnings; "" (no
    section) without a test."""
    c = page.get("correlation")
    if c is None:
        return ""
    mac = c["mac"]
    data = [{"type": "heatmap", "z": mac, "zmin": 0, "zmax": 1, "colorscale": "Viridis",
             "x": [f"model {m['mode']} ({m['Hz']:.0f} Hz)" for m in c["model"]["modes"]],
             "y": [f"test {m['mode']} ({m['Hz']:.0f} Hz)" for m in c["test"]["modes"]],
             "hovertemplate": "%{y} / %{x}: MAC %{z:.3f}<extra></extra>"}]
    layout = {"yaxis": {"autorange": "reversed"}, "height": 120 + 28 * len(mac),
              "margin": {"l": 130, "r": 15, "t": 20, "b": 110}}
    rows = [[str(p["test"]), _number(p["test_Hz"]), str(p["model"]), _number(p["model_Hz"]),
             f"{p['error_pct']:+.2f}", f"{p['mac']:.3f}", _e(p["quality"]),
             "-" if p["test_damping"] is None else _number(100 * p["test_damping"]),
             _e(p["model_label"])] for p in c["pairs"]]
    notes = [f"Unpaired test mode {u['mode']} ({_number(u['Hz'])} Hz): best MAC "
             f"{u['best_mac']:.3f} with model mode {u['best_model']}." for u in c["unpaired_test"]]
    if c["unpaired_model"]:
        notes.append("Model modes not paired: " + ", ".join(
            f"{u['mode']} ({_number(u['Hz'])} Hz, {_e(u['label'])})" for u in c["unpaired_model"])
            + ".")
    notes += [f"Warning: test modes {a['a']} and {a['b']} have autoMAC {a['auto_mac']:.3f}: the "
              "sensors cannot tell them apart (spatial aliasing)." for a in c["aliased"]]
    t = c["thresholds"]
    return ("<h3>Test correlation</h3>"
            f"<p>Test {_e(c['test']['file'])}: {c['test']['sensors']} sensors, "
            f"{c['test']['channels']} channels. Modes paired by shape (MAC, optimal "
            f"assignment): &ge; {t['good']} good, {t['doubtful']}-{t['good']} doubtful, below "
            "not paired.</p>"
            + _figure(page, figures, "mac", data, layout)
            + _table(["test", "test Hz", "model", "model Hz", "error %", "MAC", "quality",
                      "damping %", "model mode"], rows, 0)
            + "".join(f'<p class="note">{n}</p>' for n in notes))


def files_section(page: dict, figures: list) -> str:
    files = page["files"]
    links = [f'<li><a href="{_e(p)}">{_e(p)}</a></li>' for p in files["vtu"] + files["pvd"]]
    if not links:
        return ""
    return ("<h3>Files for ParaView</h3><p>Next to this page (send the folder along to keep the "
            "links working): all modes as point data (.vtu) and one animation per mode (.pvd, "
            "press play in ParaView).</p><ul class=\"files\">" + "".join(links) + "</ul>")


def _failures(messages) -> str:
    if not messages:
        return ""
    return ('<div class="warnings"><strong>Scenes not in this report</strong><ul>'
            + "".join(f"<li>{_e(m)}</li>" for m in messages) + "</ul></div>")


def kinematics_section(page: dict, figures: list) -> str:
    """A scene without beams: why there are no modes, its rigid motion as ``flexlink
    kinematics`` prints it, and its transmission angles over the cycle."""
    kin = page["kinematics"]
    data = [{"type": "scatter", "mode": "lines", "x": kin["crank_deg"], "y": values,
             "name": f"mu {pair}"} for pair, values in kin["transmission_deg"].items()]
    figure = _figure(page, figures, "transmission", data, {
        "xaxis": {"title": {"text": "crank angle [deg]"}},
        "yaxis": {"title": {"text": "transmission angle [deg]"}}, "height": 300}) if data else ""
    return (f"<h3>Rigid motion</h3><p class=\"note\">{_e(kin['note'])}.</p>"
            f"<pre>{_e(kin['text'])}</pre>" + figure)


SECTIONS = (pose_section, frequency_section, assumptions_section, sensitivity_section,
            mesh_section, modes_section,
            cycle_section, at_speed_section, life_section, kinetostatics_section,
            correlation_section,
            files_section)
KINEMATIC_SECTIONS = (pose_section, kinematics_section)  # a scene without beams


def render_page(pages: list[dict], plotly_js: str, title: str = "flexlink report",
                subtitle: str = "", failures: tuple[str, ...] = ()) -> str:
    """The whole page for ``pages`` (``report_data.scene_page`` each); ``plotly_js``: the
    plotly.js bundle, inlined; ``failures``: one message per scene that could not be
    analysed, listed at the top."""
    figures: list = []
    scenes = []
    for page in pages:
        sections = KINEMATIC_SECTIONS if "kinematics" in page else SECTIONS
        parts = [section(page, figures) for section in sections]
        summary = page["summary"]
        scenes.append(f'<section class="scene" id="scene-{_e(page["id"])}">'
                      f'<h2>{_e(summary["scene"])}</h2><p class="file">{_e(summary["file"])}</p>'
                      + "".join(f'<div class="part">{p}</div>' for p in parts if p)
                      + "</section>")
    nav = "".join(f'<li><a href="#scene-{_e(p["id"])}">{_e(p["summary"]["scene"])}</a>: '
                  f'{headline(p["summary"])}</li>' for p in pages)
    data = {"figures": figures,
            "animations": {p["id"]: p["shapes"] for p in pages if p["shapes"]["modes"]}}
    # "</script" inside a script would end it early; "<\/" means "</" in JSON and in
    # JavaScript strings, the only places a script can hold it
    payload = json.dumps(data, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
    plotly_js = re.sub(r"</(script)", r"<\\/\1", plotly_js, flags=re.I)
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            f"<title>{_e(title)}</title><style>{STYLE}</style></head><body>"
            f"<header><h1>{_e(title)}</h1><p>{_e(subtitle)}</p><nav><ul>{nav}</ul></nav></header>"
            f"<main>{_failures(failures)}{''.join(scenes)}</main>"
            f'<script type="application/json" id="flexlink-data">{payload}</script>'
            f"<script>{plotly_js}</script><script>{SCRIPT}</script></body></html>\n")
