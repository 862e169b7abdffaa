"""flexlink: finite-element modal analysis of planar linkages with flexible beam links.

Stages, one package each, plain data between them (docs/architecture.md):
scene -> kinematics -> fe (model, formulations, assembly) -> analysis (solve, sweeps,
families) -> studies -> output -> commands; errors, units, meshes, fileio at the base.

The public names below are imported on first use, so ``import flexlink`` (and ``flexlink
--help``) does not load scipy or scikit-fem until a stage is needed.
"""

import importlib

from flexlink.errors import FlexlinkError, InputError, KinematicsError, NumericalError, OutputError

_EXPORTS = {
    "FourBar": "kinematics.fourbar", "FourBarPose": "kinematics.fourbar",
    "load_constituent": "materials.mixtures", "rule_of_mixtures": "materials.mixtures",
    "woven_composite": "materials.mixtures",
    "FrameModel": "fe.model", "JointSpec": "fe.model", "LinkSpec": "fe.model",
    "Section": "fe.model", "Topology": "fe.model", "build_model": "fe.model",
    "assemble": "fe.assembly", "rigid_elimination": "fe.assembly",
    "ModalResult": "analysis.solve", "solve_modes": "analysis.solve",
    "EigenSolver": "analysis.eigensolver",
    "Scene": "scene.load", "load_scene": "scene.load",
    "CaseResult": "analysis.modal", "analyze": "analysis.modal",
    "modal_sweep": "analysis.sweep",
}

__all__ = ["FlexlinkError", "InputError", "KinematicsError", "NumericalError", "OutputError",
           *_EXPORTS]


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'flexlink' has no attribute {name!r}")


def __dir__():
    return sorted(__all__)
