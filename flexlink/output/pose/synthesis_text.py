"""The line a scene made by a synthesis method prints above its results: the method, its
inputs, and the lengths it gave [mm]."""

from __future__ import annotations


def synthesis_line(synthesis: dict, inputs: bool = True) -> str:
    """``synthesis``: the scene's synthesis record (method, inputs, lengths_m [m]); with
    ``inputs`` the method's inputs follow its name."""
    given = ", ".join(_input(k, v) for k, v in synthesis["inputs"].items())
    head = f"synthesis {synthesis['method']}" + (f" ({given})" if inputs and given else "")
    return head + ": " + ", ".join(f"{k} {1e3 * v:.3f} mm"
                                   for k, v in synthesis["lengths_m"].items())


# the unit a synthesis input's key ends in: (suffix, printed unit, factor from the stored value)
_UNITS = (("_deg", "deg", 1.0), ("_mm", "mm", 1.0), ("_m", "mm", 1e3))


def _input(key: str, value) -> str:
    """One synthesis input as a reader writes it: 'swing 30 deg' for swing_deg = 30.0, 'tip
    100 mm' for tip_m = 0.1, 'coupler ratio 3.5' for coupler_ratio = 3.5."""
    for suffix, unit, factor in _UNITS:
        if key.endswith(suffix) and isinstance(value, int | float):
            return f"{key[:-len(suffix)].replace('_', ' ')} {factor * value:g} {unit}"
    shown = f"{value:g}" if isinstance(value, int | float) else str(value)
    return f"{key.replace('_', ' ')} {shown}"
