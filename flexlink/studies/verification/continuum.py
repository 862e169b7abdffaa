"""A plane-stress continuum reference for one link, against the two beam theories.

The link is a strip of length L [m] and in-plane depth h [m], meshed with quadratic
quadrilaterals (scikit-fem ``ElementQuad2``, plane stress, Ex = Ey = E, shear modulus G,
Poisson's ratio nu). Its ends are simply supported the way a beam's pinned ends are: the
transverse displacement uy is zero over both end faces (they stay free to turn and to warp),
and ux is held at the mid-depth point of the left end only (removing the axial rigid motion).
For that support the exact 2D fields are sin / cos in x, the continuum's counterpart of
the pinned-pinned beam, so the first flexural frequency compares one to one with
``fe.beams.pinned_bending_frequencies`` of the same strip, pinned at both ends.

A flexural mode is picked out by its symmetry about the mid-depth line (uy even, ux odd in y)
and by the shape of uy along that line (one half sine); thickness-shear modes, which in a
strip soft in shear can lie below it, are skipped.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.sparse.linalg as spla

from flexlink.fe.beams import euler_bernoulli_pinned, timoshenko_pinned
from flexlink.fe.model import Section

BENDING_SHAPE = 0.9  # least correlation of the mid-line uy with sin(pi x / L) for mode 1


def _plane_stress_matrices(length, depth, E, G, nu, density, nx, ny):
    from skfem import Basis, BilinearForm, ElementQuad2, ElementVector, MeshQuad
    from skfem.helpers import dot, sym_grad

    c = E / (1.0 - nu * nu)

    @BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        sxx = c * (eu[0, 0] + nu * eu[1, 1])
        syy = c * (nu * eu[0, 0] + eu[1, 1])
        sxy = 2.0 * G * eu[0, 1]
        return sxx * ev[0, 0] + syy * ev[1, 1] + 2.0 * sxy * ev[0, 1]

    @BilinearForm
    def mass(u, v, w):
        return density * dot(u, v)

    mesh = MeshQuad.init_tensor(np.linspace(0.0, length, nx + 1), np.linspace(0.0, depth, ny + 1))
    basis = Basis(mesh, ElementVector(ElementQuad2()), intorder=4)
    return basis, stiffness.assemble(basis), mass.assemble(basis)


@dataclasses.dataclass(frozen=True)
class ContinuumMode:
    """First flexural frequency [Hz] of the strip and the mesh it was computed on."""

    frequency: float
    nx: int
    ny: int
    dofs: int


def plane_stress_first_bending(length: float, depth: float, E: float, G: float, nu: float,
                               density: float, nx: int, ny: int, n_search: int = 12) -> ContinuumMode:
    """First flexural frequency [Hz] of a simply supported plane-stress strip (module
    docstring), on an nx x ny mesh of quadratic quadrilaterals; ny must be even (the ux hold
    sits on the mid-depth node)."""
    if ny % 2:
        raise ValueError(f"ny must be even, got {ny}")
    basis, K, M = _plane_stress_matrices(length, depth, E, G, nu, density, nx, ny)
    x, y = basis.doflocs
    comp = np.empty(basis.N, dtype=int)  # 0: ux, 1: uy (dofs interleave by component)
    for dofs in (basis.nodal_dofs, basis.facet_dofs, basis.interior_dofs):
        if dofs.size:
            comp[dofs] = np.arange(dofs.shape[0])[:, None] % 2
    tol = 1e-9 * length
    ends = (np.abs(x) < tol) | (np.abs(x - length) < tol)
    fixed = (ends & (comp == 1)) | ((np.abs(x) < tol) & (np.abs(y - depth / 2) < tol * depth / length + 1e-12) & (comp == 0))
    free = np.flatnonzero(~fixed)
    Kf, Mf = K[free][:, free].tocsc(), M[free][:, free].tocsc()
    scale = euler_bernoulli_pinned(Section(E, G, density, depth, depth**3 / 12, depth), length)
    lam, vec = spla.eigsh(Kf, n_search, Mf, sigma=-(0.01 * 2 * math.pi * scale) ** 2, which="LM")
    order = np.argsort(lam)
    lam, vec = lam[order], vec[:, order]
    full = np.zeros((basis.N, len(lam)))
    full[free] = vec
    key = np.round(np.c_[x / tol, y / tol, comp]).astype(np.int64)
    mirror_key = np.round(np.c_[x / tol, (depth - y) / tol, comp]).astype(np.int64)
    index = {tuple(k): i for i, k in enumerate(key)}
    mirror = np.array([index[tuple(k)] for k in mirror_key])
    sign = np.where(comp == 1, 1.0, -1.0)  # flexural: uy even, ux odd about mid-depth
    line = np.flatnonzero((np.abs(y - depth / 2) < 1e-9 * depth) & (comp == 1))
    half_sine = np.sin(math.pi * x[line] / length)
    for k in range(len(lam)):
        u = full[:, k]
        symmetric = u @ (sign * u[mirror]) > 0.5 * (u @ u)
        mid = u[line]
        shape = abs(mid @ half_sine) / (np.linalg.norm(mid) * np.linalg.norm(half_sine) + 1e-300)
        if symmetric and shape > BENDING_SHAPE:
            return ContinuumMode(math.sqrt(lam[k]) / (2 * math.pi), nx, ny, basis.N)
    raise RuntimeError(f"no flexural mode among the lowest {n_search} of the strip "
                       f"(L = {length} m, h = {depth} m)")


@dataclasses.dataclass(frozen=True)
class Row:
    """One strip: slenderness L/h, first flexural frequency [Hz] of the continuum on two
    meshes (coarse, fine) and of the two beam theories (closed forms, pinned-pinned)."""

    slenderness: float
    continuum_coarse: float
    continuum: float
    timoshenko: float
    euler_bernoulli: float

    @property
    def mesh_change(self) -> float:
        return abs(self.continuum_coarse / self.continuum - 1.0)

    def error(self, beam: str) -> float:
        """Relative error of a beam theory against the (fine) continuum."""
        return getattr(self, beam.replace("-", "_")) / self.continuum - 1.0


def compare(E: float, G: float, nu: float, density: float, slenderness, depth: float = 0.01,
            per_depth: int = 4, depth_elements: int = 4) -> list[Row]:
    """The continuum against both beam theories for each L/h in ``slenderness``; the coarse
    mesh has ``per_depth`` elements per depth along the strip and ``depth_elements`` across
    it, the fine mesh twice both."""
    rows = []
    for ratio in slenderness:
        L = ratio * depth
        section = Section(E, G, density, depth, depth**3 / 12.0, depth, beam="timoshenko")
        nx = max(4, int(round(per_depth * ratio)))
        coarse = plane_stress_first_bending(L, depth, E, G, nu, density, nx, depth_elements)
        fine = plane_stress_first_bending(L, depth, E, G, nu, density, 2 * nx, 2 * depth_elements)
        rows.append(Row(ratio, coarse.frequency, fine.frequency, timoshenko_pinned(section, L),
                        euler_bernoulli_pinned(section, L)))
    return rows
