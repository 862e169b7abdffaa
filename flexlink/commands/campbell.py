"""``flexlink campbell SCENE --speeds "0:3000 rev/min"``: Campbell diagram and critical speeds."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (TOLERANCE, dumps, json_option,
                                       map_parallel_options, out_option)


def parse_speeds(text: str) -> tuple[float, float]:
    """"LOW:HIGH UNIT" (or "LOW UNIT:HIGH UNIT") -> (low, high) [rad/s] (``units.parse_range``)."""
    from flexlink.units import parse_range

    return parse_range(text, "angular speed", source="command line", field="--speeds")


@click.command("campbell")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--speeds", required=True,
              help="Crank speed range, e.g. '0:3000 rev/min'.")
@click.option("-n", "--modes", "n_modes", default=3, show_default=True,
              type=click.IntRange(1, 50), help="Tracked elastic modes.")
@click.option("--poses", default=72, show_default=True, type=click.IntRange(3, 100000),
              help="Crank angles over one revolution for the bands.")
@click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
              help="Elements per link (default: as in `flexlink cycle`).")
@click.option("--tol", default=None, type=TOLERANCE,
              help="Relative frequency tolerance of the default mesh [default: 1e-6].")
@click.option("--margin", default=0.05, show_default=True, type=click.FloatRange(0, 1),
              help="Relative distance from a band that counts as critical.")
@click.option("--harmonics", default=10, show_default=True, type=click.IntRange(1, 10000),
              help="Crank harmonics n = 1 ... this number.")
@click.option("--dynamic", is_flag=True,
              help="Also the bands at each speed from the modes at speed (inertia preload, "
                   "centrifugal, Coriolis), and how they move the critical speed ranges.")
@click.option("--speed-steps", default=50, show_default=True, type=click.IntRange(2, 100000),
              help="Crank speeds across the range for --dynamic.")
@click.option("--crank-acceleration", "acceleration", default=None, metavar="ACCELERATION",
              help="With --dynamic: the crank's angular acceleration at every speed, e.g. "
                   "'50 rad/s^2' [default: 0, constant speed].")
@map_parallel_options(sorted_map=False)
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speeds, n_modes, poses, elements, tol, margin, harmonics, dynamic,
            speed_steps, acceleration, jobs, scheduler, as_json, out_dir):
    """Campbell diagram of SCENE: each tracked mode's frequency band over the crank cycle
    against crank speed, the harmonics n x speed and the margin band; the critical speed
    ranges where a harmonic enters a band (with the margin), or the nearest margin when none
    does. Writes campbell.png, campbell.csv and campbell.json to OUT/<scene>/; with
    --dynamic also campbell_at_speed.png and .csv, and the ranges at speed in the JSON."""
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.parallel import use_scheduler
    from flexlink.scene import load_scene
    from flexlink.analysis.families import in_plane_only_note
    from flexlink.output.campbell_report import campbell_json, critical_csv, plot_campbell
    from flexlink.output.tracking_report import (events_json, periodicity_json, reseeds_json,
                                                 unsampled_json)
    from flexlink.studies.campbell import RPM, bands, critical_speeds, nearest_margin
    from flexlink.studies.tracking import tracked_map, unsampled_note, vanishing_lines
    from ._progress import progress_bar
    from ._written import announce, scene_folders

    window = parse_speeds(speeds)
    qdd = parse_acceleration(acceleration, dynamic)
    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    with use_scheduler(scheduler):
        result = tracked_map(scene, poses, n_modes, mesh.elements,
                             progress=progress_bar("tracked modes", as_json), n_jobs=jobs)
    found = bands(result.frequencies, vanishing_lines(result))
    critical = critical_speeds(found, window, margin, harmonics)
    nearest = nearest_margin(found, window, harmonics)
    labels = dict(enumerate(result.labels, start=1))
    paths = [folder / "campbell.png", folder / "campbell.csv", folder / "campbell.json"]
    at_speed = _at_speed(scene, window, n_modes, poses, mesh.elements, margin, harmonics,
                         speed_steps, folder, progress_bar("poses at speed", as_json), qdd) \
        if dynamic else None
    plot_campbell(found, window, margin, harmonics, critical, paths[0], scene.name, labels)
    write_atomic(paths[1], critical_csv(critical, found))
    document = {"command": "campbell", "scene": scene.name,
                "speeds_rev_per_min": [window[0] / RPM, window[1] / RPM], "margin": margin,
                "harmonics": harmonics, "poses": poses, "mesh": mesh.as_dict(),
                **campbell_json(found, critical, nearest, labels),
                "tracking_events": events_json(result),
                "tracking_reseeds": reseeds_json(result),
                "periodicity": periodicity_json(result),
                "unsampled_dead_centres_deg": unsampled_json(result),
                "unsampled_note": unsampled_note(result),
                **({"at_speed": at_speed[0]} if at_speed else {}),
                "files": [str(p) for p in paths + (at_speed[2] if at_speed else [])]}
    note = in_plane_only_note(scene, "this diagram")
    if note:  # the diagram holds the in-plane modes only
        document["note"] = note
    write_atomic(paths[2], dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(f"{scene.name}: {n_modes} tracked modes over {poses} crank angles, "
               f"{window[0] / RPM:g}-{window[1] / RPM:g} rev/min, harmonics 1..{harmonics}, "
               f"margin {100 * margin:g} %")
    click.echo(mesh.describe())
    if note:
        click.echo(note)
    click.echo(f"{'mode':>4} {'band [Hz]':>19}  label")
    for b in document["bands"]:
        click.echo(f"{b['mode']:>4} {b['min_Hz']:>9.2f}-{b['max_Hz']:<9.2f}  {b['label'] or ''}")
    for r in document["tracking_reseeds"]:
        click.echo(f"re-seeded line{'s' if len(r['lines']) > 1 else ''} "
                   f"{', '.join(map(str, r['lines']))} at crank "
                   f"{r['crank_deg']:.1f} deg: {r['reason']}")
    if document["unsampled_note"]:
        click.echo(f"warning: {document['unsampled_note']}")
    click.echo(f"periodicity: {document['periodicity']['note']}")
    if critical:
        click.echo(f"critical speeds:\n{'mode':>4} {'harmonic':>8} {'from [rev/min]':>15} "
                   f"{'to [rev/min]':>13}")
        for c in document["critical_speeds"]:
            click.echo(f"{c['mode']:>4} {c['harmonic']:>8} {c['from_rev_per_min']:>15.1f} "
                       f"{c['to_rev_per_min']:>13.1f}")
    else:  # the nearest margin says how close the range comes (inside a band it is 0)
        n = document["nearest_margin"]
        click.echo("no critical speed in the range; nearest margin: harmonic "
                   f"{n['harmonic']} of mode {n['mode']}, relative gap "
                   f"{100 * n['relative_gap']:.2f} % at {n['at_rev_per_min']:.1f} rev/min")
    for line in at_speed[1] if at_speed else ():
        click.echo(line)
    announce(paths + (at_speed[2] if at_speed else []), as_json)


def parse_acceleration(text: str | None, dynamic: bool) -> float:
    """--crank-acceleration [rad/s^2] (0 when not given); it needs --dynamic."""
    from flexlink.errors import InputError
    from flexlink.units import parse_quantity

    if text is None:
        return 0.0
    if not dynamic:
        raise InputError("a crank acceleration is for the bands at speed: give --dynamic too",
                         source="command line", field="--crank-acceleration",
                         expected="--dynamic with --crank-acceleration")
    return parse_quantity(text, "angular acceleration", source="command line",
                          field="--crank-acceleration")


def _at_speed(scene, window, n_modes, poses, elements, margin, harmonics, steps, folder,
              progress, acceleration=0.0):
    """(JSON, text lines, files written) of the speed-dependent diagram over ``window``."""
    import numpy as np

    from flexlink.fileio import write_atomic
    from flexlink.output.dynamic_campbell import (dynamic_csv, dynamic_json, dynamic_lines,
                                                  plot_dynamic)
    from flexlink.studies.dynamic_campbell import critical_shifts, dynamic_campbell

    result = dynamic_campbell(scene, np.linspace(*window, steps), poses, n_modes, elements,
                              progress=progress, crank_acceleration=acceleration)
    shifts = critical_shifts(result, margin, harmonics)
    files = [folder / "campbell_at_speed.png", folder / "campbell_at_speed.csv"]
    plot_dynamic(result, margin, harmonics, files[0], scene.name)
    write_atomic(files[1], dynamic_csv(result))
    return dynamic_json(result, shifts), dynamic_lines(result, shifts), files
