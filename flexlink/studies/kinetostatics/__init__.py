"""Kinetostatics for a given input torque: output torques, ratios, pin forces, dead points, the parametric study and the driving torque of scene families."""
