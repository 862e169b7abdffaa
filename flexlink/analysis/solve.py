"""The generalized symmetric eigenproblem K v = lambda M v, and checks of its answer.

lambda = omega^2 [rad^2/s^2], f = omega / (2 pi) [Hz]. Shapes are mass-normalised
(v^T M v = 1). Every answer carries its own evidence: per mode the relative residual
||K v - lambda M v|| / ||K v|| and the normwise backward error
||K v - lambda M v|| / ((||K||_1 + |lambda| ||M||_1) ||v||), which a stable solver keeps near
machine precision however ill-conditioned the model (the relative residual grows with
lambda_max / lambda, i.e. with mesh refinement, so it is reported but not used as the test);
and the M-orthogonality error max |V^T M V - I|. Modes whose eigenvalue is below ``zero_tol * lambda_ref`` (and below
the round-off floor 100 eps lambda_max) are rigid-body or mechanism modes; they are labelled as such and must never be paired with a measured frequency.
"""

from __future__ import annotations

import dataclasses
import enum
import logging
import warnings

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from flexlink.analysis.eigensolver import DEFAULT_SOLVER, EigenSolver, Method, lowest_pairs
from flexlink.errors import InputError, NumericalError

log = logging.getLogger(__name__)

DENSE_LIMIT = 4000  # DOFs; largest dense problem a sweep or a convergence study builds
LOST_LIMIT = 10.0  # eps lambda_max / lambda_1 beyond which the lowest mode shapes are lost
SPARE_MODES = 4  # solved beyond the elastic modes asked for, for mechanism modes below them
# The checks on every eigen answer (``check``, and ``stacked.stacked_modes`` for a stack):
BACKWARD_TOL = 1e-10  # normwise backward error of an eigenpair
ORTHOGONALITY_TOL = 1e-6  # max |V^T M V - I|
ZERO_TOL = 1e-6  # modes below ZERO_TOL * lambda_ref are rigid-body/mechanism modes
ROUNDOFF_WARN = 1e-6  # eps lambda_max / lambda_1 above this: warn (the default frequency tol)


class ModeKind(enum.StrEnum):
    """What a mode is: elastic, or a rigid-body/mechanism mode (eigenvalue below the zero
    threshold), which must never be paired with a measured frequency."""

    ELASTIC = "elastic"
    MECHANISM = "rigid-body/mechanism"


ELASTIC, MECHANISM = ModeKind.ELASTIC, ModeKind.MECHANISM


@dataclasses.dataclass(frozen=True)
class ModalResult:
    """Lowest modes of a model. eigenvalues [rad^2/s^2], frequencies [Hz], shapes (n_full, k)."""

    eigenvalues: np.ndarray
    frequencies: np.ndarray
    shapes: np.ndarray
    kinds: tuple[ModeKind, ...]
    residuals: np.ndarray
    backward_errors: np.ndarray
    orthogonality_error: float
    solver: Method  # DENSE or SPARSE, the one that solved it
    n_dofs: int
    refined: bool = False  # eigenvalues are energy Rayleigh quotients (see solve_modes)
    condensed: int = 0  # massless DOFs condensed statically before the eigen solve

    @property
    def elastic(self) -> np.ndarray:
        """Indices of the elastic (non-zero) modes, in ascending frequency."""
        return np.array([i for i, k in enumerate(self.kinds) if k == ELASTIC], dtype=int)

    @property
    def elastic_frequencies(self) -> np.ndarray:
        return self.frequencies[self.elastic]


def _condense_massless(Kr, Mr):
    """Exact static condensation of DOFs with no mass (their rows of M are zero, M being PSD):
    K_c = K_mm - K_ms K_ss^-1 K_sm, and u_s = -K_ss^-1 K_sm u_m. Returns (K_c, M_c, expand) or
    None when every DOF has mass. Dense (K, M) stay dense, sparse ones sparse."""
    massless = Mr.diagonal() <= 0
    if not massless.any():
        return None
    s, m = np.flatnonzero(massless), np.flatnonzero(~massless)
    if m.size == 0:
        raise NumericalError("no DOF has mass: the model has no inertia to vibrate with")
    dense = not sp.issparse(Kr)
    X = (_dense_static(Kr, s, m) if dense else _sparse_static(Kr, s, m))  # K_ss^-1 K_sm (n_s x n_m)
    Ksm = Kr[np.ix_(s, m)] if dense else Kr[s][:, m].toarray()
    if dense:
        Kc = Kr[np.ix_(m, m)] - Ksm.T @ X
        Kc, Mc = (Kc + Kc.T) / 2, Mr[np.ix_(m, m)]
    else:
        Kc = Kr[m][:, m] - sp.csr_matrix(Ksm.T @ X)
        Kc, Mc = ((Kc + Kc.T) / 2).tocsr(), Mr[m][:, m].tocsr()
    # (Kc symmetric to round-off; made exact for the solvers)
    log.info("condensed %d massless DOF(s) statically (exact for zero mass)", s.size)

    def expand(vecs):
        full = np.zeros((Kr.shape[0], vecs.shape[1]))
        full[m], full[s] = vecs, -X @ vecs
        return full

    return Kc, Mc, expand


