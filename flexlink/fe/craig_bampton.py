"""Craig-Bampton (fixed-interface component mode synthesis) reduction of the links, for sweeps.

A link's local K and M do not depend on the pose, so each link is reduced once, in its own
frame, to the 6 DOFs of its two end nodes (boundary) plus its lowest fixed-interface modes
(interior modes with both ends clamped); that reduction is itself one per mesh size, since
every link of that many elements is the same unit chain scaled (``_link_scales``). With u_I
the interior DOFs,
    u_I = Psi u_B + Phi q,   Psi = -K_II^-1 K_IB (static constraint modes),
and the reduced link matrices are T^T K T, T^T M T with T = [[I, 0], [Psi, Phi]]. Keeping every
interior mode gives the full model back exactly; the truncation is the only approximation.

Per pose only the boundary DOFs rotate (the modal coordinates are scalars in the link frame),
so a pose costs 2 small matrix products per link, one scatter and a dense eigen solve of
(boundary DOFs + kept modes) unknowns, all done for every pose of a sweep at once
(``CraigBamptonPlan.stacked``, ``truncation.corrected``). Springs, joint masses and rigid
constraints act on link end nodes only; they are taken from the full model's layout through a
"boundary model" (``FrameModel`` with one element per link, whose nodes are the end nodes), so
``assembly.spring_entries``, ``point_mass_entries`` and ``rigid_elimination`` are reused unchanged.

Axial (u) and bending (v, rz) DOFs of a straight link are uncoupled in its frame, so each family
is reduced on its own; that keeps every kept mode purely axial or purely bending, and lets a
link of another length L reuse the reduction made at L0 exactly: with r = L / L0 the chain
scales as K_axial / r, M_axial r, K_bending r^-3 D K D, M_bending r D M D (D = r on rotation
DOFs, as ``link.chain_entries`` scales a unit element), and the reduced matrices follow with the
same diagonal scaling (D on the boundary rotations only; the modal coordinates absorb the rest).

Mode choice (``CUTOFF``): a link keeps every fixed-interface mode whose frequency is at most
CUTOFF times the highest requested system frequency (that of the reduced pencil, an upper bound
of the exact one). ``sweep._craig_bampton_sweep`` checks this for every pose and solves the
poses whose frequencies have grown past what the basis was chosen for again, on an enlarged
basis.

Truncation correction: plain truncation converges slowly here (about 3e-5 relative on the sixth
mode of Table II case 2 with a cut-off of 16 times its frequency), because the axial
fixed-interface modes grow only like k^2. The truncated modes couple to the kept DOFs through
the mass matrix only, so their effect is put back (``truncation.corrected``) from a short series
of 6 x 6 residual-flexibility matrices per link, computed once, with a few updates of each
eigenvector; with it a basis of 3 times the highest frequency is within round-off of the full
model (tests/fe/test_craig_bampton.py).

Mode shapes: ``CraigBamptonPlan.shapes`` expands reduced eigenvectors to the full mesh (boundary
DOFs plus each link's basis); the truncation correction refines eigenvalues only, so those
shapes carry the plain truncation's error. ``modal_sweep`` returns frequencies only.
"""

from __future__ import annotations

import dataclasses
import functools
import logging
import math

import numpy as np
import scipy.linalg as la

from flexlink.errors import NumericalError
from flexlink.fe.assembly import point_mass_entries, rigid_elimination, spring_entries
from flexlink.fe.link import link_matrices
from flexlink.fe.model import GROUND, FrameModel, LinkMesh, Springs, _Layout

log = logging.getLogger(__name__)

CUTOFF = 3.0  # fixed-interface modes kept up to this times the highest requested frequency
SERIES = 6  # terms of the truncated modes' series in lambda / lambda_k (``ReducedLink``)


