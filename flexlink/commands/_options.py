"""What every command shares: the JSON style, the ``--json`` and ``--out`` options, the mesh
options and ``--scheduler``."""

from __future__ import annotations

import json
import math

import click


def _json_default(value):
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value)}")


def dumps(document) -> str:
    """The one JSON style of every command (NaN refused: JSON has none)."""
    return json.dumps(document, indent=2, default=_json_default, allow_nan=False)


json_option = click.option("--json", "as_json", is_flag=True,
                           help="Print one machine-readable JSON document on stdout.")
out_option = click.option("--out", "out_dir", default="out", show_default=True,
                          type=click.Path(file_okay=False), help="Folder for result files.")


turn_poses_option = click.option("--poses", default=360, show_default=True,
                                 type=click.IntRange(3, 1000000),
                                 help="Crank angles over one turn.")


class FiniteFloatRange(click.FloatRange):
    """click's FloatRange that also refuses nan and inf (which compare false with any bound,
    so FloatRange lets nan through)."""

    name = "finite float range"

    def convert(self, value, param, ctx):
        number = click.FLOAT.convert(value, param, ctx)
        if not math.isfinite(number):
            self.fail(f"{value!r} is not a number", param, ctx)
        return super().convert(number, param, ctx)


class EnumChoice(click.Choice):
    """click's Choice over the values of an enum ``kind``, giving its member: the edge where a
    command-line choice becomes the enum the stages compare. ``none``: one more word (such as
    "auto"), given as None (the stage then picks)."""

    def __init__(self, kind, none: str | None = None):
        self.kind, self.none = kind, none
        super().__init__(([none] if none else []) + [member.value for member in kind])

    def convert(self, value, param, ctx):
        if isinstance(value, self.kind):
            return value
        text = super().convert(value, param, ctx)
        return None if text == self.none else self.kind(text)


TOLERANCE = FiniteFloatRange(0, 1, min_open=True)  # a relative frequency tolerance, in (0, 1]


def stacked(options):
    """One decorator applying ``options`` (click decorators) in the order listed, so that
    ``--help`` shows them in that order."""
    def decorate(command):
        for option in reversed(options):
            command = option(command)
        return command
    return decorate


def mesh_options(method: bool = True):
    """-e/--elements and --tol (the mesh rule of ``analysis.mesh.choose_mesh``), and with
    ``method`` the eigen solver's --method, given to the command as ``solver`` (an
    ``analysis.eigensolver.EigenSolver``): one wording for every command that solves a scene."""
    options = [
        click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
                     help="Elements per link (default: the scene's mesh.elements_per_link if it "
                          "pins one, else the coarsest mesh meeting --tol)."),
        click.option("--tol", default=None, type=TOLERANCE,
                     help="Relative frequency tolerance of the default mesh: the coarsest of 8, "
                          "16, 32, ... elements/link whose Richardson error estimate meets it "
                          "[default: 1e-6]."),
    ]
    if method:
        from flexlink.analysis.eigensolver import EigenSolver, Method

        options.append(click.option("--method", "solver", type=EnumChoice(Method),
                                    default=Method.AUTO.value, show_default=True,
                                    callback=lambda ctx, param, method: EigenSolver(method),
                                    help="Eigen solver."))

    return stacked(options)


def scheduler_option(runs: str, note: str = ""):
    """--scheduler ADDRESS (None: stay on this machine), for a command whose ``runs`` (e.g. "the
    fits and the Monte Carlo") go to dask.distributed inside ``parallel.use_scheduler``;
    ``note`` ends the help."""
    return click.option(
        "--scheduler", default=None, metavar="ADDRESS",
        help=f"Run {runs} on dask.distributed: 'local' starts a LocalCluster on this machine, "
             "else a scheduler address such as tcp://host:8786 (needs the 'dask' extra; see "
             f"docs/performance.md).{note}")


def map_parallel_options(sorted_map: bool):
    """-j/--jobs and --scheduler of the commands that compute a tracked cycle map (``cycle``,
    ``campbell``): its poses go out in chunks (``tracking.tracked_map``), same result; with
    ``sorted_map`` the help also says where a --sorted map goes."""
    runs = "the tracked map's poses in chunks" + (
        " (a --sorted map: its Craig-Bampton sweep as one task)" if sorted_map else "")
    worth = " Worth it for fine meshes or many poses: starting the workers takes seconds."
    options = (
        click.option("-j", "--jobs", default=1, show_default=True, type=int,
                     help="Worker processes (joblib) for the tracked map's poses; 1: in this "
                          "process, -1: one per core." + worth),
        scheduler_option(runs, worth))

    return stacked(options)


def refuse_unless(option: str, needs: str, present: bool) -> None:
    """InputError when the option whose parameter is ``option`` was given on the command line
    (not left at its default) although what it acts on, ``needs`` (another option, e.g.
    "--speeds"), is not ``present``: an option silently ignored would mislead."""
    from click.core import ParameterSource

    from flexlink.errors import InputError

    source = click.get_current_context().get_parameter_source(option)
    if present or source in (None, ParameterSource.DEFAULT, ParameterSource.DEFAULT_MAP):
        return
    flag = "--" + option.replace("_", "-")
    raise InputError(f"{flag} acts only with {needs}, which is not given", source="command line",
                     field=flag, expected=f"{needs} with {flag}, or no {flag}")


