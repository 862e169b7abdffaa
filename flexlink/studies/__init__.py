"""Studies built on the analysis: the crank cycle, convergence, stability, calibration,
uncertainty, the comparison with a reference table, and the pseudo-rigid-body check."""