def _no_energy(s) -> NumericalError:
    return NumericalError(f"{s.size} DOF(s) have neither mass nor stiffness (first: reduced "
                          f"DOF {s[0]}): they are free to move without energy; give the "
                          "joint a mass or a spring")


def _sparse_static(Kr, s, m) -> np.ndarray:
    """K_ss^-1 K_sm, dense (few massless DOFs expected), by sparse LU."""
    try:
        lu = spla.splu(Kr[s][:, s].tocsc())
    except RuntimeError:
        lu = None
    if lu is None or not np.all(np.isfinite(lu.U.diagonal())) or np.any(lu.U.diagonal() == 0):
        raise _no_energy(s)
    return lu.solve(Kr[s][:, m].toarray())


def _dense_static(Kr, s, m) -> np.ndarray:
    """K_ss^-1 K_sm by dense LU; an exactly zero or non-finite pivot means no stiffness."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", la.LinAlgWarning)  # the pivot check below says it
        lu, piv = la.lu_factor(Kr[np.ix_(s, s)])
    pivots = np.diagonal(lu)
    if not np.all(np.isfinite(pivots)) or np.any(pivots == 0):
        raise _no_energy(s)
    return la.lu_solve((lu, piv), Kr[np.ix_(s, m)])


def _norm1(A) -> float:
    """||A||_1, the largest absolute column sum; for CSR straight from its arrays (scipy's
    abs(A).sum(axis=0) builds two temporary matrices, which costs more than a small eigen solve)."""
    if not sp.issparse(A):
        return float(np.abs(A).sum(axis=0).max())
    sums = np.bincount(A.indices, weights=np.abs(A.data), minlength=A.shape[1])
    return float(sums.max()) if sums.size else 0.0


@dataclasses.dataclass(frozen=True)
class Prepared:
    """The eigenproblem as the solver sees it: ``Kr``, ``Mr`` reduced by u = T q (what the
    checks use), ``Ks``, ``Ms`` after condensing massless DOFs (what the solver gets), and
    ``expand`` mapping solver vectors back to reduced ones."""

    Kr: object
    Mr: object
    Ks: object
    Ms: object
    expand: object  # callable (n_s, k) -> (n, k), or None when nothing was condensed

    @property
    def n(self) -> int:
        return self.Kr.shape[0]

    @property
    def n_solved(self) -> int:
        return self.Ks.shape[0]

    @property
    def lambda_max(self) -> float:
        """Lower estimate of the largest eigenvalue [rad^2/s^2]: the largest diagonal ratio."""
        return float((self.Ks.diagonal() / self.Ms.diagonal()).max())


def prepare(K, M, T=None) -> Prepared:
    """Reduce (K, M) by u = T q and condense the massless DOFs (``_condense_massless``).
    Dense (K, M) with T None stay dense: converting small matrices to CSR and back costs more
    than their eigen solve."""
    if T is None and isinstance(K, np.ndarray) and isinstance(M, np.ndarray):
        Kr, Mr = K, M
    else:
        Kr, Mr = (K, M) if T is None else ((T.T @ K @ T).tocsr(), (T.T @ M @ T).tocsr())
        Kr, Mr = sp.csr_matrix(Kr), sp.csr_matrix(Mr)
    if Kr.shape[0] == 0:
        raise NumericalError("the model has no free DOFs: every DOF is constrained")
    condensed = _condense_massless(Kr, Mr)
    if condensed is None:
        return Prepared(Kr, Mr, Kr, Mr, None)
    return Prepared(Kr, Mr, condensed[0], condensed[1], condensed[2])


def roundoff_floor(lambda_max: float) -> float:
    """K's own round-off leaves a rigid-body mode about eps lambda_max above zero [rad^2/s^2]."""
    return 100 * np.finfo(float).eps * lambda_max


