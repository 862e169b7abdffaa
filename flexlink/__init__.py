"""flexlink: finite-element modal analysis of planar linkages with flexible beam links.

Stages, one module each, plain data between them:
materials -> kinematics -> model -> assembly -> solve -> report / export.

The public names below are imported on first use, so ``import flexlink`` (and ``flexlink
--help``) does not load scipy or scikit-fem until a stage is needed.
"""

import importlib

from .errors import FlexlinkError, InputError, KinematicsError, NumericalError, OutputError

_EXPORTS = {
    "FourBar": "kinematics", "Pose": "kinematics",
    "load_constituent": "materials", "rule_of_mixtures": "materials",
    "woven_composite": "materials",
    "FrameModel": "model", "JointSpec": "model", "LinkSpec": "model", "Section": "model",
    "Topology": "model", "build_model": "model",
    "assemble": "assembly", "reduction": "assembly",
    "ModalResult": "solve", "solve_modes": "solve",
    "Scene": "scene", "load_scene": "scene",
    "CaseResult": "analysis", "analyze": "analysis",
    "modal_sweep": "sweep",
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
