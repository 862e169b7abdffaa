"""The steady elastic response of the running linkage: deflection and bending strain over one
revolution at a crank speed, and the peak strain against speed.

The periodic equations of ``analysis.periodic`` (the stability map's: its basis,
``analysis.pose_basis``, co-rotating node coordinates, modal damping) forced by the loads of the
rigid motion: the d'Alembert loads (which scale with Omega^2 at constant crank speed) and the
scene's [[loads]] (independent of speed),

    M(theta) x'' + (C + Omega G1) x' + (K + K_ext + Omega^2 K2) x = Omega^2 f2(theta) + f_ext(theta),

both projected like the matrices at each of the model's poses and interpolated in theta by
their Fourier series. The steady state is found by harmonic balance
(``analysis.harmonic_balance``): the interpolated coefficients are exact trigonometric
polynomials of the crank angle, so the periodic solution's harmonics fall spectrally and their
count does not grow with the stiffest basis frequency (a time integration over the turn needs
steps ~ omega_max / Omega). Whether the steady state exists (every Floquet multiplier inside
the unit circle) is the stability map's verdict at the same speed
(``analysis.periodic.speed_multipliers``).

Outputs at named points (a link and a distance from its start joint; by default each link's
midspan): the bending deflection v(s) - chord (the local transverse displacement less the line
through the link's end nodes, so a link carried bodily by its compliant joints does not count)
and the bending strain at the fibre y = +depth/2, eps = -depth/2 * dpsi/dx (psi the section
rotation: dv/dx for Euler-Bernoulli), both from the element's own shape functions.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.analysis.harmonic_balance import HarmonicSolution, harmonic_balance
from flexlink.analysis.periodic import PeriodicModel, periodic_model, speed_multipliers
from flexlink.errors import InputError, NumericalError
from flexlink.fe.beams import shear_parameter
from flexlink.fe.timoshenko import shape_functions
from flexlink.scene import Scene
from flexlink.studies.array_shapes import check_shape
from flexlink.units import rev_per_min

SAMPLES = 180  # crank angles per revolution of the output (2 deg)
TOLERANCE = 1e-7  # harmonic balance's error estimate, relative to the largest |q| over the turn


class UnstableError(NumericalError):
    """The free motion grows (a Floquet multiplier |mu| >= 1): no steady state exists."""


@dataclasses.dataclass(frozen=True)
class StrainPoint:
    """A point of link ``link`` at ``position`` [m] from its start joint."""

    link: str
    position: float

    @property
    def label(self) -> str:
        return f"{self.link}@{self.position * 1e3:.4g}mm"


@dataclasses.dataclass(frozen=True)
class ForcedModel:
    """The forced periodic equations (``periodic``, with its forcing) and the output rows at
    ``points``, sampled at ``periodic.angles``: deflection, curvature (poses, points, n): [m]
    and [1/m] per modal coordinate; half_depth (points,) [m]."""

    periodic: PeriodicModel
    points: tuple[StrainPoint, ...]
    deflection: np.ndarray
    curvature: np.ndarray
    half_depth: np.ndarray

    def __post_init__(self):
        poses, n = len(self.periodic.angles), len(self.periodic.frequencies)
        if self.periodic.inertia_forcing is None:
            raise ValueError("ForcedModel.periodic carries no forcing")
        for name in ("deflection", "curvature"):
            check_shape("ForcedModel", name, getattr(self, name), (poses, len(self.points), n))
        check_shape("ForcedModel", "half_depth", self.half_depth, (len(self.points),))

    def at(self, samples: np.ndarray, theta) -> np.ndarray:
        """``samples`` (poses, ...) interpolated at crank angles ``theta`` (m,) [rad], as the
        periodic model interpolates its matrices."""
        return self.periodic.at(samples, theta)


# a peak deflection above this share of the link's depth (in the plane) leaves the
# small-deflection theory the model rests on (a beam whose ends cannot draw in would stiffen
# by its own stretching, by about (w / h)^2 of its bending stiffness). Conservative: against
# the geometrically exact time-domain record of Table II case 3, the coupler at 0.95 x depth
# (600 rev/min) leaves every midspan peak within 0.7 %, at 3.8 x depth (1200 rev/min) the
# rocker's departs by 1.7 %, growing with the load (docs/steady-response.md)
SMALL_DEFLECTION = 0.5


def depth_ratio(model: ForcedModel, peak_deflection: np.ndarray) -> np.ndarray:
    """Each point's peak deflection [m] (points,) (or (speeds, points)) over its link's
    depth in the plane [-]: above SMALL_DEFLECTION the linear model no longer holds."""
    return np.asarray(peak_deflection) / (2.0 * model.half_depth)


def midspans(scene: Scene) -> tuple[StrainPoint, ...]:
    """Each beam link's midspan."""
    lengths = _link_lengths(scene)
    return tuple(StrainPoint(name, length / 2.0) for name, length in lengths.items())


