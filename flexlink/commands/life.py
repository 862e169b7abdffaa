"""``flexlink life SCENE --speed ... | --speeds LOW:HIGH``: stress over the crank turn and the
fatigue life and safety factors of every link."""

from __future__ import annotations

import click

from flexlink.analysis.fatigue import MeanStress
from flexlink.commands._failures import names_scene
from flexlink.commands._options import EnumChoice, json_option, out_option
from flexlink.materials.fatigue import Surface


@click.command("life")
@click.argument("scene_path", metavar="SCENE", type=click.Path())
@click.option("--speed", help="Crank speed, e.g. '1200 rev/min' (default: the scene's "
                              "[operation] crank_speed).")
@click.option("--speeds", help="Instead: the smallest safety factor against crank speed over "
                               "a range, e.g. '300:3000 rev/min'.")
@click.option("--count", default=20, show_default=True, type=click.IntRange(2, 10000),
              help="Speeds over the --speeds range.")
@click.option("--hours", type=float, default=None,
              help="Required life [h]: safety factors against the strength at that life "
                   "[default: against the endurance limit].")
@click.option("--reliability", type=float, default=0.99, show_default=True,
              help="Reliability of the S-N line (Marin factor ke), in (0, 1).")
@click.option("--surface", type=EnumChoice(Surface), default=Surface.MACHINED.value,
              show_default=True, help="Surface finish of the metal links (Marin factor ka).")
@click.option("--temperature", type=float, default=20.0, show_default=True,
              help="Operating temperature [C] (Marin factor kd).")
@click.option("--mean-stress", type=EnumChoice(MeanStress), default=MeanStress.GOODMAN.value,
              show_default=True, help="Mean-stress correction.")
@click.option("-n", "--modes", "n_modes", default=14, show_default=True,
              type=click.IntRange(1, 50),
              help="Static modes per pose behind the reduced basis (stress needs more than "
                   "the frequencies: docs/life.md).")
@click.option("--damping-ratio", default=None, type=float,
              help="Modal damping ratio in [0, 1) for every basis vector [default: the scene's "
                   "[damping] table, else the loss factors its materials write, else 0.01].")
@click.option("--elements", type=click.IntRange(1, 10000), default=None,
              help="Elements per link [default: the scene's mesh].")
@click.option("--estimate/--no-estimate", default=True, show_default=True,
              help="Estimate the peak stress's error by refining the mesh and the basis once.")
@json_option
@out_option
@names_scene("scene_path")
def command(scene_path, speed, speeds, count, hours, reliability, surface, temperature,
            mean_stress, n_modes, damping_ratio, elements, estimate, as_json, out_dir):
    """Stress at both fibres of every element end over one crank turn at a speed, and each
    link's peak stress, range, mean, safety factor and life (worst link first). Writes
    life.json, life.csv (the full field), life.pvd (a ParaView series over the crank angle),
    life_haigh.png (where a link is metal) and life_stress.png to OUT/<scene>/; with --speeds, life_speeds.json and
    .png."""

    from flexlink.output.life import life as render
    from flexlink.studies.life.convergence import peak_error
    from flexlink.studies.life.life import (Conditions, check_strengths, life_study,
                                           safety_sweep)
    from flexlink.studies.life.stress_field import stress_field, stress_model
    from ._progress import progress_bar
    from ._speeds import operating_speed, speed_or_sweep
    from ._written import folder_and_scene, publish

    conditions = Conditions(surface=surface, temperature=temperature, reliability=reliability,
                            mean_stress=mean_stress, hours=hours)
    one, sweep = speed_or_sweep(speed, speeds, count)
    folder, scene = folder_and_scene(out_dir, scene_path)
    check_strengths(scene)
    model = stress_model(scene, n_modes, damping_ratio=damping_ratio,
                         elements_per_link=elements)
    if sweep is not None:
        result = safety_sweep(scene, model, sweep[sweep > 0], conditions,
                              progress=progress_bar("speeds", as_json))
        document = render.margin_document(scene, result)
        path = folder / "life_speeds.png"
        render.plot_margin_sweep(result, path, scene.name)
        publish(folder / "life_speeds.json", document, [path],
                "\n".join(render.margin_lines(document)), as_json)
        return
    field = stress_field(model, operating_speed(scene, one)[0])
    study = life_study(scene, model, field, conditions)
    error = (peak_error(scene, field, model.elements[0], n_modes, damping_ratio=damping_ratio)
             if estimate else None)
    document = render.life_document(scene, study, model, error)
    publish(folder / "life.json", document, render.write_life(folder, scene, study, model),
            "\n".join(render.life_lines(document)), as_json)
