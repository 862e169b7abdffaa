"""Fourier coefficients of periodic functions sampled over one turn: the one representation
the stability map's interpolation and the harmonic balance share (numpy only, so the map does
not load what the harmonic balance's solver needs)."""

from __future__ import annotations

import numpy as np


def fourier_coefficients(samples: np.ndarray) -> np.ndarray:
    """c_d, d = 0..P ((P + 1, ...) complex) of the trigonometric polynomial through samples
    (N, ...) at N = 2P + 1 equal steps from angle 0."""
    N = samples.shape[0]
    if N % 2 == 0:
        raise ValueError(f"an odd count of samples is needed, got {N}")
    return np.fft.rfft(samples, axis=0) / N
