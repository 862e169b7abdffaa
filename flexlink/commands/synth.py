"""``flexlink synth minimax|brodell-soni``: crank-rocker proportions from design targets."""

from __future__ import annotations

import click

from flexlink.commands._options import dumps, json_option


def _quantity(text: str, kind: str, field: str) -> float:
    from flexlink.units import parse_quantity

    return parse_quantity(text, kind, source="command line", field=field)


def _report(method: str, inputs: dict[str, str], first: float, second: float, ground: float,
            as_json: bool) -> None:
    from flexlink.output.pose.crank_rocker import crank_rocker_document, crank_rocker_text
    from flexlink.studies.pose.crank_rocker import crank_rocker

    document = crank_rocker_document(crank_rocker(method, inputs, first, second, ground))
    click.echo(dumps(document) if as_json else crank_rocker_text(document))


@click.group("synth")
def command():
    """Crank-rocker synthesis: mini-max transmission angle, or Brodell-Soni unit time ratio."""


@command.command("minimax")
@click.argument("theta4i")
@click.argument("delta")
@click.option("--ground", default="1 m", show_default=True, help="Ground link L1.")
@json_option
def minimax_command(theta4i, delta, ground, as_json):
    """From the rocker angle THETA4I at mu_min and the band mu = 90 +- DELTA (e.g. '100 deg'
    '20 deg'): mu_min + mu_max = 180 deg."""
    _report("minimax", {"theta4i": theta4i, "delta": delta, "ground": ground},
            _quantity(theta4i, "angle", "THETA4I"), _quantity(delta, "angle", "DELTA"),
            _quantity(ground, "length", "--ground"), as_json)


@command.command("brodell-soni")
@click.argument("gamma_min")
@click.argument("swing")
@click.option("--ground", default="1 m", show_default=True, help="Ground link a1.")
@json_option
def brodell_soni_command(gamma_min, swing, ground, as_json):
    """Unit time ratio, minimum transmission angle GAMMA_MIN, rocker swing SWING (e.g.
    '60 deg' '30 deg')."""
    _report("brodell-soni", {"gamma_min": gamma_min, "swing": swing, "ground": ground},
            _quantity(gamma_min, "angle", "GAMMA_MIN"), _quantity(swing, "angle", "SWING"),
            _quantity(ground, "length", "--ground"), as_json)
