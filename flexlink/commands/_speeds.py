"""Crank speeds on the command line: the options, their one parser and checker, and the one
place a speed given there and the scene's [operation] resolve into the speed a study runs at."""

from __future__ import annotations

import math

import click

from flexlink.errors import InputError
from flexlink.units import parse_quantity, parse_range, rev_per_min

WHERE = "command line"


def speeds_option(help_text: str = "Crank speed range, e.g. '0:3000 rev/min'.",
                  required: bool = True):
    """--speeds LOW:HIGH UNIT, read by ``parse_speeds``."""
    return click.option("--speeds", required=required, help=help_text)


def speed_option(help_text: str):
    """--speed SPEED, read by ``parse_speed``."""
    return click.option("--speed", default=None, metavar="SPEED", help=help_text)


def crank_acceleration_option(help_text: str, name: str = "crank_acceleration"):
    """--crank-acceleration ACCELERATION, read by ``parse_acceleration``."""
    return click.option("--crank-acceleration", name, default=None, metavar="ACCELERATION",
                        help=help_text)


def parse_speed(text: str | None, field: str = "--speed") -> float | None:
    """A crank speed with its unit [rad/s] (None when not given): finite and >= 0."""
    if text is None:
        return None
    speed = parse_quantity(text, "angular speed", source=WHERE, field=field)
    checked_speed(speed, field)
    return speed


def checked_speed(speed: float, field: str = "--speed") -> float:
    """``speed`` [rad/s] if finite and >= 0 (the crank turns counter-clockwise), else
    InputError naming ``field``."""
    if not (math.isfinite(speed) and speed >= 0):
        raise InputError(f"crank speed {rev_per_min(speed):.6g} rev/min ({speed:.6g} rad/s)",
                         source=WHERE, field=field,
                         expected="a finite speed >= 0 (the crank turns counter-clockwise)")
    return float(speed)


def parse_acceleration(text: str | None, field: str = "--crank-acceleration") -> float | None:
    """A crank angular acceleration with its unit [rad/s^2] (None when not given), finite."""
    if text is None:
        return None
    value = parse_quantity(text, "angular acceleration", source=WHERE, field=field)
    if not math.isfinite(value):
        raise InputError(f"got {value!r} rad/s^2", source=WHERE, field=field,
                         expected="a finite angular acceleration")
    return value


def parse_speeds(text: str, field: str = "--speeds") -> tuple[float, float]:
    """"LOW:HIGH UNIT" (or "LOW UNIT:HIGH UNIT") -> (low, high) [rad/s]
    (``units.parse_range``), 0 <= low < high and finite."""
    low, high = parse_range(text, "angular speed", source=WHERE, field=field)
    if not (0 <= low < high and math.isfinite(high)):
        raise InputError(f"speed range {rev_per_min(low):g}:{rev_per_min(high):g} rev/min",
                         source=WHERE, field=field, expected="0 <= low < high, finite")
    return low, high


def speed_or_sweep(speed: str | None, speeds: str | None, count: int):
    """(one crank speed [rad/s] or None, a sweep of ``count`` speeds [rad/s] or None) from
    --speed and --speeds LOW:HIGH, which exclude each other."""
    import numpy as np

    if speed is not None and speeds is not None:
        raise InputError("give --speed or --speeds, not both", source=WHERE, field="--speeds")
    sweep = None if speeds is None else np.linspace(*parse_speeds(speeds), count)
    return parse_speed(speed), sweep


def operating_speed(scene, speed: float | None = None,
                    crank_acceleration: float | None = None) -> tuple[float, float]:
    """(speed [rad/s], crank acceleration [rad/s^2]) from the command line's values (None: not
    given, as ``parse_speed`` and ``parse_acceleration`` read them), else the scene's
    [operation]; a speed given alone runs at constant speed. Refuses a missing speed and an
    acceleration without a speed, naming the option."""
    if speed is None:
        if crank_acceleration is not None and scene.options.crank_speed is None:
            raise InputError("a crank acceleration needs a crank speed: give --speed too (or "
                             "[operation] crank_speed in the scene)", source=WHERE,
                             field="--crank-acceleration")
        if scene.options.crank_speed is None:
            raise InputError("no crank speed: give --speed (e.g. '600 rev/min') or [operation] "
                             "crank_speed in the scene", source=WHERE, field="--speed")
        speed = scene.options.crank_speed
        if crank_acceleration is None:
            crank_acceleration = scene.options.crank_acceleration
    checked_speed(speed)
    acceleration = 0.0 if crank_acceleration is None else float(crank_acceleration)
    if not math.isfinite(acceleration):
        raise InputError(f"got {acceleration!r} rad/s^2", source=WHERE,
                         field="--crank-acceleration", expected="a finite angular acceleration")
    return float(speed), acceleration