@dataclasses.dataclass(frozen=True)
class _Family:
    """One DOF family (axial or bending) of a link, reduced with every interior mode kept; in
    ``_families`` the unit chain's (element length 1, EA = EI = rhoA = 1, units to match).

    boundary: local DOF indices of the family's end-node DOFs; slots: their places among the
    link's 6 boundary DOFs; K, M: reduced matrices over (boundary, all interior modes in
    ascending eigenvalue), so keeping the lowest m modes is a leading block; eigenvalues
    [rad^2/s^2] of the fixed-interface modes; basis: T (local family DOFs x reduced DOFs) to
    recover full shapes; tail (modes + 1, SERIES, boundary, boundary): tail[m, j] = sum over
    the modes from the m-th on of c c^T / lambda^(j + 1) (c: a mode's mass coupling with the
    boundary DOFs, its modal mass being 1), the series of the modes truncated after m."""

    dofs: np.ndarray
    boundary: np.ndarray
    slots: np.ndarray
    K: np.ndarray
    M: np.ndarray
    eigenvalues: np.ndarray
    basis: np.ndarray
    tail: np.ndarray


@functools.lru_cache(maxsize=16)
def _families(elements: int) -> tuple[_Family, _Family]:
    """(axial, bending) _Family of a chain of ``elements`` unit-length elements with
    EA = EI = rhoA = 1 (cached). Every link of that many elements is this chain with its
    matrices scaled (``_link_scales``), so one eigen solve per mesh serves all its links.

    The reduced matrices come from their block formulas, O(n) products with the static modes
    Psi, rather than T^T K T on dense n x n: K_BB + K_BI Psi, M_BB + M_BI Psi + Psi^T C and
    C^T Phi with C = M_IB + M_II Psi; the interior blocks are diag(eigenvalues) and I."""
    K, M = (A.toarray() for A in link_matrices(float(elements), elements, 1.0, 1.0, 1.0))
    n = K.shape[0]
    local = np.arange(n)
    end = np.isin(local // 3, (0, elements))
    out = []
    for members in (local % 3 == 0, local % 3 != 0):
        dofs = local[members]
        b, i = dofs[end[dofs]], dofs[~end[dofs]]
        nb, ni = len(b), len(i)
        Kbb, Mbb = K[np.ix_(b, b)], M[np.ix_(b, b)]
        T = np.zeros((len(dofs), nb + ni))
        T[np.flatnonzero(end[dofs]), np.arange(nb)] = 1.0
        Kr, Mr = np.zeros((2, nb + ni, nb + ni))
        if ni:
            Kii, Mii, Kib, Mib = K[np.ix_(i, i)], M[np.ix_(i, i)], K[np.ix_(i, b)], M[np.ix_(i, b)]
            psi = -la.solve(Kii, Kib, assume_a="pos")
            lam, phi = la.eigh(Kii, Mii)
            T[np.flatnonzero(~end[dofs]), :nb] = psi
            T[np.flatnonzero(~end[dofs]), nb:] = phi
            C = Mib + Mii @ psi
            Kbb = Kbb + Kib.T @ psi
            Mbb = Mbb + Mib.T @ psi + psi.T @ C
            Mr[:nb, nb:] = C.T @ phi
            Mr[nb:, :nb] = Mr[:nb, nb:].T
        else:
            lam = np.zeros(0)
        # the boundary blocks are symmetric in exact arithmetic; the coupling of K is exactly 0
        # (static modes K-orthogonal to the M-orthonormal fixed-interface modes), as
        # ``CraigBamptonPlan.mass_factor`` assumes
        Kr[:nb, :nb], Mr[:nb, :nb] = (Kbb + Kbb.T) / 2, (Mbb + Mbb.T) / 2
        Kr[nb:, nb:], Mr[nb:, nb:] = np.diag(lam), np.eye(ni)
        out.append(_Family(dofs=dofs, boundary=b, slots=np.searchsorted(np.flatnonzero(end), b),
                           K=Kr, M=Mr, eigenvalues=lam, basis=T, tail=_tail(Mr[:nb, nb:], lam)))
    return tuple(out)


def _tail(c: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """``_Family.tail`` from the mass couplings ``c`` (boundary, modes) of M-normalised modes
    and their eigenvalues ``lam`` [rad^2/s^2]."""
    terms = np.einsum("ak,bk,jk->kjab", c, c, lam ** -(np.arange(SERIES)[:, None] + 1.0))
    tail = np.zeros((len(lam) + 1, SERIES, len(c), len(c)))
    tail[:-1] = np.cumsum(terms[::-1], axis=0)[::-1]  # smallest terms first
    return tail


@dataclasses.dataclass(frozen=True)
class ReducedLink:
    """One link reduced to its 6 boundary DOFs (start u, v, rz, end u, v, rz, local frame)
    followed by ``n_modes`` fixed-interface modal coordinates, at reference ``length`` [m].

    K, M: reduced matrices; axial, rotation: which reduced DOFs scale how with the length (see
    the module docstring); basis (3 (elements + 1), 6 + n_modes): local displacements of the
    whole chain from the reduced coordinates at the reference length; flexibility
    (SERIES, 6, 6): F_j = sum over truncated modes of c c^T m^j / k^(j + 1) at the
    reference length (c: a truncated mode's mass coupling with the boundary DOFs, k, m: its
    modal stiffness and mass; local frame). Eliminating the truncated modes adds
    -lambda^2 sum_k c c^T / (k - lambda m) = -lambda^2 sum_j lambda^j F_j to the reduced dynamic
    stiffness (``truncation.py``); every truncated mode has k / m > lambda_cut >= CUTOFF^2
    lambda, so the terms left out are below CUTOFF^(-2 SERIES) of the first. Axial and bending
    truncated modes act on separate boundary DOFs (0, 3 and 1, 2, 4, 5), so F_j holds both."""

    length: float
    K: np.ndarray
    M: np.ndarray
    axial: np.ndarray  # bool per reduced DOF: axial family
    rotation: np.ndarray  # bool per reduced DOF: boundary rotation
    basis: np.ndarray
    flexibility: np.ndarray

    @property
    def n_modes(self) -> int:
        return self.K.shape[0] - 6

    def powers(self) -> np.ndarray:
        """(2, 6 + n_modes): the link at r times its reference length has K = a a^T * K_ref and
        M = b b^T * M_ref, elementwise, with a = r^powers[0], b = r^powers[1] (exact rescaling,
        module docstring)."""
        turn = self.rotation.astype(float)
        return np.stack([np.where(self.axial, -0.5, -1.5) + turn, 0.5 + turn])

    def matrices(self, length: float) -> tuple[np.ndarray, np.ndarray]:
        """(K, M) of the same link at ``length`` [m], exact rescaling of the reference ones."""
        if length == self.length:
            return self.K, self.M
        a, b = (length / self.length) ** self.powers()
        return a[:, None] * self.K * a, b[:, None] * self.M * b


def _link_scales(length: float, elements: int, EA: float, EI: float,
                 rhoA: float) -> tuple[tuple[float, float, float], ...]:
    """Per family (axial, bending) of a link of ``length`` [m], EA [N], EI [N m^2], rhoA
    [kg/m]: (k, m, h) such that its K is k S K_1 S and its M is m S M_1 S, with K_1, M_1 the
    unit chain's (``_families``), h the element length [m] and S = h on rotation DOFs, 1
    elsewhere (``link.chain_entries``): k = EA / h or EI / h^3, m = rhoA h. Then Psi =
    S_I^-1 Psi_1 S_B, Phi = S_I^-1 Phi_1 / sqrt(m), the eigenvalues are k / m times the unit
    chain's, and the reduced matrices, basis and truncated-mode series follow by diagonal
    scalings (E = diag(S_B, 1 / sqrt(m)) on the reduced DOFs)."""
    h = length / elements
    return (EA / h, rhoA * h, h), (EI / h**3, rhoA * h, h)


def _fixed_interface_eigenvalues(length: float, elements: int, EA: float, EI: float,
                                 rhoA: float) -> list[np.ndarray]:
    """Fixed-interface eigenvalues [rad^2/s^2] of a link (axial, bending), ascending."""
    return [fam.eigenvalues * (k / m) for fam, (k, m, _) in
            zip(_families(elements), _link_scales(length, elements, EA, EI, rhoA))]


def reduce_link(length: float, elements: int, EA: float, EI: float, rhoA: float,
                lambda_cut: float) -> ReducedLink:
    """Craig-Bampton reduction of a link of ``length`` [m], EA [N], EI [N m^2], rhoA [kg/m]
    keeping the fixed-interface modes with eigenvalue <= lambda_cut [rad^2/s^2] (both
    families): the unit chain's, scaled (``_link_scales``)."""
    scales = _link_scales(float(length), int(elements), EA, EI, rhoA)
    families = _families(int(elements))
    lams = _fixed_interface_eigenvalues(float(length), int(elements), EA, EI, rhoA)
    kept = [int(np.searchsorted(lam, lambda_cut, side="right")) for lam in lams]
    # reduced DOF order: the 6 boundary DOFs in local node order, then axial, then bending modes
    n = 6 + sum(kept)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    basis = np.zeros((3 * (int(elements) + 1), n))
    axial_mask = np.zeros(n, dtype=bool)
    flexibility = np.zeros((SERIES, 6, 6))
    next_mode = 6
    for index, (fam, (k, m, h), lam, kept_f) in enumerate(zip(families, scales, lams, kept)):
        slots = np.concatenate([fam.slots, next_mode + np.arange(kept_f)])
        nb, size = len(fam.slots), len(slots)
        s_b = np.where(fam.boundary % 3 == 2, h, 1.0)
        e = np.concatenate([s_b, np.full(kept_f, m**-0.5)])
        Kf, Mf = k * e[:, None] * fam.K[:size, :size] * e, m * e[:, None] * fam.M[:size, :size] * e
        # the modal blocks exactly, as in ``_families``
        Kf[nb:, nb:], Mf[nb:, nb:] = np.diag(lam[:kept_f]), np.eye(kept_f)
        K[np.ix_(slots, slots)], M[np.ix_(slots, slots)] = Kf, Mf
        s = np.where(fam.dofs % 3 == 2, h, 1.0)
        basis[np.ix_(fam.dofs, slots)] = fam.basis[:, :size] * e / s[:, None]
        axial_mask[slots] = index == 0
        series = m * (m / k) ** (np.arange(SERIES) + 1.0)
        flexibility[:, fam.slots[:, None], fam.slots] = (series[:, None, None] * s_b[:, None]
                                                         * fam.tail[kept_f] * s_b)
        next_mode += kept_f
    rotation = np.zeros(n, dtype=bool)
    rotation[[2, 5]] = True
    for A in (K, M, basis, axial_mask, rotation, flexibility):
        A.flags.writeable = False
    return ReducedLink(length=float(length), K=K, M=M, axial=axial_mask, rotation=rotation,
                       basis=basis, flexibility=flexibility)


def fixed_interface_bound(links, k: int) -> float:
    """The k-th lowest fixed-interface eigenvalue [rad^2/s^2] of the ``links`` (LinkMesh) taken
    together (inf when they have fewer). Clamping every link end leaves exactly these modes, and
    constraining DOFs raises each eigenvalue (interlacing), so the linkage's k-th eigenvalue is
    at most this, and so is any Craig-Bampton reduction's keeping the lowest k of them."""
    lams = np.sort(np.concatenate([lam for l in links for lam in _fixed_interface_eigenvalues(
        float(l.length), int(l.elements), l.section.EA, l.section.EI,
        l.section.mass_per_length)]))
    return float(lams[k - 1]) if len(lams) >= k else math.inf


def boundary_model(lay: _Layout, model: FrameModel) -> FrameModel:
    """The full model's end nodes only (node 2 l: start of link l, 2 l + 1: its end), with the
    model's springs (the layout's, some made rigid by ``pose.pose_model``) and joint masses
    renumbered onto them. Every spring and joint mass of the
    full model sits on an end node, so nothing is lost (checked)."""
    node_map = {}
    for index, link in enumerate(model.links):
        node_map[link.first_node] = 2 * index
        node_map[link.first_node + link.elements] = 2 * index + 1

    def dof(d):
        if d == GROUND:
            return GROUND
        node, k = divmod(int(d), 3)
        if node not in node_map:
            raise AssertionError("a spring acts on an inner node of a link")
        return 3 * node_map[node] + k

    s = model.springs
    springs = Springs(np.array([dof(d) for d in s.dof_a], dtype=np.int64),
                      np.array([dof(d) for d in s.dof_b], dtype=np.int64),
                      np.asarray(s.stiffness, dtype=float), s.labels)
    links = tuple(LinkMesh(l.name, 2 * i, 1, l.length, l.angle, l.section)
                  for i, l in enumerate(model.links))
    nodes = np.concatenate([model.nodes[[l.first_node, l.first_node + l.elements]]
                            for l in model.links])
    return FrameModel(nodes=nodes, links=links, springs=springs,
                      point_masses=tuple((node_map[n], m) for n, m in lay.point_masses),
                      joint_nodes={j: tuple(node_map[n] for n in v)
                                   for j, v in lay.joint_nodes.items()})


class CraigBamptonPlan:
    """The reduced dense K and M of every pose of one topology (boundary DOFs after the exact
    rigid-joint elimination, then each link's modal coordinates), for a given cut-off
    ``lambda_cut`` [rad^2/s^2]. Built from one model of the topology; ``reach``: the lowest
    truncated fixed-interface eigenvalue [rad^2/s^2] (inf: none truncated) at its lengths."""

    def __init__(self, model: FrameModel, lay: _Layout, lambda_cut: float):
        self.links = []
        kept, truncated = [0.0], [math.inf]
        for link in model.links:
            s = link.section
            self.links.append(reduce_link(link.length, link.elements, s.EA, s.EI,
                                          s.mass_per_length, lambda_cut))
            for lam in _fixed_interface_eigenvalues(float(link.length), int(link.elements),
                                                    s.EA, s.EI, s.mass_per_length):
                m = int(np.searchsorted(lam, lambda_cut, side="right"))
                kept += list(lam[:m][-1:])
                truncated += list(lam[m:m + 1])
        # the same basis for any cut-off in [highest kept, reach) [rad^2/s^2], at these lengths
        self.highest_kept, self.reach = max(kept), min(truncated)
        bmodel = boundary_model(lay, model)
        T = rigid_elimination(bmodel)
        n_b = bmodel.n_dofs
        if T is None:
            column, n_br = np.arange(n_b), n_b
        else:
            T = T.tocsr()
            column = np.full(n_b, -1)
            column[np.diff(T.indptr) == 1] = T.indices
            n_br = T.shape[1]
        self.n_boundary = n_br
        self.n = n_br + sum(l.n_modes for l in self.links)
        self.spare = self.n * self.n
        # each link's reduced DOFs -> column of the plan's matrix (-1: grounded)
        offset, columns = n_br, []
        for index, rl in enumerate(self.links):
            boundary = column[6 * index + np.arange(6)]
            columns.append(np.concatenate([boundary, offset + np.arange(rl.n_modes)]))
            offset += rl.n_modes
        self.columns = columns
        self.boundary = bmodel
        self.boundary_column = column
        # every link's reduced matrices padded to one size, K over M, with the slot of each
        # entry in the (n + 1)-square stack (grounded DOFs and padding: the dropped last row)
        size = max(rl.K.shape[0] for rl in self.links)
        self._reference = np.zeros((2, len(self.links), size, size))
        self._power = np.zeros((2, len(self.links), size))  # entries scale as r^(p_i + p_j)
        where = np.full((len(self.links), size), self.n)
        for index, (rl, cols) in enumerate(zip(self.links, columns)):
            kept = cols[cols >= 0]
            if len(np.unique(kept)) != len(kept):
                raise AssertionError("two DOFs of one link share a reduced DOF")
            m = rl.K.shape[0]
            self._reference[:, index, :m, :m] = rl.K, rl.M
            self._power[:, index, :m] = rl.powers()
            where[index, :m] = np.where(cols >= 0, cols, self.n)
        self._slots = (where[:, :, None] * (self.n + 1) + where[:, None, :]).ravel()
        self.boundary_columns = np.array([cols[:6] for cols in columns])
        # the truncated modes' series (``truncation.corrected``): per link, F_0 .. F_SERIES-1
        # stacked, at reference length
        self.flexibility = np.stack([rl.flexibility.reshape(SERIES * 6, 6)
                                     for rl in self.links])
        self.reference_lengths = np.array([rl.length for rl in self.links])
        self.constant = []
        for rows, cols, vals in (spring_entries(bmodel), point_mass_entries(bmodel)):
            r, c = column[rows], column[cols]
            slots = np.where((r >= 0) & (c >= 0), r * self.n + c, self.spare)
            self.constant.append(np.bincount(slots, weights=vals, minlength=self.spare + 1)
                                 [:self.spare].reshape(self.n, self.n))

    def matrices(self, model: FrameModel) -> tuple[np.ndarray, np.ndarray]:
        """Reduced dense (K, M) of ``model`` (the plan's topology at any pose)."""
        angles = np.array([[link.angle for link in model.links]])
        lengths = np.array([[link.length for link in model.links]])
        K, M = self.stacked(angles, lengths)
        return K[0], M[0]

    def stacked(self, angles: np.ndarray, lengths: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Reduced dense K and M, each (poses, n, n), of the plan's topology at many poses at
        once: ``angles`` [rad] and ``lengths`` [m], each (poses, links), in the plan's link
        order. Every link's rescaled reduced matrices are rotated on their boundary DOFs
        (Q^T K Q) for all poses together and summed into a (n + 1)-square stack by one
        ``np.bincount``; its last row and column collect the grounded DOFs and are dropped."""
        angles, lengths = np.atleast_2d(angles), np.atleast_2d(lengths)
        poses, n = angles.shape[0], self.n
        r = lengths / self.reference_lengths  # (P, L)
        scale = r[None, :, :, None] ** self._power[:, None]  # (2, P, L, size): a and b
        A = scale[..., :, None] * self._reference[:, None] * scale[..., None, :]
        c, s = np.cos(angles)[..., None], np.sin(angles)[..., None]
        for x in (0, 3):  # Q^T A Q, Q turning each end's (u, v) into the link frame
            rows = A[..., x, :].copy()
            A[..., x, :] = c * rows - s * A[..., x + 1, :]
            A[..., x + 1, :] = s * rows + c * A[..., x + 1, :]
            cols = A[..., x].copy()
            A[..., x] = c * cols - s * A[..., x + 1]
            A[..., x + 1] = s * cols + c * A[..., x + 1]
        stack = (n + 1) ** 2
        slots = np.arange(2 * poses)[:, None] * stack + self._slots
        summed = np.bincount(slots.ravel(), weights=A.ravel(), minlength=2 * poses * stack)
        K, M = summed.reshape(2, poses, n + 1, n + 1)[:, :, :n, :n]
        return K + self.constant[0], M + self.constant[1]

    def mass_factor(self, M: np.ndarray) -> np.ndarray:
        """F^-1 (P, n, n) with F^-1 M F^-T = I for a stack M (P, n, n) of this plan's mass
        matrices, from their structure: M = [[B, C], [C^T, D]] over (boundary DOFs, modal
        coordinates) with D diagonal (the modes of a link are M-orthonormal, those of two
        links do not couple), so M = F F^T with F = [[L, C D^-1/2], [0, D^1/2]], L L^T =
        B - C D^-1 C^T: a Cholesky factor and an inverse of the boundary size only."""
        nb = self.n_boundary
        C = M[:, :nb, nb:]
        d = np.einsum("pii->pi", M[:, nb:, nb:])
        CD = C / d[:, None, :]
        try:
            L = np.linalg.cholesky(M[:, :nb, :nb] - CD @ C.transpose(0, 2, 1))
        except np.linalg.LinAlgError:
            raise NumericalError("a reduced mass matrix of the sweep is not positive "
                                 "definite") from None
        Li = np.linalg.inv(L)
        out = np.zeros_like(M)
        out[:, :nb, :nb] = Li
        out[:, :nb, nb:] = -Li @ CD
        out[:, nb + np.arange(self.n - nb), nb + np.arange(self.n - nb)] = d**-0.5
        return out

    def shapes(self, model: FrameModel, vectors: np.ndarray) -> np.ndarray:
        """Full-model displacement shapes (model.n_dofs, k) from reduced eigenvectors
        (self.n, k): boundary DOFs from the plan's columns, each link's chain from its
        Craig-Bampton basis (rotated back to the global frame)."""
        vectors = np.asarray(vectors)
        padded = np.vstack([vectors, np.zeros((1, vectors.shape[1]))])  # -1: grounded -> 0
        out = np.zeros((model.n_dofs, vectors.shape[1]))
        for rl, link, cols in zip(self.links, model.links, self.columns):
            c, s = math.cos(link.angle), math.sin(link.angle)
            R = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
            q = padded[cols].copy()
            q[:6] = np.kron(np.eye(2), R) @ q[:6]  # boundary DOFs to the link frame
            r = link.length / rl.length
            scale = np.where(rl.rotation, r, 1.0)  # basis at length L: see the module docstring
            inner = np.where(np.arange(rl.basis.shape[0]) % 3 == 2, 1 / r, 1.0)
            local = inner[:, None] * (rl.basis @ (scale[:, None] * q))
            nodes = link.nodes
            for k in range(3):
                out[3 * nodes + k] = sum(R[j, k] * local[j::3] for j in range(3))
        return out