def _link_lengths(scene: Scene) -> dict[str, float]:
    points = scene.rigid_state(None).points
    return {link.name: float(np.hypot(*(np.asarray(points[link.end])
                                        - np.asarray(points[link.start]))))
            for link in scene.topology().links}


def check_points(scene: Scene, points, field: str = "points") -> tuple[StrainPoint, ...]:
    """``points`` unchanged if each lies on a beam link of ``scene``, else InputError naming
    ``field``."""
    lengths = _link_lengths(scene)
    for p in points:
        if p.link not in lengths:
            raise InputError(f"no beam link named {p.link!r}", source=scene.path, field=field,
                             expected=" or ".join(map(repr, lengths)))
        if not 0.0 <= p.position <= lengths[p.link]:
            raise InputError(f"{p.position * 1e3:g} mm lies outside link {p.link!r}",
                             source=scene.path, field=field,
                             expected=f"a distance from 0 to {lengths[p.link] * 1e3:g} mm")
    return tuple(points)


def forced_model(scene: Scene, n_modes: int = 6, poses: int = 37,
                 damping_ratio: float | None = None,
                 points: tuple[StrainPoint, ...] | None = None,
                 elements_per_link: int | None = None,
                 basis_size: int | None = None, load_vectors: bool = True) -> ForcedModel:
    """``analysis.periodic.periodic_model`` (its forcing included) with the output rows at
    ``points`` (default: each link's midspan), read off the basis at each of its poses; the
    damping ratio and the basis size as there (None: the scene's declared damping; the checked
    basis). ``load_vectors``: the loads' static answers added to the modal basis (the
    default), so that the basis holds the quasi-static answer at every pose, and the modes
    left out of it add their static share to the dynamic answer."""
    points = check_points(scene, midspans(scene) if points is None else points)
    periodic = periodic_model(scene, n_modes, poses, damping_ratio, elements_per_link,
                              basis_size=basis_size, load_vectors=load_vectors)
    rows = np.stack([_point_rows(model, shapes, points) for model, shapes in
                     zip(periodic.pose_models, periodic.pose_shapes)], axis=1)
    model0 = periodic.pose_models[0]
    half = np.array([_link(model0, p.link).section.depth / 2.0 for p in points])
    return ForcedModel(periodic=periodic, points=points, deflection=rows[0], curvature=rows[1],
                       half_depth=half)


def _link(model, name):
    return next(link for link in model.links if link.name == name)


def _point_rows(model, full: np.ndarray, points) -> np.ndarray:
    """(2, points, n): bending deflection [m] and curvature dpsi/dx [1/m] at each point per
    column of ``full`` (3 N, n), global nodal displacements at this pose."""
    out = np.empty((2, len(points), full.shape[1]))
    for k, point in enumerate(points):
        link = _link(model, point.link)
        h = link.length / link.elements
        c, s = math.cos(link.angle), math.sin(link.angle)
        nodes = link.nodes
        v = -s * full[3 * nodes] + c * full[3 * nodes + 1]  # local transverse, (nodes, n)
        rz = full[3 * nodes + 2]
        e = min(int(point.position / h), link.elements - 1)
        xi = point.position / h - e
        Nv, _, _, dNpsi = shape_functions(np.array([xi]), h, shear_parameter(link.section, h))
        dofs = np.stack([v[e], rz[e], v[e + 1], rz[e + 1]])  # (4, n)
        along = point.position / link.length
        chord = (1.0 - along) * v[0] + along * v[-1]
        out[0, k] = Nv[:, 0] @ dofs - chord
        out[1, k] = dNpsi[:, 0] @ dofs
    return out


@dataclasses.dataclass(frozen=True)
class SteadyResponse:
    """One speed [rad/s]: crank angles (samples,) [rad]; deflection [m] and strain [-]
    (samples, points); largest_modulus [-] of the unforced multipliers."""

    speed: float
    angles: np.ndarray
    deflection: np.ndarray
    strain: np.ndarray
    largest_modulus: float

    def __post_init__(self):
        samples = len(self.angles)
        check_shape("SteadyResponse", "angles", self.angles, (samples,))
        check_shape("SteadyResponse", "deflection", self.deflection, (samples, None))
        check_shape("SteadyResponse", "strain", self.strain, self.deflection.shape)

    @property
    def peak_strain(self) -> np.ndarray:
        """max |strain| over the turn, per point [-]."""
        return np.abs(self.strain).max(axis=0)

    @property
    def peak_deflection(self) -> np.ndarray:
        """max |deflection| over the turn, per point [m]."""
        return np.abs(self.deflection).max(axis=0)


