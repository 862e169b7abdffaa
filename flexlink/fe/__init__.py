"""Finite elements: sections and the frame model (``model``), the beam element (``link``),
assembly and exact constraints (``assembly``, ``rigid``), energies, Craig-Bampton reduction and
mode-shape sampling. Imports nothing from scene, analysis, studies or output."""
