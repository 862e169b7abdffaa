"""Rendering of ``studies.life``: the JSON document, the text, the full stress field as CSV
and as a ParaView time series over the crank angle, and the pictures (Haigh diagram, stress
along each link over the turn, margin against speed)."""

from __future__ import annotations

import math

import numpy as np

from flexlink.studies.life.convergence import HOW
from flexlink.studies.life.life import COMPOSITE_NOTE, LinkKind
from flexlink.studies.life.stress_field import ASSUMPTIONS, INCLUDED
from flexlink.units import RPM

MPA = 1e6


def _number(x: float):
    """JSON has no inf or NaN: null."""
    return None if x is None or not math.isfinite(x) else float(x)


def _where(w) -> dict:
    return {"stress_MPa": w.value / MPA, "position_m": w.position,
            "fibre": "+y" if w.fibre > 0 else "-y", "crank_deg": math.degrees(w.angle) % 360}


def strength_data(materials: str) -> dict:
    """The strength data of the material(s) ``materials`` (shipped names or paths, " + "
    between two) with their ranges and sources: what the verdict rests on, estimates
    included."""
    from flexlink.materials.strength import EXPONENT_KEY, load_strength

    out = {}
    for name in materials.split(" + "):
        strength = load_strength(name)
        out[name] = {key: {("value" if key == EXPONENT_KEY else "value_MPa"):
                           d.value if key == EXPONENT_KEY else d.value / MPA,
                           "range": [d.low, d.high] if key == EXPONENT_KEY
                           else [d.low / MPA, d.high / MPA], "source": d.source}
                     for key, d in strength.data.items()}
    return out


def life_document(scene, study, model=None, error=None) -> dict:
    """The ``life`` command's document: what is included and assumed, the conditions, the
    error estimate, and per link (worst first) its peak, range, mean, safety and life; the
    basis, damping and mesh of the stress ``model`` where given."""
    c = study.conditions
    links = []
    for link in study.links:
        entry = {"link": link.link, "kind": str(link.kind), "material": link.material,
                 "peak": _where(link.peak), "range": _where(link.range),
                 "range_mean_MPa": link.mean / MPA,
                 "quasi_static_peak_MPa": link.quasi_static_peak / MPA,
                 "strength_data": strength_data(link.material)}
        if link.kind is LinkKind.METAL:
            hours = study.hours(link)
            entry.update({
                "safety_factor": _number(link.safety), "worst": _where(link.worst),
                "worst_cycle": {"amplitude_MPa": link.amplitude / MPA,
                                "mean_MPa": link.cycle_mean / MPA},
                "life_turns": _number(link.life), "life_hours": _number(hours),
                "unlimited_life": not math.isfinite(link.life),
                "yield_safety_factor": _number(link.yield_safety),
                "endurance_limit_MPa": link.endurance / MPA, "Sut_MPa": link.Sut / MPA,
                "Sy_MPa": link.Sy / MPA, "marin": link.marin, "load_type": link.load_type})
        else:
            entry.update({"max_stress_ratio": _number(link.max_stress_ratio),
                          "tsai_wu_ratio": _number(link.tsai_wu_ratio),
                          "worst_ply": link.ply, "life": None, "note": COMPOSITE_NOTE})
        links.append(entry)
    field = study.field
    document = {
        "command": "life", "scene": scene.name, "speed_rev_per_min": study.speed / RPM,
        "included": INCLUDED, "assumptions": ASSUMPTIONS,
        "scene_assumptions": [f"{a.field} = {a.value}: {a.note}" for a in scene.assumptions],
        "conditions": {"surface": str(c.surface), "temperature_C": c.temperature,
                       "reliability": c.reliability, "mean_stress": str(c.mean_stress),
                       "required_hours": c.hours,
                       "safety_against": ("the strength at the required life" if c.hours
                                          else "the endurance limit")},
        "harmonic_balance": {"harmonics": field.harmonics,
                             "estimated_error": field.harmonic_error},
        "largest_modulus": _number(field.largest_modulus),
        "links": links,
    }
    if model is not None:
        document.update({"basis_frequencies_Hz": model.forced.periodic.frequencies.tolist(),
                         "damping_source": model.forced.periodic.damping_source,
                         "elements_per_link": list(model.elements)})
    if error is not None:
        document["peak_stress_error"] = {
            "how": HOW, "tolerance": error.tolerance, "met": error.met,
            "links": {name: {"mesh": float(m), "basis": float(b), "estimate": float(e)}
                      for name, m, b, e in zip(error.links, error.mesh, error.basis,
                                               error.estimate)}}
    return document


