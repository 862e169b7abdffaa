"""The first step every per-scene command shares: read the scene, pick its mesh, analyse it."""

from __future__ import annotations


def analysed_scene(path, n_modes: int, elements: int | None, tol: float | None, solver):
    """(scene, mesh rule, ``analysis.modal.analyze`` result) of the scene file at ``path``: on
    ``elements`` per link if given, else the scene's pinned mesh, else the mesh rule at ``tol``;
    ``solver``: the eigen solver (``analysis.eigensolver.EigenSolver``)."""
    from flexlink.analysis.mesh import choose_mesh
    from flexlink.analysis.modal import analyze
    from flexlink.scene import load_scene

    scene = load_scene(path)
    mesh = choose_mesh(scene, n_modes, elements, tol)
    return scene, mesh, analyze(scene, n_modes, mesh.elements, solver)
