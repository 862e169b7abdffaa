"""``flexlink campbell SCENE --speeds "0:3000 rev/min"``: Campbell diagram and critical speeds."""

from __future__ import annotations

import click

from flexlink.commands._failures import names_scene
from flexlink.commands._options import (TOLERANCE, dumps, json_option,
                                       map_parallel_options, out_option)


def parse_speeds(text: str) -> tuple[float, float]:
    """"LOW:HIGH UNIT" (or "LOW UNIT:HIGH UNIT") -> (low, high) [rad/s]."""
    from flexlink.errors import InputError
    from flexlink.units import parse_quantity

    parts = text.split(":")
    if len(parts) != 2:
        raise InputError(f"cannot read {text!r} as a speed range", field="--speeds",
                         expected="LOW:HIGH with a unit, e.g. '0:3000 rev/min'")
    low, high = (p.strip() for p in parts)
    unit = high.split(None, 1)[1] if len(high.split(None, 1)) == 2 else ""
    if low and not any(c.isalpha() for c in low.lstrip("eE+-.0123456789")) and unit:
        low = f"{low} {unit}"
    read = [parse_quantity(v, "angular speed", source="command line", field="--speeds")
            for v in (low, high)]
    return read[0], read[1]


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
@map_parallel_options(sorted_map=False)
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speeds, n_modes, poses, elements, tol, margin, harmonics, jobs, scheduler,
            as_json, out_dir):
    """Campbell diagram of SCENE: each tracked mode's frequency band over the crank cycle
    against crank speed, the harmonics n x speed and the margin band; the critical speed
    ranges where a harmonic enters a band (with the margin), or the nearest margin when none
    does. Writes campbell.png, campbell.csv and campbell.json to OUT/<scene>/."""
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.fileio import prepare_out_dir, write_atomic
    from flexlink.parallel import use_scheduler
    from flexlink.scene import load_scene
    from flexlink.studies.campbell import (RPM, bands, campbell_json, critical_csv,
                                           critical_speeds, nearest_margin, plot_campbell)
    from flexlink.studies.tracking import events_json, tracked_map
    from ._progress import progress_bar
    from ._written import announce, scene_folders, write_drawn

    window = parse_speeds(speeds)
    [folder] = scene_folders(prepare_out_dir(out_dir), [scene_path])
    scene = load_scene(scene_path)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    with use_scheduler(scheduler):
        result = tracked_map(scene, poses, n_modes, mesh.elements,
                             progress=progress_bar("tracked modes", as_json), n_jobs=jobs)
    found = bands(result.frequencies)
    critical = critical_speeds(found, window, margin, harmonics)
    nearest = nearest_margin(found, window, harmonics)
    labels = dict(enumerate(result.labels, start=1))
    paths = [folder / "campbell.png", folder / "campbell.csv", folder / "campbell.json"]
    write_drawn(paths[0], lambda file: plot_campbell(found, window, margin, harmonics, critical,
                                                     file, scene.name, labels))
    write_atomic(paths[1], critical_csv(critical, found))
    document = {"command": "campbell", "scene": scene.name,
                "speeds_rev_per_min": [window[0] / RPM, window[1] / RPM], "margin": margin,
                "harmonics": harmonics, "poses": poses, "mesh": mesh.as_dict(),
                **campbell_json(found, critical, nearest, labels),
                "tracking_events": events_json(result),
                "files": [str(p) for p in paths]}
    write_atomic(paths[2], dumps(document))
    if as_json:
        click.echo(dumps(document))
        return
    click.echo(f"{scene.name}: {n_modes} tracked modes over {poses} crank angles, "
               f"{window[0] / RPM:g}-{window[1] / RPM:g} rev/min, harmonics 1..{harmonics}, "
               f"margin {100 * margin:g} %")
    click.echo(mesh.describe())
    click.echo(f"{'mode':>4} {'band [Hz]':>19}  label")
    for b in document["bands"]:
        click.echo(f"{b['mode']:>4} {b['min_Hz']:>9.2f}-{b['max_Hz']:<9.2f}  {b['label'] or ''}")
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
    announce(paths, as_json)
