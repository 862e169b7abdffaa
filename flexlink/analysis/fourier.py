"""Fourier series of periodic functions sampled over one turn: the one representation the
stability map's interpolation and the harmonic balance share, and the one evaluator of it
(numpy only, so the map does not load what the harmonic balance's solver needs)."""

from __future__ import annotations

import numpy as np


def fourier_coefficients(samples: np.ndarray) -> np.ndarray:
    """c_d, d = 0..P ((P + 1, ...) complex) of the trigonometric polynomial through samples
    (N, ...) at N = 2P + 1 equal steps from angle 0."""
    N = samples.shape[0]
    if N % 2 == 0:
        raise ValueError(f"an odd count of samples is needed, got {N}")
    return np.fft.rfft(samples, axis=0) / N


def fourier_values(coefficients: np.ndarray, theta, derivative: int = 0) -> np.ndarray:
    """The real function sum_{|d| <= P} c_d exp(i d theta) (c_-d = conj c_d), or its
    ``derivative``-th derivative in theta [per rad^derivative], at angles theta (m,) [rad]
    from coefficients c_d, d = 0..P ((P + 1, ...)): (m, ...), as the real cosine-sine sum
    2 Re(c_d) cos d theta - 2 Im(c_d) sin d theta (c_0 once)."""
    c = np.asarray(coefficients)
    theta = np.asarray(theta, dtype=float)
    k = np.arange(c.shape[0])
    weights = np.full(c.shape[0], 2.0)
    weights[0] = 1.0
    # d^j/dtheta^j of exp(i k theta) is (i k)^j exp(i k theta): fold (i k)^j into c
    flat = (weights * (1j * k) ** derivative)[:, None] * c.reshape(c.shape[0], -1)
    angle = np.multiply.outer(theta, k).reshape(-1, len(k))
    values = np.cos(angle) @ flat.real - np.sin(angle) @ flat.imag
    return values.reshape(theta.shape + c.shape[1:])


def fourier_series(samples: np.ndarray, theta, derivative: int = 0) -> np.ndarray:
    """Trigonometric interpolation over one turn of samples (N, ...) taken at N equal steps
    from angle 0 (N odd, so every harmonic has its pair and the interpolant is real), at
    angles theta (m,) [rad]; ``derivative``: 0 for the interpolant, 1 for its exact
    derivative in theta [per rad]."""
    return fourier_values(fourier_coefficients(samples), theta, derivative)
