"""The same scene under the other value of a two-way modelling choice, for the one-line notes
beside a result: the strip orientation (``section.bending``) and, for Timoshenko links of a
composite, the source of the shear modulus (``material.composite.shear_modulus``)."""

from __future__ import annotations

import dataclasses

import numpy as np

from flexlink.analysis.families import elastic_modes
from flexlink.fe.beams import BeamTheory
from flexlink.materials.mixtures import ShearSource
from flexlink.scene import Scene, load_scene
from flexlink.studies.array_shapes import check_shape
from flexlink.units import percent_error

OTHER_BENDING = {"flatwise": "edgewise", "edgewise": "flatwise"}
OTHER_SHEAR = {ShearSource.PRINTED: ShearSource.ISOTROPIC,
               ShearSource.ISOTROPIC: ShearSource.PRINTED}


def _mean_abs_errors(scene: Scene, computed) -> dict[str, float]:
    columns = scene.reference.columns if scene.reference else {}
    out = {}
    for name, values in columns.items():
        pairs = [(c, r) for c, r in zip(computed, values)]
        if pairs:
            out[name] = float(sum(abs(percent_error(c, r)) for c, r in pairs) / len(pairs))
    return out


@dataclasses.dataclass(frozen=True)
class Alternative:
    """The scene with ``field`` set to ``value``: its lowest elastic frequencies [Hz] (NaN
    where fewer were found), their mean |error| [%] per reference column, and for a choice the
    scene made itself the value it ``used``."""

    field: str
    value: str
    frequencies: np.ndarray
    mean_abs_error_pct: dict[str, float]
    used: str | None = None

    def __post_init__(self):
        check_shape("Alternative", "frequencies", self.frequencies, (None,))


def _alternative(scene: Scene, field: str, value: str, n_modes: int, elements: int | None,
                 overrides: dict | None) -> Alternative:
    other = load_scene(scene.path, overrides={**(overrides or {}), field: value})
    computed = elastic_modes(other, n_modes, elements)[0]
    return Alternative(field, value, np.asarray(computed, dtype=float),
                       _mean_abs_errors(other, computed))


def bending_of(scene: Scene) -> str | None:
    """The orientation the scene's strips lie in, if it says (shared [section] bending)."""
    names = {link.section.bending for link in scene.links}
    return names.pop() if len(names) == 1 and scene.has_field("section.bending") else None


def other_orientation(scene: Scene, n_modes: int, elements: int | None,
                      overrides: dict | None = None) -> Alternative | None:
    """Frequencies [Hz] and mean |error| [%] with the strips turned the other way, or None
    when the scene does not set the orientation. ``overrides``: those ``scene`` was loaded
    with (a Scene does not keep them)."""
    bending = bending_of(scene)
    if bending is None:
        return None
    return _alternative(scene, "section.bending", OTHER_BENDING[bending], n_modes, elements,
                        overrides)


def other_shear_source(scene: Scene, n_modes: int, elements: int | None,
                       overrides: dict | None = None) -> Alternative | None:
    """For Timoshenko links of a composite: the frequencies with the other shear modulus
    source (printed Table I G, or E / 2 (1 + nu) of each constituent); None otherwise."""
    if scene.composite is None or all(l.section.beam is not BeamTheory.TIMOSHENKO for l in scene.links):
        return None
    used = scene.composite.shear_modulus
    out = _alternative(scene, "material.composite.shear_modulus", OTHER_SHEAR[used], n_modes,
                       elements, overrides)
    return dataclasses.replace(out, used=used)


def timoshenko_alternative(scene: Scene, n_modes: int, elements: int | None,
                           overrides: dict | None = None) -> Alternative | None:
    """The scene's frequencies with Timoshenko links (shear and rotary inertia), for scenes
    built with Euler-Bernoulli links; None otherwise. The computed difference a
    slenderness warning points to."""
    if all(link.section.beam is BeamTheory.TIMOSHENKO for link in scene.links):
        return None
    return _alternative(scene, "model.beam", "timoshenko", n_modes, elements, overrides)
