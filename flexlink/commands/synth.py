"""``flexlink synth minimax|brodell-soni``: crank-rocker proportions from design targets."""

from __future__ import annotations

import math

import click

from flexlink.commands._options import dumps, json_option


def _report(fb, method, inputs, as_json):
    mu_min, mu_max = fb.transmission_limits()
    doc = {"command": "synth", "method": method, "inputs": inputs,
           "lengths_m": dict(zip(("ground", "crank", "coupler", "rocker"), fb.lengths)),
           "ratios": dict(zip(("R2", "R3", "R4"), fb.ratios)),
           "mu_min_deg": math.degrees(mu_min), "mu_max_deg": math.degrees(mu_max),
           "rocker_swing_deg": math.degrees(fb.rocker_swing())}
    if as_json:
        click.echo(dumps(doc))
        return
    click.echo(f"{method} {inputs}")
    click.echo("  lengths: " + ", ".join(f"{k} {v:.6g} m" for k, v in doc["lengths_m"].items()))
    click.echo("  R2 = {R2:.4f}, R3 = {R3:.4f}, R4 = {R4:.4f}".format(**doc["ratios"]))
    click.echo(f"  transmission angle {doc['mu_min_deg']:.3f} .. {doc['mu_max_deg']:.3f} deg, "
               f"rocker swing {doc['rocker_swing_deg']:.3f} deg")


def _angle(text, name):
    from flexlink.units import parse_quantity
    return parse_quantity(text, "angle", source="command line", field=name)


def _length(text, name):
    from flexlink.units import parse_quantity
    return parse_quantity(text, "length", source="command line", field=name)


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
    from flexlink.kinematics.synthesis import minimax

    fb = minimax(_angle(theta4i, "THETA4I"), _angle(delta, "DELTA"), _length(ground, "--ground"))
    _report(fb, "minimax", {"theta4i": theta4i, "delta": delta, "ground": ground}, as_json)


@command.command("brodell-soni")
@click.argument("gamma_min")
@click.argument("swing")
@click.option("--ground", default="1 m", show_default=True, help="Ground link a1.")
@json_option
def brodell_soni_command(gamma_min, swing, ground, as_json):
    """Unit time ratio, minimum transmission angle GAMMA_MIN, rocker swing SWING (e.g.
    '60 deg' '30 deg')."""
    from flexlink.kinematics.synthesis import brodell_soni

    fb = brodell_soni(_angle(gamma_min, "GAMMA_MIN"), _angle(swing, "SWING"),
                      _length(ground, "--ground"))
    _report(fb, "brodell-soni", {"gamma_min": gamma_min, "swing": swing, "ground": ground}, as_json)
