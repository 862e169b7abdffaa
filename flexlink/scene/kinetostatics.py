"""The ``[kinetostatics]`` table: the input torque on the driver (constant, or over the crank
angle from a CSV file read as a ``[[loads]]`` CSV is), the output bodies with the input link
that drives each, how they share the input, and the losses. Refused with the file and the
field: an output that is not a body, the driver, or a body not turning about a ground pivot;
an input torque that a ``[[loads]]`` torque contradicts (one on the driver declares the input
twice; one on a loaded output fixes the torque the input torque decides)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexlink.errors import InputError
from flexlink.kinematics import Linkage
from flexlink.kinematics.kinetostatics import Losses, Output, Sharing, Transmission
from flexlink.scene import parts, schema
from flexlink.scene.contract import KinetostaticsSpec, LoadKind, LoadSpec
from flexlink.scene.loads import _one_turn, _rows
from flexlink.scene.source import SceneSource
from flexlink.units import parse_quantity

TABLE = "kinetostatics"


def _feeder(src: SceneSource, linkage: Linkage, body: str,
            pairs: tuple[tuple[str, str], ...]) -> tuple[str, str]:
    """(input link, shared joint) of output ``body``: its partner in a transmission pair, else
    the one body sharing a moving joint with it."""
    own = linkage.body(body)
    named = [a if b == body else b for a, b in pairs if body in (a, b)]
    candidates = named or [b.name for b in linkage.bodies if b.name != body
                           and any(j in own.joints and j not in linkage.ground for j in b.joints)]
    if len(candidates) != 1:
        raise InputError(f"output {body!r} is driven through {candidates or 'no body'}: name its "
                         "input link in linkage.transmission, e.g. [['link', "
                         f"'{body}']]", source=src.file_of(f"{TABLE}.outputs"),
                         field=f"{TABLE}.outputs")
    feeder = linkage.body(candidates[0])
    shared = [j for j in own.joints if j in feeder.joints and j not in linkage.ground]
    if len(shared) != 1:
        raise InputError(f"{feeder.name!r} and {body!r} share no moving joint",
                         source=src.file_of("linkage.transmission"), field="linkage.transmission")
    return feeder.name, shared[0]


def _outputs(src: SceneSource, table: schema.KinetostaticsTable, linkage: Linkage,
             pairs) -> tuple[Output, ...]:
    names = [b.name for b in linkage.bodies]
    field = f"{TABLE}.outputs"
    out = []
    for body in table.outputs:
        if body not in names:
            raise parts.unknown_name(src, field, "output body", body, names)
        pivot = linkage.body(body).joints[0]
        if body == linkage.driver or pivot not in linkage.ground:
            why = "is the driver" if body == linkage.driver else "does not turn about a ground pivot"
            raise InputError(f"output {body!r} {why}", source=src.file_of(field), field=field,
                             expected="a body whose first joint is a ground pivot (a rocker)")
        feeder, feed = _feeder(src, linkage, body, pairs)
        out.append(Output(body, pivot, feed, feeder))
    return tuple(out)


def _input_torque(src: SceneSource, table: schema.KinetostaticsTable, driver: str) -> LoadSpec:
    field = f"{TABLE}.input_torque"
    if table.csv is None:
        return LoadSpec(LoadKind.TORQUE, driver, np.array([[table.input_torque]]), None,
                        field=field)
    file = src.file_of(f"{TABLE}.csv")
    scale = parse_quantity(f"1 {table.unit}", "torque", source=file, field=f"{TABLE}.unit")
    path = Path(file).parent / table.csv
    _, data = _rows(path, f"{TABLE}.csv", 1)
    data = _one_turn(path, f"{TABLE}.csv", data)
    return LoadSpec(LoadKind.TORQUE, driver, data[:, 1:] * scale, np.radians(data[:, 0]),
                    field=f"{TABLE}.csv")


def _contradictions(src: SceneSource, loads: tuple[LoadSpec, ...], driver: str,
                    loaded: set[str]) -> None:
    for load in loads:
        if load.kind is not LoadKind.TORQUE:
            continue
        if load.body == driver:
            raise InputError(f"a torque on the driver {driver!r} contradicts {TABLE}."
                             "input_torque: the input is declared twice",
                             source=src.file_of("loads"), field=load.field,
                             expected="the input torque in one place")
        if load.body in loaded:
            raise InputError(f"a torque on the loaded output {load.body!r} contradicts {TABLE}."
                             "input_torque, which decides that output's torque",
                             source=src.file_of("loads"), field=load.field,
                             expected="no [[loads]] torque on a loaded output")


def build_kinetostatics(src: SceneSource, table: schema.KinetostaticsTable, linkage: Linkage,
                        pairs, loads: tuple[LoadSpec, ...]) -> KinetostaticsSpec:
    """The checked ``[kinetostatics]`` of a scene (see the module doc)."""
    outputs = _outputs(src, table, linkage, pairs)
    shares = ()
    if table.sharing is Sharing.SPLIT:
        if len(outputs) != 2:
            raise InputError(f"'split' shares between two outputs, not {len(outputs)}",
                             source=src.file_of(f"{TABLE}.sharing"), field=f"{TABLE}.sharing",
                             expected="two outputs, or sharing = 'series'")
        shares = (table.share, 1.0 - table.share)
    transmission = Transmission(outputs, table.sharing, shares)
    loaded = {o.body for o, is_loaded in zip(outputs, transmission.loaded()) if is_loaded}
    _contradictions(src, loads, linkage.driver, loaded)
    losses = Losses(table.friction, table.efficiency, source=src.file_of(TABLE))
    return KinetostaticsSpec(_input_torque(src, table, linkage.driver), transmission, losses)
