"""Studies built on the analysis: the crank cycle, convergence, stability, calibration against a
reference table (the fitting machinery and the whole calibration study), uncertainty and
sensitivities, and the pseudo-rigid-body check."""