def life_lines(document: dict) -> list[str]:
    """The text summary of the document."""
    out = [f"{document['scene']} at {document['speed_rev_per_min']:g} rev/min "
           f"(largest |mu| {document['largest_modulus'] or float('nan'):.4g})",
           f"included: {document['included']}",
           f"assumed: {document['assumptions']}"]
    c = document["conditions"]
    out.append(f"parts: {c['surface']} surface, {c['temperature_C']:g} C, reliability "
               f"{c['reliability']:g}, {c['mean_stress']} mean-stress correction, safety "
               f"against {c['safety_against']}")
    error = document.get("peak_stress_error")
    if error:
        worst = max(v["estimate"] for v in error["links"].values())
        out.append(f"estimated error of the peak stress: {worst * 100:.2g} % "
                   f"({'within' if error['met'] else 'NOT within'} {error['tolerance'] * 100:g} %"
                   f"; {error['how']})")
    out.append(f"{'link':>10} {'peak [MPa]':>11} {'at':>18} {'range [MPa]':>12} "
               f"{'mean [MPa]':>11} {'safety':>8} {'life [h]':>10}")
    for link in document["links"]:
        p = link["peak"]
        where = f"{p['position_m'] * 1e3:.4g} mm {p['fibre']} {p['crank_deg']:.0f} deg"
        if link["kind"] == "metal":
            safety = f"{link['safety_factor']:.3g}" if link["safety_factor"] else "inf"
            life = "unlimited" if link["unlimited_life"] else f"{link['life_hours']:.3g}"
        else:
            safety = f"{min(link['max_stress_ratio'], link['tsai_wu_ratio']):.3g}*"
            life = "none*"
        out.append(f"{link['link']:>10} {p['stress_MPa']:>11.4g} {where:>18} "
                   f"{link['range']['stress_MPa']:>12.4g} {link['range_mean_MPa']:>11.4g} "
                   f"{safety:>8} {life:>10}")
    if any(link["kind"] == "composite" for link in document["links"]):
        out.append(f"* composite: the smaller ply strength ratio (maximum stress, Tsai-Wu); "
                   f"{COMPOSITE_NOTE}")
    return out


def field_csv(study) -> str:
    """The full field: one row per crank angle and point (link, element, end, position,
    fibre), total, quasi-static and dynamic stress [Pa]."""
    field = study.field
    p = field.points
    deg = np.degrees(field.angles) % 360.0
    rows = ["crank_deg,link,element,end,position_m,fibre,stress_Pa,quasi_static_Pa,dynamic_Pa"]
    names = np.array(p.links)[p.link]
    fibre = np.where(p.fibre == 0, "+y", "-y")
    dynamic = field.dynamic
    for i, d in enumerate(deg):
        rows.extend(f"{d:.4f},{names[k]},{p.element[k]},{p.end[k]},{p.position[k]:.6g},"
                    f"{fibre[k]},{field.total[i, k]:.8g},{field.quasi_static[i, k]:.8g},"
                    f"{dynamic[i, k]:.8g}" for k in range(len(names)))
    return "\n".join(rows) + "\n"


def node_stresses(field, model, name: str) -> np.ndarray:
    """(samples, nodes, 2 fibres) [Pa] at ``name``'s nodes: the mean of the two element ends
    meeting at an inner node, the one end at the link's ends."""
    index = model.points.of(name)
    e = model.elements[model.points.links.index(name)]
    s = field.total[:, index].reshape(len(field.angles), e, 2, 2)  # (samples, e, end, fibre)
    nodes = np.zeros((len(field.angles), e + 1, 2))
    count = np.zeros(e + 1)
    nodes[:, :-1] += s[:, :, 0]
    nodes[:, 1:] += s[:, :, 1]
    count[:-1] += 1
    count[1:] += 1
    return nodes / count[None, :, None]


