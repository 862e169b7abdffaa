"""``flexlink kinematics SCENE``: rigid motion over one crank revolution."""

from __future__ import annotations

import math
from pathlib import Path

import click

from flexlink.commands._options import dumps, json_option, out_option


def _analyse(scene, poses, omega, progress):
    from flexlink.studies.cycle import kinematic_cycle, transmission_angles
    from flexlink.kinematics.motion import body_summary, extremes, limit_positions

    cycle = kinematic_cycle(scene, poses, progress)
    linkage = scene.linkage
    bodies = {}
    for b in linkage.bodies:
        output = b.name != linkage.driver and b.joints[0] in linkage.ground
        bodies[b.name] = summary = body_summary(cycle, b.name, omega, output)
        limits = limit_positions(linkage, cycle, b.name) if output else []
        if limits:
            summary["limit_positions"] = limits
            angles = [lim["angle_deg"] for lim in limits]
            summary["swing_deg"] = max(angles) - min(angles)
            if len(limits) == 2:
                summary["time_ratio"] = _time_ratio(limits)
    mu = {k: extremes(cycle.q, v * 180 / math.pi)
          for k, v in transmission_angles(scene, cycle).items()}
    return cycle, {"scene": scene.name, "synthesis": scene.synthesis, "bodies": bodies,
                   "transmission_angle_deg": mu}


def _time_ratio(limits):
    """Crank turn from the first limit to the second over the turn back (>= 1)."""
    a, b = limits[0]["crank_deg"], limits[1]["crank_deg"]
    forward = (b - a) % 360.0
    return max(forward, 360.0 - forward) / min(forward, 360.0 - forward)


def _span(e, fmt):
    """'min@at .. max@at' of an ``motion.extremes`` dict."""
    return (f"{format(e['min'], fmt):>8}@{e['min_at_deg']:<5.1f}.. "
            f"{format(e['max'], fmt):>8}@{e['max_at_deg']:<5.1f}")


def _print_summary(doc, omega):
    click.echo(f"{doc['scene']}")
    if doc.get("synthesis"):
        s = doc["synthesis"]
        click.echo(f"  synthesis {s['method']} {s['inputs']}: " + ", ".join(
            f"{k} {1e3 * v:.3f} mm" for k, v in s["lengths_m"].items()))
    click.echo("  extremes over the cycle as value@crank angle [deg]")
    click.echo(f"  {'body':<9} {'angle [deg]':^27} {'K = dtheta/dq':^29} {'L = dK/dq':^29}")
    for name, b in doc["bodies"].items():
        a, K, L = b["angle_deg"], b["K"], b["L"]
        span = _span(a, ".3f") if a else f"{'full turn':^27}"
        click.echo(f"  {name:<9} {span} {_span(K, '.4f')} {_span(L, '.4f')}")
        for lim in b.get("limit_positions", []):
            click.echo(f"            limit position {lim['angle_deg']:.3f} deg at crank "
                       f"{lim['crank_deg']:.3f} deg")
        if "swing_deg" in b:
            ratio = f", time ratio {b['time_ratio']:.4f}" if "time_ratio" in b else ""
            click.echo(f"            swing {b['swing_deg']:.3f} deg{ratio}")
        if "torque_ratio_min_abs" in b:
            t = b["torque_ratio_min_abs"]
            click.echo(f"            |T_{name}/T_crank| = 1/|K| >= {t['value']:.4f} (at crank "
                       f"{t['at_deg']:.1f} deg)")
        if omega and "peak_abs_alpha" in b and "limit_positions" in b:
            w, p = b["omega_rad_s"], b["peak_abs_alpha"]
            click.echo(f"            omega {w['min']:.3f}..{w['max']:.3f} rad/s; peak |alpha| "
                       f"{p['value_rad_s2']:.1f} rad/s^2 at crank {p['at_deg']:.1f} deg")
    for pair, m in doc["transmission_angle_deg"].items():
        click.echo(f"  transmission angle {pair}: {m['min']:.3f} deg (crank {m['min_at_deg']:.1f})"
                   f" .. {m['max']:.3f} deg (crank {m['max_at_deg']:.1f})")


def _print_family(members, omega):
    """One line per family member and output body: swing, time ratio, omega and peak alpha."""
    label = None
    for m in members:
        if m["family"] != label:
            label = m["family"]
            click.echo(f"\n{label}:")
            click.echo(f"  {'value':>7} {'body':<8} {'limits [deg]':>17} {'swing':>8} {'ratio':>7}"
                       + (f" {'omega min..max [rad/s]':>23} {'peak |alpha| [rad/s^2] at':>29}"
                          if omega else ""))
        for name, b in m["bodies"].items():
            if "limit_positions" not in b:
                continue
            limits = "/".join(f"{lim['angle_deg']:.2f}" for lim in b["limit_positions"])
            line = (f"  {m['value']:>7g} {name:<8} {limits:>17} {b['swing_deg']:>8.3f} "
                    f"{b.get('time_ratio', float('nan')):>7.4f}")
            if omega:
                w, p = b["omega_rad_s"], b["peak_abs_alpha"]
                line += (f" {w['min']:>10.2f}..{w['max']:<10.2f} {p['value_rad_s2']:>15.1f} "
                         f"at {p['at_deg']:>6.1f} deg")
            click.echo(line)


@click.command("kinematics")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--poses", default=360, show_default=True, type=click.IntRange(3, 1000000),
              help="Crank angles over one revolution.")
@click.option("--speed", default=None,
              help="Constant crank speed, e.g. '2000 rev/min' (default: the scene's "
                   "operation.crank_speed, if any), for angular velocity and acceleration.")
@json_option
@out_option
def command(scene_path, poses, speed, as_json, out_dir):
    """Angular positions, velocity coefficients K = dtheta/dq and their derivatives
    L = dK/dq of every body of SCENE over one crank revolution: extremes and where they occur,
    limit positions, torque ratio 1/K; for a scene with [[family]] tables, every member too."""
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.kinematics.motion import motion_csv
    from flexlink.scene.load import load_scene
    from flexlink.scene.general import as_general
    from flexlink.units import parse_quantity
    from ._progress import progress_bar

    out = prepare_out_dir(out_dir)
    scene = as_general(load_scene(scene_path))
    r = scene.reader()
    if speed is not None:
        omega = parse_quantity(speed, "angular speed", source="command line", field="--speed")
    else:
        omega = r.quantity("operation.crank_speed", "angular speed", default=None)
    cycle, doc = _analyse(scene, poses, omega, progress_bar("kinematics", as_json))
    stem = Path(scene_path).stem
    written = [write_atomic(out / f"{stem}-kinematics.csv", motion_csv(cycle, omega))]
    members = []
    for family in r.raw("family", []):
        field, label = family["field"], family.get("name", family["field"])
        for value in family["values"]:
            member = as_general(load_scene(scene_path, overrides={field: value}))
            _, mdoc = _analyse(member, poses, omega, None)
            mdoc.update({"family": label, "field": field, "value": value})
            members.append(mdoc)
    document = {"command": "kinematics", "poses": poses,
                "crank_speed_rev_per_min": omega * 60 / (2 * math.pi) if omega else None,
                **doc, "family": members, "files": [str(p) for p in written],
                "assumptions": [f"{a.field}: {a.note}" for a in scene.assumptions]}
    write_atomic(out / f"{stem}-kinematics.json", dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    _print_summary(document, omega)
    _print_family(members, omega)
    click.echo(f"\nwritten: {written[0]}, {out / (stem + '-kinematics.json')}")