def eigen_solve(p: Prepared, k: int, method: Method, lambda_ref: float):
    """The lowest ``k`` eigenpairs of ``p`` by ``method`` (DENSE or SPARSE), vectors
    expanded to the reduced DOFs: (eigenvalues [rad^2/s^2], vectors (n, k))."""
    floor = roundoff_floor(p.lambda_max)
    try:
        vals, vecs = lowest_pairs(method, p.Ks, p.Ms, k, shift=-lambda_ref)
    except NumericalError:
        if floor <= lambda_ref:
            raise
        # On a mesh this fine, K - shift M is singular in floating point unless the shift is at
        # least the round-off floor; retry there (slower to converge, but it factorises), and
        # let the floor check judge what comes out.
        vals, vecs = lowest_pairs(method, p.Ks, p.Ms, k, shift=-floor)
    if p.expand is not None:
        vecs = p.expand(vecs)
    return vals, vecs


def backward_errors(KV, MV, vecs, vals, norm_K, norm_M) -> np.ndarray:
    """Normwise backward error ||K v - lambda M v|| / ((||K|| + |lambda| ||M||) ||v||) of each
    eigenpair: vectors along axis -2 of ``vecs`` (n, k) or a stack (P, n, k), ``KV`` = K vecs,
    ``MV`` = M vecs, ``vals`` (k,) or (P, k); ``norm_K``, ``norm_M``: 1-norms, scalars or (P,)."""
    R = np.linalg.norm(KV - MV * vals[..., None, :], axis=-2)
    scale = np.asarray(norm_K)[..., None] + np.abs(vals) * np.asarray(norm_M)[..., None]
    return R / (scale * np.linalg.norm(vecs, axis=-2))


def not_finite_message() -> str:
    return "eigen solve returned NaN or infinite eigenvalues"


def negative_message(value: float) -> str:
    return (f"negative eigenvalue {value:.6g} rad^2/s^2: K is not positive semi-definite "
            "(check spring and section inputs)")


def orthogonality_message(value: float) -> str:
    return f"eigenvectors lost M-orthogonality: max |V^T M V - I| = {value:.3g}"


@dataclasses.dataclass(frozen=True)
class Evidence:
    """Per mode: relative residual and normwise backward error; max |V^T M V - I|."""

    vectors: np.ndarray  # mass-normalised (n, k)
    residuals: np.ndarray
    backward_errors: np.ndarray
    orthogonality_error: float


