"""Calibration against a reference table and what feeds it: least-squares fitting, sensitivities, Jacobians and uncertainty propagation."""
