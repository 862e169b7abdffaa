"""Finite elements: sections and the frame model (``model``), joints as springs (``joints``),
the in-plane and out-of-plane formulations (``formulation``, ``strip``), the beam elements
(``link``, ``timoshenko``, behind ``beams``), assembly and exact constraints (``assembly``,
``rigid``), energies, Craig-Bampton reduction and mode-shape sampling. Imports nothing from scene, analysis, studies or output."""