def odd_count(ctx, param, value: int) -> int:
    """Click callback: the option's count must be odd (every harmonic sampled with its pair)."""
    if value % 2 == 0:
        raise click.BadParameter(f"must be odd (every harmonic with its pair), got {value}")
    return value


def deprecated_for(new: str):
    """Click callback of an old spelling kept for a while: when it is given, a note on stderr
    says which option replaces it; its value passes through."""
    def note(ctx, param, value):
        if value is not None:
            click.echo(f"flexlink: {ctx.info_name} {param.opts[0]} is deprecated (it names a "
                       f"model part, not the [model] family): use {new}", err=True)
        return value
    return note


def _damping_ratio(ctx, param, value):
    """Click callback: a damping ratio in [0, 1), refused as flexlink refuses bad input."""
    from flexlink.errors import InputError

    if value is not None and not (math.isfinite(value) and 0.0 <= value < 1.0):
        raise InputError(f"damping ratio {value} is outside [0, 1)", source="command line",
                         field="--damping-ratio", expected="a ratio in [0, 1)")
    return value


def _periodic_poses_option():
    return click.option("--poses", default=37, show_default=True,
                        type=click.IntRange(3, 1001), callback=odd_count,
                        help="Crank angles the periodic matrices are sampled at (odd).")


def periodic_basis_options(command):
    """-n/--modes, --damping-ratio, the mesh options and --poses of the commands on the
    periodic equations at speed (``stability-map``, ``response``): the static modes the basis
    must reproduce, the modal damping in it (None when not given: ``analysis.damping`` picks),
    -e/--tol (``periodic_mesh``) and the crank angles sampled."""
    options = (
        click.option("-n", "--modes", "n_modes", default=6, show_default=True,
                     type=click.IntRange(1, 50), help="Static modes of the basis."),
        click.option("--damping-ratio", default=None, type=float, callback=_damping_ratio,
                     help="Modal damping ratio in [0, 1) for every basis vector [default: the "
                          "scene's [damping] table, else the loss factors its materials "
                          "write, else 0.01]."),
        click.option("-e", "--elements", default=None, type=click.IntRange(1, 100000),
                     help="Elements per link (default: the scene's mesh.elements_per_link if "
                          "it pins one, else the mesh rule with --tol, else each link's own "
                          "mesh, with its error estimate in the output)."),
        click.option("--tol", default=None, type=TOLERANCE,
                     help="Relative frequency tolerance: the coarsest of 8, 16, 32, ... "
                          "elements/link whose Richardson error estimate meets it."),
        _periodic_poses_option())
    return stacked(options)(command)


PERIODIC_MESH_REASON = (
    "the periodic equations keep five dense matrices of the whole frame per sampled pose, so "
    "the default tolerance's mesh (128 elements/link on Table II's cases) would cost about 64 "
    "times the memory and time; the results are read from a basis of the lowest modes, whose "
    "frequency error this estimate bounds; -e or --tol choose the mesh")


def periodic_mesh(scene, n_modes: int, elements: int | None, tol: float | None):
    """(elements per link for the periodic equations, None: each link's own mesh; the
    ``analysis.mesh.MeshRule`` saying why): -e, else the scene's pinned mesh, else the mesh
    rule at ``tol`` when given, else each link's own mesh (``analysis.mesh.fixed_mesh``)."""
    from flexlink.analysis.mesh import choose_mesh, fixed_mesh

    if elements is not None or scene.elements_per_link is not None or tol is not None:
        rule = choose_mesh(scene, n_modes, elements, tol)
        return rule.elements, rule
    counts = {link.elements for link in scene.topology().links}
    return None, fixed_mesh(scene, n_modes, max(counts), PERIODIC_MESH_REASON
                            + ("" if len(counts) == 1 else
                               f"; the links' own meshes differ: {sorted(counts)}"))


harmonics_option = click.option(
    "--harmonics", default=10, show_default=True, type=click.IntRange(1, 10000),
    help="Crank harmonics n = 1 ... this number.")


def parse_point(text: str, field: str = "--at"):
    """"LINK:DISTANCE" (e.g. "coupler:60 mm", the distance from the link's start joint) as a
    ``studies.running.steady_response.StrainPoint``."""
    from flexlink.errors import InputError
    from flexlink.studies.running.steady_response import StrainPoint
    from flexlink.units import parse_quantity

    link, sep, distance = str(text).partition(":")
    if not sep or not link.strip():
        raise InputError(f"{text!r} is not LINK:DISTANCE", source="command line", field=field,
                         expected="e.g. 'coupler:60 mm'")
    return StrainPoint(link.strip(), parse_quantity(distance.strip(), "length",
                                                    source="command line", field=field))
