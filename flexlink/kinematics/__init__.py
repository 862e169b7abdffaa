"""Rigid kinematics: the four-bar in closed form (``fourbar``), any planar linkage of revolute
joints as data (``linkage``), synthesis (``synthesis``) and what a cycle amounts to
(``motion``). numpy only: importing this package loads neither scipy nor scikit-fem."""

from flexlink.kinematics.fourbar import Branch, FourBar, FourBarPose, GrashofClass
from flexlink.kinematics.linkage import Body, Cycle, Linkage, State, crank_angles

__all__ = ["Body", "Branch", "Cycle", "FourBar", "FourBarPose", "GrashofClass", "Linkage", "State",
           "crank_angles"]
