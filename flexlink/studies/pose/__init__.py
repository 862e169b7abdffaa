"""Studies of one scene at its pose: the modal summary, modelling alternatives, MAC comparisons, the pseudo-rigid-body check and crank-rocker synthesis."""
