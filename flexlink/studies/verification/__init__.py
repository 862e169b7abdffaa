"""Verification of the model itself: numerical self-checks, mesh convergence and the continuum reference."""
