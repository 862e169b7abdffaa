"""The kinetostatics options of the command line (``flexlink outputs``) as scene overrides
of its [kinetostatics] table, each value checked and refused naming its option."""

from __future__ import annotations

from flexlink.errors import InputError
from flexlink.units import parse_quantity

WHERE = "command line"


def kinetostatics_overrides(input_torque, torque_csv, unit, outputs, sharing, share, friction,
                            efficiency) -> dict:
    """{scene field: value} for the options given (None or empty: the scene's own): the input
    torque (a constant, or a CSV over the crank angle in ``unit``), the output bodies, how they
    share the input, the first output's friction m in [0, 1) and the bearing efficiency eta in
    (0, 1]."""
    if friction is not None and not 0.0 <= friction < 1.0:
        raise InputError(f"got {friction!r}", source=WHERE, field="--friction",
                         expected="m in [0, 1)")
    if efficiency is not None and not 0.0 < efficiency <= 1.0:
        raise InputError(f"got {efficiency!r}", source=WHERE, field="--efficiency",
                         expected="eta in (0, 1]")
    if share is not None and not 0.0 <= share <= 1.0:
        raise InputError(f"got {share!r}", source=WHERE, field="--share", expected="[0, 1]")
    overrides = {}
    if input_torque is not None and torque_csv is not None:
        raise InputError("give --input-torque or --input-torque-csv, not both", source=WHERE,
                         field="--input-torque-csv")
    if torque_csv is not None:
        from pathlib import Path

        parse_quantity(f"1 {unit}", "torque", source=WHERE, field="--unit")
        overrides.update({"kinetostatics.input_torque": None, "kinetostatics.unit": unit,
                          "kinetostatics.csv": str(Path(torque_csv).resolve())})
    if input_torque is not None:
        parse_quantity(input_torque, "torque", source=WHERE, field="--input-torque")
        overrides.update({"kinetostatics.input_torque": input_torque, "kinetostatics.csv": None,
                          "kinetostatics.unit": None})
    for key, value in (("outputs", list(outputs) or None), ("friction", friction),
                       ("efficiency", efficiency), ("share", share),
                       ("sharing", sharing.value if sharing else None)):
        if value is not None:
            overrides[f"kinetostatics.{key}"] = value
    return overrides