def write_life(folder, scene, study, model) -> list:
    """Every file of one speed's life study in ``folder``: life.csv (the full field), the
    ParaView series, life_haigh.png (where a link is metal) and life_stress.png; returns their
    paths."""
    from flexlink.fileio import write_atomic

    files = [write_atomic(folder / "life.csv", field_csv(study))]
    files += plot_haigh(study, folder / "life_haigh.png", scene.name)
    plot_stress_maps(study, model, folder / "life_stress.png", scene.name)
    files.append(folder / "life_stress.png")
    return files + write_series(folder, "life", scene, study, model)


def write_series(folder, stem: str, scene, study, model) -> list:
    """``<stem>.pvd`` over the crank angle (time = crank angle [deg]) and one .vtu per angle
    in ``<stem>/``: each link a line of its nodes at the rigid pose of that angle, with the
    point arrays stress_plus_y, stress_minus_y and stress_abs_max [Pa]."""
    import meshio

    from flexlink.errors import OutputError
    from flexlink.fe.model_at_pose import pose_model
    from flexlink.fileio import write_atomic
    from flexlink.output.export_vtk import pvd_text, write_vtu

    frames = folder / stem
    try:
        frames.mkdir(exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot create {frames}: {exc.strerror or exc}") from None
    field = study.field
    topology = scene.topology(model.elements[0] if len(set(model.elements)) == 1 else None)
    per_link = [node_stresses(field, model, name) for name in model.points.links]
    written, entries = [], []
    for i, angle in enumerate(field.angles):
        fem = pose_model(topology, scene.rigid_state(angle).points)
        points, cells, values = [], [], []
        for link, stress in zip(fem.links, per_link):
            first = sum(len(p) for p in points)
            points.append(fem.nodes[link.nodes])
            cells.append(np.stack([np.arange(link.elements), np.arange(1, link.elements + 1)],
                                  axis=1) + first)
            values.append(stress[i])
        xy = np.vstack(points)
        s = np.vstack(values)
        mesh = meshio.Mesh(np.column_stack([xy, np.zeros(len(xy))]), [("line", np.vstack(cells))],
                           point_data={"stress_plus_y": s[:, 0], "stress_minus_y": s[:, 1],
                                       "stress_abs_max": np.abs(s).max(axis=1)})
        file = frames / f"angle{i:03d}.vtu"
        written.append(write_vtu(file, mesh))
        start = math.degrees(field.angles[0]) % 360.0  # increasing times from the first angle
        entries.append((start + math.degrees(angle - field.angles[0]), f"{stem}/{file.name}"))
    written.append(write_atomic(folder / f"{stem}.pvd", pvd_text(entries)))
    return written


def plot_haigh(study, path, title: str) -> list:
    """PNG: the Haigh diagram (alternating against mean stress) of each metal link's part,
    with its Goodman line Se - Sut, the yield line Sy, and the link's worst cycle; returns
    ``[path]``, or ``[]`` (nothing drawn) where no link is metal: a composite link has no
    Goodman line (its verdict is the ply strength ratio, in the table)."""
    metals = [link for link in study.links if link.kind is LinkKind.METAL]
    if not metals:
        return []
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexlink.output.figures import write_figure

    fig, ax = plt.subplots(figsize=(7, 5))
    for k, link in enumerate(metals):
        colour = f"C{k}"
        ax.plot([0, link.Sut / MPA], [link.endurance / MPA, 0], color=colour, lw=1,
                label=f"{link.link}: Goodman, Se {link.endurance / MPA:.0f} MPa")
        ax.plot([0, link.Sy / MPA], [link.Sy / MPA, 0], color=colour, lw=0.8, ls="--",
                label=f"{link.link}: first-cycle yield, Sy {link.Sy / MPA:.0f} MPa")
        ax.plot([link.cycle_mean / MPA], [link.amplitude / MPA], "o", color=colour,
                label=f"{link.link}: worst cycle, n = {link.safety:.3g}")
    ax.set(xlabel="mean stress [MPa]", ylabel="alternating stress [MPa]",
           title=f"{title}: Haigh diagram at {study.speed / RPM:g} rev/min "
                 f"({study.conditions.mean_stress})")
    ax.set_xlim(left=min(0.0, ax.get_xlim()[0]))
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7)
    write_figure(fig, path)
    return [path]


