"""The shape check every study result runs on construction (as meshio's ``Mesh`` does), so a
wrong array fails where it is made, with the shape it should have had."""

from __future__ import annotations

import numpy as np


def check_shape(owner: str, name: str, value, shape: tuple) -> None:
    """Raise ValueError naming ``owner.name`` unless ``value`` has ``shape`` (None: any size)."""
    actual = np.shape(value)
    if len(actual) != len(shape) or any(e is not None and a != e for a, e in zip(actual, shape)):
        dims = ", ".join("any" if e is None else str(e) for e in shape)
        expected = f"({dims},)" if len(shape) == 1 else f"({dims})"
        raise ValueError(f"{owner}.{name} has shape {actual}, expected {expected}")