def check(p: Prepared, vals, vecs, zero: float, method: Method,
          backward_tol: float = BACKWARD_TOL) -> Evidence:
    """Mass-normalise ``vecs`` and check the answer: NaN, eigenvalues below ``-zero``
    [rad^2/s^2], backward error above ``backward_tol``, lost M-orthogonality (NumericalError)."""
    if not np.all(np.isfinite(vals)):
        raise NumericalError(not_finite_message())
    if vals.min() < -zero:
        raise NumericalError(negative_message(vals.min()))
    # eigh already mass-normalises and ARPACK's vectors are normalised the same way; redo it
    # so the checks below do not rest on either
    vecs = vecs / np.sqrt(np.einsum("ij,ij->j", vecs, p.Mr @ vecs))
    KV, MV = p.Kr @ vecs, p.Mr @ vecs
    R = np.linalg.norm(KV - MV * vals, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        residuals = R / np.linalg.norm(KV, axis=0)
    backward = backward_errors(KV, MV, vecs, vals, _norm1(p.Kr), _norm1(p.Mr))
    ortho = float(np.abs(vecs.T @ MV - np.eye(vecs.shape[1])).max())
    if backward.max() > backward_tol:
        raise NumericalError(f"eigen backward error {backward.max():.3g} exceeds {backward_tol:g} "
                             f"(mode {int(backward.argmax()) + 1}, {method} solver)")
    if ortho > ORTHOGONALITY_TOL:
        raise NumericalError(orthogonality_message(ortho))
    return Evidence(vecs, residuals, backward, ortho)


def refined_eigenvalues(vals, shapes, energy, lambda_ref: float, lambda_max: float,
                        zero_tol: float):
    """Eigenvalues as energy Rayleigh quotients ``energy(shapes)`` (v^T M v = 1), and the order
    that sorts them. Refuses vectors lost to K's round-off (NumericalError)."""
    vals = np.asarray(energy(shapes), dtype=float)
    # The quotient is free of K's cancellation, but not of a vector that is itself lost:
    # K as stored perturbs its own spectrum by about eps lambda_max, so past
    # eps lambda_max / lambda_1 ~ 10 the lowest vectors are wrong and their quotients with
    # them (a 30 000-element cantilever: mode 1 off by 11 %, 10 000 elements: 3e-5).
    elastic = vals > zero_tol * lambda_ref
    if elastic.any():
        lost = np.finfo(float).eps * lambda_max / vals[elastic].min()
        if lost > LOST_LIMIT:
            raise NumericalError(
                f"the mesh is too fine for double precision: eps lambda_max / lambda_1 = "
                f"{lost:.2g}, so the lowest mode shapes are lost to round-off in K. Use fewer "
                "elements per link")
        if lost > 1e-2:
            log.warning("eps lambda_max / lambda_1 = %.2g: the lowest frequencies may be off "
                        "by 1e-5 or more; use fewer elements per link", lost)
    return vals, np.argsort(vals, kind="stable")


def label(vals, zero: float, lambda_ref: float, zero_tol: float, refined: bool,
          lambda_max: float) -> tuple[ModeKind, ...]:
    """ELASTIC or MECHANISM per eigenvalue: below ``zero`` [rad^2/s^2] a mode is a rigid-body
    or mechanism mode. Unrefined eigenvalues between the physical threshold
    ``zero_tol * lambda_ref`` and ``zero`` (the round-off floor) cannot be told apart from a
    mechanism: NumericalError."""
    if not refined:
        unsure = (vals >= zero_tol * lambda_ref) & (vals < zero)
        if unsure.any():
            raise NumericalError(
                f"mode {int(np.argmax(unsure)) + 1} ({np.sqrt(max(vals[unsure][0], 0)) / (2 * np.pi):.4g} "
                f"Hz) lies below the round-off floor of this mesh ({np.sqrt(zero) / (2 * np.pi):.4g} "
                "Hz, 100 eps lambda_max): it cannot be told from a mechanism mode. Use fewer "
                "elements per link, or the energy refinement (analysis.analyze does by default)")
        elastic = vals[vals >= zero]
        # warn where the round-off could reach the default frequency tolerance (1e-6)
        if elastic.size and np.finfo(float).eps * lambda_max / elastic[0] > ROUNDOFF_WARN:
            log.warning("eigenvalues carry about %.1g relative round-off (eps lambda_max / "
                        "lambda_1): the mesh is finer than double precision supports without "
                        "the energy refinement", np.finfo(float).eps * lambda_max / elastic[0])
    return tuple(MECHANISM if v < zero else ELASTIC for v in vals)


def solve_modes(K, M, n_modes: int, *, T=None, lambda_ref: float,
                solver: EigenSolver = DEFAULT_SOLVER, zero_tol: float = ZERO_TOL,
                backward_tol: float = BACKWARD_TOL, energy=None) -> ModalResult:
    """Lowest ``n_modes`` modes of the model's (K, M), its rigid constraints eliminated by
    u = T q when T is given: ``prepare``, ``eigen_solve``, ``check``, then (optionally)
    ``refined_eigenvalues`` and ``label``.

    ``lambda_ref`` [rad^2/s^2] is the model's own scale (e.g. the lowest bare-beam eigenvalue);
    modes below ``zero_tol * lambda_ref`` are labelled rigid-body/mechanism. ``solver`` picks
    the dense or the sparse eigen solver (``eigensolver.EigenSolver``). DOFs without mass are
    condensed exactly (never handed to the eigen solver). ``energy``: optional callable giving
    u^T K u for full-size shapes without cancellation (``energy.twice_strain_energy``); the
    eigenvalues are then its Rayleigh quotients, free of the round-off of K's large entries.
    Raises NumericalError on NaN, clearly negative eigenvalues, a backward error above
    ``backward_tol`` or lost M-orthogonality.
    """
    return _solved(prepare(K, M, T), T, n_modes, lambda_ref, solver, zero_tol, backward_tol,
                   energy)


def solve_eliminated_modes(Kt, Mt, n_modes: int, *, T, lambda_ref: float,
                           solver: EigenSolver = DEFAULT_SOLVER, zero_tol: float = ZERO_TOL,
                           backward_tol: float = BACKWARD_TOL, energy=None) -> ModalResult:
    """``solve_modes`` of a model whose rigid constraints are already eliminated: ``Kt``,
    ``Mt`` are T^T K T and T^T M T (``assembly.assemble_reduced_dense``), and T (None: no
    constraint) only maps the shapes back to the model's DOFs."""
    return _solved(prepare(Kt, Mt), T, n_modes, lambda_ref, solver, zero_tol, backward_tol,
                   energy)


def _solved(p: Prepared, T, n_modes: int, lambda_ref: float, solver: EigenSolver,
            zero_tol: float, backward_tol: float, energy) -> ModalResult:
    k = min(n_modes, p.n_solved)
    method = solver.pick(p.n_solved, k)
    lambda_max = p.lambda_max
    vals, vecs = eigen_solve(p, k, method, lambda_ref)
    zero = max(zero_tol * lambda_ref, roundoff_floor(lambda_max))
    ev = check(p, vals, vecs, zero, method, backward_tol)
    shapes = ev.vectors if T is None else np.asarray(T @ ev.vectors)
    residuals, backward = ev.residuals, ev.backward_errors
    if energy is not None:
        vals, order = refined_eigenvalues(vals, shapes, energy, lambda_ref, lambda_max, zero_tol)
        vals, shapes, residuals, backward = vals[order], shapes[:, order], residuals[order], backward[order]
        # The quotient of a mechanism mode is ~ (eps lambda_max)^2 / lambda: the round-off floor
        # no longer applies (it passes lambda_1 near 512 elements per link).
        zero = zero_tol * lambda_ref
    kinds = label(vals, zero, lambda_ref, zero_tol, energy is not None, lambda_max)
    lam = np.clip(vals, 0.0, None)
    return ModalResult(eigenvalues=vals, frequencies=np.sqrt(lam) / (2 * np.pi), shapes=shapes,
                       kinds=kinds, residuals=residuals, backward_errors=backward,
                       orthogonality_error=ev.orthogonality_error, solver=method, n_dofs=p.n,
                       refined=energy is not None, condensed=p.n - p.n_solved)


def lowest_elastic(solve, n_elastic: int, expected_mechanisms: int = 0,
                   spare: int = SPARE_MODES) -> ModalResult:
    """The lowest modes up to and including the ``n_elastic``-th elastic one.

    ``solve(k)`` -> ModalResult of the lowest k modes. Solves for ``n_elastic`` plus the
    mechanism modes expected (these sit lowest) plus ``spare``; when more mechanism modes turn
    up than there was room for (a free joint frees a whole link), solves again with room for
    all of them and SPARE_MODES more. Returns fewer elastic modes only when the model has no more (every mode was
    solved); ``require_elastic`` turns that into an error."""
    k = n_elastic + expected_mechanisms + spare
    while True:
        try:
            result = solve(k)
        except NumericalError:
            _refuse_beyond_the_model(solve, n_elastic, expected_mechanisms + spare + 1)
            raise
        n_mechanism = result.kinds.count(MECHANISM)
        if len(result.kinds) - n_mechanism >= n_elastic or len(result.kinds) < k:
            return result  # enough, or every mode of the model
        k = n_elastic + n_mechanism + SPARE_MODES


def _refuse_beyond_the_model(solve, n_elastic: int, probe: int) -> None:
    """When a request for (nearly) every mode fails its checks, see whether it asked for more
    elastic modes than the model has: the highest modes of a stiff, light frame fail the
    backward-error check through the spectral shift, and a user who asked for more modes than
    there are should hear that, not about round-off. Raises that InputError, or returns."""
    while True:  # the lowest modes, until the first elastic one shows all the mechanisms
        low = solve(probe)
        n_mechanism = low.kinds.count(MECHANISM)
        if n_mechanism < len(low.kinds) or len(low.kinds) < probe:
            break
        probe *= 2
    available = low.n_dofs - low.condensed - n_mechanism
    if n_elastic > available:
        raise _too_few_elastic(n_elastic, available, low)


def require_elastic(result: ModalResult, n_elastic: int) -> ModalResult:
    """``result`` if it holds ``n_elastic`` elastic modes; else InputError naming how many the
    model has (its DOFs less its rigid-body/mechanism modes)."""
    found = len(result.elastic)
    if found < n_elastic:
        raise _too_few_elastic(n_elastic, found, result)
    return result


def _too_few_elastic(asked: int, available: int, result: ModalResult) -> InputError:
    """The refusal of ``asked`` elastic modes from a model with ``available``, which
    ``result`` (a solve of it) describes."""
    return InputError(
        f"{asked} elastic modes asked for, but the model has only {available} ({result.n_dofs} "
        f"DOFs, {result.kinds.count(MECHANISM)} of them rigid-body/mechanism modes"
        + (f", {result.condensed} massless and condensed" if result.condensed else "") + ")",
        field="number of modes (-n)", expected=f"at most {available}, or a finer mesh (-e)")