def plot_stress_maps(study, model, path, title: str) -> None:
    """PNG: per link, the stress at its +y fibre (the left side, start -> end) as a colour map
    of crank angle against the distance along the link (the -y fibre's is N/A less the same
    bending part; both are in life.csv)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexlink.output.figures import write_figure

    field = study.field
    names = model.points.links
    fig, axes = plt.subplots(len(names), 1, figsize=(8, 2.4 * len(names)), squeeze=False)
    deg = np.degrees(field.angles - field.angles[0])
    for ax, name in zip(axes[:, 0], names):
        s = node_stresses(field, model, name)
        signed = s[..., 0] / MPA
        e = model.elements[names.index(name)]
        length = model.points.position[model.points.of(name)].max()
        x = np.linspace(0.0, length, e + 1) * 1e3
        limit = np.abs(signed).max() or 1.0
        image = ax.pcolormesh(deg, x, signed.T, cmap="RdBu_r", vmin=-limit, vmax=limit,
                              shading="nearest")
        fig.colorbar(image, ax=ax, label="stress [MPa]")
        ax.set(ylabel=f"{name} [mm]")
    axes[-1, 0].set(xlabel=f"crank angle from {math.degrees(field.angles[0]) % 360:.1f} deg "
                           "[deg]")
    axes[0, 0].set(title=f"{title}: stress at the +y fibre at {study.speed / RPM:g} rev/min")
    write_figure(fig, path)


def margin_document(scene, sweep) -> dict:
    """``life --speeds``: each link's margin against speed, unstable speeds null, beside the
    stability map's unstable ranges."""
    return {
        "command": "life", "scene": scene.name, "included": INCLUDED,
        "assumptions": ASSUMPTIONS,
        "margin": "the fatigue safety factor of a metal link, the smaller ply strength ratio "
                  "of a composite one",
        "speeds_rev_per_min": (sweep.speeds / RPM).tolist(),
        "largest_modulus": [_number(m) for m in sweep.largest_modulus],
        "links": {name: [_number(v) for v in sweep.margin[:, k]]
                  for k, name in enumerate(sweep.links)},
        "smallest_margin": [_number(np.nanmin(row)) if np.isfinite(row).any() else None
                            for row in sweep.margin],
        "unstable_ranges_rev_per_min": [
            {"low": r.low / RPM, "high": r.high / RPM, "kind": r.kind,
             "modes": list(r.modes), "harmonic": r.harmonic} for r in sweep.ranges],
    }


def margin_lines(document: dict) -> list[str]:
    speeds = document["speeds_rev_per_min"]
    out = [f"{document['scene']}: smallest margin over {len(speeds)} speeds, {speeds[0]:g} to "
           f"{speeds[-1]:g} rev/min ({document['margin']})"]
    for s, m in zip(speeds, document["smallest_margin"]):
        out.append(f"{s:>10.5g} rev/min: " + ("no steady state" if m is None else f"{m:.4g}"))
    for r in document["unstable_ranges_rev_per_min"]:
        out.append(f"unstable {r['low']:.5g} to {r['high']:.5g} rev/min ({r['kind']})")
    return out


def plot_margin_sweep(sweep, path, title: str) -> None:
    """PNG: each link's margin against speed, the stability map's unstable ranges shaded."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexlink.output.figures import write_figure

    rpm = sweep.speeds / RPM
    fig, ax = plt.subplots(figsize=(8, 4))
    for k, name in enumerate(sweep.links):
        ax.semilogy(rpm, sweep.margin[:, k], lw=1.2, label=name)
    for r in sweep.ranges:
        ax.axvspan(r.low / RPM, r.high / RPM, color="tab:red", alpha=0.25, lw=0)
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.set(xlabel="crank speed [rev/min]", ylabel="safety factor / strength ratio",
           title=f"{title}: margin against speed (shaded: no steady state)",
           xlim=(rpm[0], rpm[-1]))
    ax.legend(fontsize=8)
    write_figure(fig, path)
