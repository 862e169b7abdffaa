"""``flexlink cycle SCENE``: the modal map over one crank revolution and a resonance check."""

from __future__ import annotations

import math
import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (TOLERANCE, dumps, json_option,
                                       map_parallel_options, out_option)


@click.command("cycle")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("-n", "--modes", "n_modes", default=3, show_default=True,
              type=click.IntRange(1, 50), help="Elastic modes per pose.")
@click.option("--poses", default=360, show_default=True, type=click.IntRange(3, 100000),
              help="Crank angles over one revolution.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: the scene's mesh.elements_per_link if it pins "
                   "one, else the coarsest mesh meeting --tol at the start pose).")
@click.option("--tol", default=None, type=TOLERANCE,
              help="Relative frequency tolerance of the default mesh (as in `flexlink modes`) "
                   "[default: 1e-6].")
@click.option("--speed", default=None,
              help="Crank speed for the resonance check, e.g. '2000 rev/min' (default: the "
                   "scene's operation.crank_speed; none or 0: no check; negative: the other "
                   "direction, checked at |speed|).")
@click.option("--margin", default=0.05, show_default=True, type=click.FloatRange(0, 1),
              help="Relative distance that counts as near a natural frequency.")
@click.option("--harmonics", default=10, show_default=True, type=click.IntRange(1, 10000),
              help="Crank harmonics n = 1 ... this number.")
@click.option("--track/--sorted", default=True, show_default=True,
              help="Follow each mode's shape from pose to pose by MAC (crossings and veerings "
                   "marked), or list the n-th lowest frequency at each pose (faster).")
@map_parallel_options(sorted_map=True)
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, n_modes, poses, elements, tol, speed, margin, harmonics, track, jobs,
            scheduler, as_json, out_dir):
    """Natural frequencies of the first modes at every crank angle of SCENE (CSV and PNG in
    --out), the poses where the transmission angle is 90 deg, and the crank harmonics that
    come within --margin of a natural frequency anywhere in the cycle. Writes cycle.csv,
    cycle.png and cycle.json to OUT/<scene>/."""
    from flexlink.studies.cycle import (modal_map, modal_map_csv, plot_map, resonance_speed,
                                        resonances, runs)
    from flexlink.studies.campbell import nearest_harmonic
    from flexlink.studies.tracking import events_json, plot_tracked, tracked_csv, tracked_map
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.parallel import use_scheduler
    from flexlink.scene import load_scene
    from flexlink.units import parse_quantity
    from ._progress import progress_bar
    from ._written import announce, scene_folders, write_drawn

    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    omega = (scene.options.crank_speed if speed is None else
             parse_quantity(speed, "angular speed", source="command line", field="--speed"))
    check_speed, check_note = resonance_speed(omega)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    with use_scheduler(scheduler):
        if track:
            result = tracked_map(scene, poses, n_modes, mesh.elements,
                                 progress=progress_bar("tracked modes", as_json), n_jobs=jobs)
        else:
            result = modal_map(scene, poses, n_modes, mesh.elements,
                               progress=progress_bar("modal map", as_json))
    hits = resonances(result, check_speed, margin, harmonics) if check_speed else []
    paths = [folder / "cycle.csv", folder / "cycle.png", folder / "cycle.json"]
    write_atomic(paths[0], tracked_csv(result) if track else modal_map_csv(result))
    if track:
        write_drawn(paths[1], lambda file: plot_tracked(result, file, check_speed, hits))
    else:
        plot_map(result, paths[1], check_speed, hits)
    f = result.frequencies
    document = {
        "command": "cycle", "scene": scene.name, "poses": poses,
        "synthesis": scene.synthesis,
        "modes": [{"mode": j + 1, "min_Hz": float(f[:, j].min()),
                   "at_crank_deg": math.degrees(result.q[f[:, j].argmin()]) % 360.0,
                   "max_Hz": float(f[:, j].max()),
                   "at_crank_deg_max": math.degrees(result.q[f[:, j].argmax()]) % 360.0}
                  for j in range(f.shape[1])],
        "mu90_crank_deg": {k: [math.degrees(a) for a in v] for k, v in result.mu90.items()},
        "mechanism_modes_max": int(result.mechanism_counts.max()),
        "mesh": mesh.as_dict(),
        "crank_speed_rev_per_min": None if omega is None else omega * 60 / (2 * math.pi),
        "resonance_check": {"speed_rev_per_min": None if check_speed is None
                                                 else check_speed * 60 / (2 * math.pi),
                            "note": check_note},
        "margin": margin,
        "resonances": [{"harmonic": h.harmonic, "harmonic_Hz": h.frequency, "mode": h.mode,
                        "closest_relative_gap": h.closest,
                        "crank_deg_ranges": [[round(math.degrees(a), 2), round(math.degrees(b), 2)]
                                             for a, b in runs(h.angles, 2 * math.pi / poses)]}
                       for h in hits],
        "tracking": {"by": "MAC", "labels": list(result.labels),
                     "events": events_json(result)} if track else {"by": "frequency order"},
        "nearest_harmonic": None if not check_speed else dict(zip(
            ("relative_gap", "mode", "harmonic"),
            nearest_harmonic(result.frequencies, check_speed, harmonics))),
        "files": [str(p) for p in paths],
        "assumptions": [f"{a.field}: {a.note}" for a in scene.assumptions],
    }
    write_atomic(paths[2], dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(f"{scene.name}: first {n_modes} elastic modes over {poses} crank angles")
    click.echo(mesh.describe())
    if scene.synthesis:
        click.echo(f"synthesis {scene.synthesis['method']}: " + ", ".join(
            f"{k} {1e3 * v:.3f} mm" for k, v in scene.synthesis["lengths_m"].items()))
    click.echo(f"{'mode':>4} {'min [Hz]':>10} {'at [deg]':>9} {'max [Hz]':>10} {'at [deg]':>9}")
    labels = document["tracking"].get("labels", [])
    for m in document["modes"]:
        click.echo(f"{m['mode']:>4} {m['min_Hz']:>10.2f} {m['at_crank_deg']:>9.1f} "
                   f"{m['max_Hz']:>10.2f} {m['at_crank_deg_max']:>9.1f}"
                   + (f"  {labels[m['mode'] - 1]}" if m["mode"] <= len(labels) else ""))
    for pair, angles in document["mu90_crank_deg"].items():
        where = (", ".join(f"{a:.2f}" for a in angles) + " deg") if angles else "never in the cycle"
        click.echo(f"mu = 90 deg ({pair}) at crank {where}")
    if check_note:
        click.echo(check_note)
    if check_speed and not hits:
        near = document["nearest_harmonic"]
        click.echo(f"resonance check at {document['resonance_check']['speed_rev_per_min']:g} "
                   f"rev/min: no harmonic 1..{harmonics} within {100 * margin:g} % of a natural "
                   f"frequency; nearest: harmonic {near['harmonic']} at "
                   f"{100 * near['relative_gap']:.1f} % from mode {near['mode']}")
    for e in document.get("tracking", {}).get("events", []):
        click.echo(f"{e['kind']} of modes {e['lines'][0]} and {e['lines'][1]} at crank "
                   f"{e['crank_deg']:.1f} deg (gap {100 * e['gap']:.1f} %)")
    for h in document["resonances"]:
        ranges = ", ".join(f"{a:.1f}-{b:.1f}" for a, b in h["crank_deg_ranges"])
        click.echo(f"resonance: harmonic {h['harmonic']} ({h['harmonic_Hz']:.2f} Hz) within "
                   f"{100 * margin:g} % of mode {h['mode']} at crank {ranges} deg")
    announce(paths, as_json)
