"""Which small motions a model of a linkage lying in one plane holds.

A ``Part`` is one set of motions with its own formulation (``formulation.FORMULATIONS``): the
in-plane frame motions (ux, uy, rz) or the out-of-plane strip motions (w, rx, ry). A
``ModelFamily`` is what a scene asks for in ``[model] family``: one part, or both (their
motions decouple to first order for doubly symmetric sections, so "3d" is the two parts'
spectra together).
"""

from __future__ import annotations

import enum


class Part(enum.StrEnum):
    IN_PLANE = "in-plane"
    OUT_OF_PLANE = "out-of-plane"


class ModelFamily(enum.StrEnum):
    PLANAR = "planar"
    OUT_OF_PLANE = "out-of-plane"
    THREE_D = "3d"

    @property
    def parts(self) -> tuple[Part, ...]:
        """The parts whose modes make up this family's spectrum."""
        return {ModelFamily.PLANAR: (Part.IN_PLANE,),
                ModelFamily.OUT_OF_PLANE: (Part.OUT_OF_PLANE,),
                ModelFamily.THREE_D: (Part.IN_PLANE, Part.OUT_OF_PLANE)}[self]