def periodic_solution(model: ForcedModel, speed: float,
                      tolerance: float = TOLERANCE) -> HarmonicSolution:
    """The periodic modal coordinates q(theta - first pose) at crank ``speed`` [rad/s] by
    harmonic balance to ``tolerance`` (its error estimate), whether stable or not."""
    return harmonic_balance(*model.periodic.harmonic_equations(speed), speed, tolerance)


def steady_response(model: ForcedModel, speed: float, samples: int = SAMPLES,
                    tolerance: float = TOLERANCE, on_steps=None) -> SteadyResponse:
    """The steady response at crank ``speed`` [rad/s] > 0 over one revolution at ``samples``
    crank angles. UnstableError where a Floquet multiplier has |mu| >= 1 (the stability
    map's multipliers at this speed, by its own step rule; ``on_steps``: their progress, as
    ``speed_multipliers``)."""
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError(f"crank speed {rev_per_min(speed):.6g} rev/min", field="speed",
                         expected="a positive finite speed")
    stability = speed_multipliers(model.periodic.stability, speed, on_steps=on_steps)
    if stability.largest_modulus >= 1.0:
        rpm = rev_per_min(speed)
        raise UnstableError(f"no steady state at {rpm:.6g} rev/min: largest Floquet multiplier "
                            f"|mu| = {stability.largest_modulus:.6g} >= 1, the free motion "
                            "grows; the unstable speeds around it: flexlink stability-map "
                            f"--speeds '{rpm / 2:.4g}:{2 * rpm:.4g} rev/min'")
    turn = 2.0 * np.pi * np.arange(samples) / samples
    q = periodic_solution(model, speed, tolerance).at(turn)
    angles = model.periodic.angles[0] + turn
    deflection = np.einsum("spn,sn->sp", model.at(model.deflection, angles), q)
    strain = -model.half_depth * np.einsum("spn,sn->sp", model.at(model.curvature, angles), q)
    return SteadyResponse(speed=float(speed), angles=angles, deflection=deflection,
                          strain=strain, largest_modulus=stability.largest_modulus)


@dataclasses.dataclass(frozen=True)
class ResponseSweep:
    """Per speed [rad/s]: peak |strain| [-] and |deflection| [m] per point (speeds, points),
    NaN where unstable; the largest multiplier modulus [-] (NaN at speed 0)."""

    speeds: np.ndarray
    points: tuple[StrainPoint, ...]
    peak_strain: np.ndarray
    peak_deflection: np.ndarray
    largest_modulus: np.ndarray

    def __post_init__(self):
        n, k = len(self.speeds), len(self.points)
        check_shape("ResponseSweep", "speeds", self.speeds, (n,))
        for name in ("peak_strain", "peak_deflection"):
            check_shape("ResponseSweep", name, getattr(self, name), (n, k))
        check_shape("ResponseSweep", "largest_modulus", self.largest_modulus, (n,))

    @property
    def unstable(self) -> np.ndarray:
        return np.isnan(self.peak_strain[:, 0]) & (self.speeds > 0)


def response_sweep(model: ForcedModel, speeds, samples: int = SAMPLES,
                   tolerance: float = TOLERANCE, progress=None,
                   on_steps=None) -> ResponseSweep:
    """Peak strain and deflection over ``speeds`` [rad/s] (speed 0: no inertia loads, the
    static answer to the scene's [[loads]]); unstable speeds are NaN, not refused.
    ``progress`` wraps the speeds (a bar), ``on_steps`` counts the Floquet steps within each
    (``steady_response``)."""
    speeds = np.asarray(speeds, dtype=float)
    k = len(model.points)
    strain, deflection = np.full((len(speeds), k), np.nan), np.full((len(speeds), k), np.nan)
    modulus = np.full(len(speeds), np.nan)
    for i in (progress or iter)(range(len(speeds))):
        if speeds[i] == 0.0:
            strain[i], deflection[i] = _static_peaks(model, samples)
            continue
        try:
            r = steady_response(model, speeds[i], samples, tolerance, on_steps)
        except UnstableError:
            continue
        strain[i], deflection[i], modulus[i] = r.peak_strain, r.peak_deflection, \
            r.largest_modulus
    return ResponseSweep(speeds, model.points, strain, deflection, modulus)


def _static_peaks(model: ForcedModel, samples: int):
    """Peaks at speed 0: K(theta) x = f_ext(theta) over the crank angles (a slow turn)."""
    periodic = model.periodic
    angles = periodic.angles[0] + 2.0 * np.pi * np.arange(samples) / samples
    K = model.at(periodic.stiffness, angles)
    q = np.linalg.solve(K, model.at(periodic.external_forcing, angles)[..., None])[..., 0]
    deflection = np.einsum("spn,sn->sp", model.at(model.deflection, angles), q)
    strain = -model.half_depth * np.einsum("spn,sn->sp", model.at(model.curvature, angles), q)
    return np.abs(strain).max(axis=0), np.abs(deflection).max(axis=0)
