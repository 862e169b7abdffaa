"""Scene files: the declared schema (``schema``), reading with base files, overrides and notes
(``source``), the one scene contract every command uses (``contract``), built per scene kind
(``fourbar``, ``general``) by ``load_scene``."""

from flexlink.scene.contract import Reference, RigidPose, Scene
from flexlink.scene.load import load_scene, scene_files
from flexlink.scene.source import Assumption

__all__ = ["Assumption", "Reference", "RigidPose", "Scene", "load_scene", "scene_files"]
