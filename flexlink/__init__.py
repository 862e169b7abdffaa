"""flexlink: finite-element modal analysis of planar linkages with flexible beam links.

Stages, one module each, plain data between them:
materials -> kinematics -> model -> assembly -> solve -> report / export.
"""

from .errors import FlexlinkError, InputError, KinematicsError, NumericalError, OutputError
from .kinematics import FourBar, Pose
from .materials import load_constituent, rule_of_mixtures, woven_composite
from .model import FrameModel, JointSpec, LinkSpec, Section, Topology, build_model
from .assembly import assemble, reduction
from .solve import ModalResult, solve_modes
from .scene import Scene, load_scene
from .analysis import CaseResult, analyze

__all__ = [
    "FlexlinkError", "InputError", "KinematicsError", "NumericalError", "OutputError",
    "FourBar", "Pose", "load_constituent", "rule_of_mixtures", "woven_composite",
    "FrameModel", "JointSpec", "LinkSpec", "Section", "Topology", "build_model",
    "assemble", "reduction", "ModalResult", "solve_modes", "Scene", "load_scene",
    "CaseResult", "analyze",
]
