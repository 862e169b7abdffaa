"""Small model builders shared by the tests: single beams with chosen supports."""

import math

import numpy as np

from flexlink.analysis.eigensolver import EigenSolver
from flexlink.fe.model_at_pose import in_plane_eigen_scale
from flexlink.fe.assembly import assemble, rigid_elimination
from flexlink.fe.model import JointSpec, LinkSpec, Section, Topology, build_model
from flexlink.analysis.solve import solve_modes

INF = math.inf
# A slender steel-like strip: L/h = 100, so axial modes lie far above the first bending modes.
LENGTH, WIDTH, THICK = 1.0, 0.01, 0.005
SECTION = Section.rectangle(E=210e9, G=81e9, density=7850.0, width=WIDTH, thickness=THICK)


def beam_scale(section=SECTION, length=LENGTH):
    """sqrt(EI / (rhoA L^4)) [rad/s]: omega_n = (beta_n L)^2 times this."""
    return math.sqrt(section.EI / (section.mass_per_length * length**4))


# beta_n L roots of the Euler-Bernoulli characteristic equations (Blevins, Formulas for Natural
# Frequency): cantilever 1 + cos x cosh x = 0, pinned-pinned sin x = 0, free-free
# 1 - cos x cosh x = 0; omega_n = (beta_n L)^2 beam_scale()
BETA_L = {
    "cantilever": [1.875104068711961, 4.694091132974175, 7.854757438237613, 10.99554073487547],
    "pinned-pinned": [math.pi * n for n in range(1, 5)],
    "free-free": [4.730040744862704, 7.853204624095838, 10.99560783800167, 14.13716549125746],
}

SUPPORTS = {
    # (start joint Kt, Kr), (end joint Kt, Kr); None = free end (no joint springs)
    "cantilever": ((INF, INF), None),
    "pinned-pinned": ((INF, 0.0), (INF, 0.0)),
    "free-free": (None, None),
}


def single_beam(support, elements, angle=0.0, section=SECTION, length=LENGTH):
    ends = SUPPORTS[support]
    joints = tuple(JointSpec(name, ground=spec is not None, Kt=spec[0] if spec else 0.0,
                             Kr=spec[1] if spec else 0.0)
                   for name, spec in zip(("S", "E"), ends))
    topo = Topology(links=(LinkSpec("beam", "S", "E", section, elements),), joints=joints)
    c, s = math.cos(angle), math.sin(angle)
    return build_model(topo, {"S": (0.0, 0.0), "E": (length * c, length * s)})


def modes_of(model, n, method="dense"):
    K, M = assemble(model)
    return solve_modes(K, M, n, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model), solver=EigenSolver(method))


def bending_frequencies(result, n):
    """Elastic frequencies [rad/s] of the bending modes: modes whose shape is mostly transverse."""
    omegas = 2 * np.pi * result.frequencies
    return omegas[np.array([k == "elastic" for k in result.kinds])][:n]


def written_out_equations(model, speed):
    """x' = f(t, x) of a ``steady_response.ForcedModel`` at crank speed ``speed`` [rad/s],
    x = (q, q'), t = 0 at the model's first pose: the reduced equations written out from the
    model's samples (M^-1 C, M^-1 G1, M^-1 K, M^-1 K2 and M^-1 f at the poses), interpolated
    between poses by their Fourier series, independently of the study's own integrator."""
    p = model.periodic
    n, N = len(p.frequencies), len(p.angles)
    damping = p.damping
    k = np.fft.fftfreq(N, 1.0 / N)
    c, g, k0, k2 = (np.linalg.solve(p.mass, a) for a in (
        damping, p.coriolis, p.stiffness, p.speed_stiffness))
    f2, fe = (np.linalg.solve(p.mass, f[..., None])[..., 0]
              for f in (p.inertia_forcing, p.external_forcing))
    # at one speed the equations are linear in the samples: q'' = forcing - [K | D] (q, q'),
    # and the Fourier series of that sum is the sum of the series, so one series of n (2n + 1)
    # entries is summed a call (the integrator calls this tens of thousands of times)
    lhs = np.concatenate([k0 + speed**2 * k2, c + speed * g], axis=2)
    forcing = speed**2 * f2 + fe
    stacked = np.fft.fft(np.concatenate([lhs.reshape(N, -1), forcing], axis=1), axis=0) / N
    cut = 2 * n * n

    def rhs(t, x):
        flat = (np.exp(1j * k * speed * t) @ stacked).real
        return np.concatenate([x[n:], flat[cut:] - flat[:cut].reshape(n, 2 * n) @ x])
    return rhs
