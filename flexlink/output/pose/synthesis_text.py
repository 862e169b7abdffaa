"""The line a scene made by a synthesis method prints above its results: the method, its
inputs, and the lengths it gave [mm]."""

from __future__ import annotations


def synthesis_line(synthesis: dict, inputs: bool = True) -> str:
    """``synthesis``: the scene's synthesis record (method, inputs, lengths_m [m]); with
    ``inputs`` the method's inputs follow its name."""
    head = f"synthesis {synthesis['method']}" + (f" {synthesis['inputs']}" if inputs else "")
    return head + ": " + ", ".join(f"{k} {1e3 * v:.3f} mm"
                                   for k, v in synthesis["lengths_m"].items())
