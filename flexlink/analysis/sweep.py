"""Natural frequencies over many poses of one linkage: the inner loop of cycle maps,
calibration and Monte Carlo.

The topology (links, sections, joints, mesh) is fixed; only joint positions change from pose to
pose, so each link's local matrices are built once (cached in ``link.py``) and every pose only
rotates and assembles them before the eigen solve. Which global entry each rotated link entry
lands in, and the springs, masses and rigid-joint elimination, depend on the topology alone; for
models the dense solver takes, ``_DensePlan`` works them out once and each pose scatters its
rotated entries straight into the reduced dense K and M (one ``np.bincount``), so the pose costs
little more than the eigen solve itself.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import logging
import math
from collections.abc import Iterable, Mapping

import numpy as np

from flexlink.fe.model_at_pose import in_plane_eigen_scale
from flexlink.fe.assembly import (assemble, dense_slots, dense_sum, placed_link_entries,
                                  point_mass_entries, reduced_columns, spring_entries)
from flexlink.fe.assembly import rigid_elimination
from flexlink.fe.craig_bampton import CUTOFF, CraigBamptonPlan, fixed_interface_bound
from flexlink.fe.truncation import CONVERGED, corrected
from flexlink.fe.beams import BeamTheory, link_entries
from flexlink.fe.model import FrameModel, Topology, layout
from flexlink.fe.model_at_pose import pose_model
from flexlink.analysis.eigensolver import EigenSolver, Method
from flexlink.analysis.solve import DENSE_LIMIT, ELASTIC, SPARE_MODES, lowest_elastic, solve_modes
from flexlink.analysis.stacked import stacked_modes
from flexlink.choices import parse_choice
from flexlink.errors import InputError
from flexlink.parallel import run_tasks, workers

log = logging.getLogger(__name__)

# A sweep's dense solves go through ``_DensePlan``, which makes a pose's dense K and M cheap,
# so its solver stays dense far beyond a single solve's AUTO_DENSE_MAX.
SWEEP_SOLVER = EigenSolver(dense_max=DENSE_LIMIT)
DENSE_SOLVER = EigenSolver(Method.DENSE)


class Reduction(enum.StrEnum):
    """How a sweep cuts each link down before the eigen solve (None: the full model)."""

    CRAIG_BAMPTON = "craig-bampton"  # end nodes and fixed-interface modes (``craig_bampton.py``)


@dataclasses.dataclass(frozen=True)
class SweepResult:
    """frequencies[i, j]: j-th elastic natural frequency [Hz] at pose i (NaN if fewer found);
    mechanism_counts[i]: rigid-body/mechanism modes found at pose i; note: why the sweep
    solved the full model instead of the reduction asked for (None: as asked)."""

    frequencies: np.ndarray
    mechanism_counts: np.ndarray
    note: str | None = None  # why the reduction asked for was not used, if it was not


# A node's rotation R = [[c, s, 0], [-s, c, 0], [0, 0, 1]] (assembly.node_rotation), each entry as
# (sign, factor) with factor 0: c, 1: s, 2: 1, 3: 0; a rotated entry's coefficient R[p, i] R[q, j]
# is then +- one of the products c c, c s, s s, c, s, 1 (or 0), indexed by _PRODUCT.
_R_SIGN = np.array([[1, 1, 1], [-1, 1, 1], [1, 1, 1]])
_R_FACTOR = np.array([[0, 1, 3], [1, 0, 3], [3, 3, 2]])
_PRODUCT = np.array([[0, 1, 3, -1],   # c c, c s, c 1, c 0
                     [1, 2, 4, -1],   # s c, s s, s 1, s 0
                     [3, 4, 5, -1],   # 1 c, 1 s, 1 1, 1 0
                     [-1, -1, -1, -1]])


class _DensePlan:
    """Where every link entry, spring and point mass goes in the reduced dense K and M of one
    topology, worked out once (u = T q with T from ``assembly.rigid_elimination``: a 0/1 matrix, one 1
    per kept DOF, so T^T K T only renumbers and drops entries).

    A link entry (3a + p, 3b + q) of value v adds v R[p, i] R[q, j] to (3a + i, 3b + j), and
    R[p, i] R[q, j] is +- one of six products of the link's cos and sin. The plan keeps, for each
    nonzero share, its source entry, its sign and product and its slot in the reduced matrix, so
    a pose costs a small table of products, one gather, one multiply and one ``np.bincount``
    for K and M together."""

    def __init__(self, model: FrameModel, T):
        self.column, self.n = reduced_columns(T, model.n_dofs)
        self.spare = self.n * self.n
        self.n_links = len(model.links)

        rows, cols, _, _, _ = placed_link_entries(model)
        link_of = np.repeat(np.arange(self.n_links),
                            [len(self._local(link)[0]) for link in model.links])
        p, q = rows % 3, cols % 3
        i, j = np.arange(3)[:, None], np.arange(3)[None, :]
        product = _PRODUCT[_R_FACTOR[p][:, :, None], _R_FACTOR[q][:, None, :]]  # (e, 3, 3)
        sign = _R_SIGN[p][:, :, None] * _R_SIGN[q][:, None, :]
        slot = self.slots((rows - p)[:, None, None] + i, (cols - q)[:, None, None] + j)
        keep = (product >= 0) & (slot != self.spare)
        self.source = np.broadcast_to(np.arange(len(rows))[:, None, None], keep.shape)[keep]
        # products of link l with sign +-1 sit at 12 l + 6 (sign < 0) + product in one table
        self.factor = (12 * link_of[:, None, None] + 6 * (sign < 0) + product)[keep]
        self.slot = slot[keep]
        self.size = self.spare + 1
        self.both_slots = np.concatenate([self.slot, self.slot + self.size])
        self._sources = {}  # link lengths -> (2, shares) local values
        self.constant = []
        for rows, cols, vals in (spring_entries(model), point_mass_entries(model)):
            self.constant.append(self.scatter(self.slots(rows, cols), vals))

    @staticmethod
    def _local(link):
        s = link.section
        return link_entries(link.length, link.elements, s)

    def slots(self, rows, cols) -> np.ndarray:
        return dense_slots(self.column, self.n, rows, cols)

    def scatter(self, slots, values) -> np.ndarray:
        return dense_sum(slots, values, self.n)

    def _source_values(self, model: FrameModel) -> np.ndarray:
        """(2, shares): each share's local K and M value. They depend on the link lengths only,
        which a rigid linkage repeats from pose to pose (up to a few last-bit variants)."""
        key = tuple(link.length for link in model.links)
        if key not in self._sources:
            if len(self._sources) >= 64:
                self._sources.clear()
            entries = [self._local(link) for link in model.links]
            self._sources[key] = np.stack([np.concatenate([e[2] for e in entries]),
                                           np.concatenate([e[3] for e in entries])])[:, self.source]
        return self._sources[key]

    def matrices(self, model: FrameModel) -> tuple[np.ndarray, np.ndarray]:
        """Reduced dense (K, M) of ``model`` (same topology as the plan's): T^T K T, T^T M T."""
        if len(model.links) != self.n_links:
            raise AssertionError("every pose of a sweep must have the plan's topology")
        table = []
        for link in model.links:
            c, s = math.cos(link.angle), math.sin(link.angle)
            products = [c * c, c * s, s * s, c, s, 1.0]
            table += products + [-p for p in products]
        shares = self._source_values(model) * np.array(table)[self.factor]
        # K and M in one bincount: M's slots follow K's
        summed = np.bincount(self.both_slots, weights=shares.ravel(), minlength=2 * self.size)
        K = summed[:self.spare].reshape(self.n, self.n) + self.constant[0]
        M = summed[self.size:self.size + self.spare].reshape(self.n, self.n) + self.constant[1]
        return K, M


def _solve_lowest(solve, n_modes: int, expected_mechanisms: int):
    """``solve.lowest_elastic`` (``expected_mechanisms``: found at the previous pose, usually
    the same at the next) and the bool mask of its elastic modes."""
    # no spare modes: a sweep's poses usually repeat the previous pose's mechanism count
    result = lowest_elastic(solve, n_modes, expected_mechanisms, spare=0)
    return result, np.array([kind == ELASTIC for kind in result.kinds])


def _lowest_elastic(solve, n_modes: int, expected_mechanisms: int):
    """(elastic frequencies [Hz], at most n_modes; mechanism count), see ``_solve_lowest``."""
    result, elastic = _solve_lowest(solve, n_modes, expected_mechanisms)
    return result.frequencies[elastic][:n_modes], len(elastic) - int(elastic.sum())


def craig_bampton_refusal(topology: Topology) -> str | None:
    """Why the Craig-Bampton reduction cannot take ``topology``'s links, None if it can. It
    reduces one unit chain per mesh size and scales it to each link, which is exact for
    Euler-Bernoulli elements only: a Timoshenko element's shear parameter 12 EI / (k G A h^2)
    changes with the element length h, so the scaled chain is another beam."""
    others = sorted({spec.section.beam for spec in topology.links} - {BeamTheory.EULER_BERNOULLI})
    if not others:
        return None
    return (f"the Craig-Bampton reduction takes Euler-Bernoulli links only, not {others[0]} "
            "ones: the full model was solved at every pose")


def modal_sweep(topology: Topology, poses: Iterable[Mapping[str, tuple[float, float]]],
                n_modes: int, solver: EigenSolver = SWEEP_SOLVER, progress=None,
                reduction: Reduction | None = None) -> SweepResult:
    """Lowest ``n_modes`` elastic frequencies [Hz] at each pose (joint name -> (x, y) [m]).

    ``progress``: optional callable wrapping the pose iterable (e.g. a tqdm factory).
    ``solver``: the eigen solver of the full model (``eigensolver.EigenSolver``).
    ``reduction``: None solves the full model; CRAIG_BAMPTON (or its text) solves each link
    reduced to its end nodes and fixed-interface modes (``craig_bampton.py``; its own stacked
    dense solve, ``solver`` unused)."""
    if reduction is not None:
        reduction = parse_choice(Reduction, reduction, "reduction")
    note = craig_bampton_refusal(topology) if reduction is Reduction.CRAIG_BAMPTON else None
    if note:
        log.info("%s", note)
        reduction = None
    poses = list(poses)
    iterator = progress(poses) if progress else poses
    freqs = np.full((len(poses), n_modes), np.nan)
    mechanism = np.zeros(len(poses), dtype=int)
    if reduction is Reduction.CRAIG_BAMPTON:
        _craig_bampton_sweep(topology, iterator, n_modes, freqs, mechanism)
        return SweepResult(frequencies=freqs, mechanism_counts=mechanism)
    plan = None
    expected = 0  # mechanism modes found at the previous pose: usually the same at the next
    fixed = layout(topology)
    for i, points in enumerate(iterator):
        model = pose_model(topology, points, fixed, warn=i == 0)
        lambda_ref = in_plane_eigen_scale(model)
        if i == 0:
            T = rigid_elimination(model)  # depends on the topology only
            n = model.n_dofs if T is None else T.shape[1]
            if solver.pick(n, n_modes) is Method.DENSE:  # refuses a dense solve too large
                plan = _DensePlan(model, T)
        if plan is not None:  # constraints eliminated by the plan
            K, M = plan.matrices(model)
            solve = functools.partial(solve_modes, K, M, lambda_ref=lambda_ref, solver=DENSE_SOLVER)
        else:
            K, M = assemble(model)
            solve = functools.partial(solve_modes, K, M, T=T, lambda_ref=lambda_ref, solver=solver)
        elastic, expected = _lowest_elastic(solve, n_modes, expected)
        freqs[i, :len(elastic)] = elastic
        mechanism[i] = expected
    return SweepResult(frequencies=freqs, mechanism_counts=mechanism, note=note)


def pose_geometry(topology: Topology, poses) -> tuple[np.ndarray, np.ndarray]:
    """(angles [rad], lengths [m]), each (poses, links): every link's direction and length at
    every pose (joint name -> (x, y) [m]), as ``model.build_model`` meshes them."""
    names = sorted({j for spec in topology.links for j in (spec.start, spec.end)})
    index = {name: k for k, name in enumerate(names)}
    try:
        xy = np.array([[points[name] for name in names] for points in poses], dtype=float)
    except KeyError as exc:
        raise InputError(f"no position for joint {exc.args[0]!r}", field="pose") from None
    start = xy[:, [index[spec.start] for spec in topology.links]]
    end = xy[:, [index[spec.end] for spec in topology.links]]
    d = end - start
    return np.arctan2(d[..., 1], d[..., 0]), np.hypot(d[..., 0], d[..., 1])


CHUNK = 64  # poses solved together: all their temporaries stay within a few MB
SAMPLE = 64  # poses of a sweep whose needs set the basis of the others
MARGIN = 1.1  # basis for the eigenvalue a sweep's sample needs times this


def _craig_bampton_sweep(topology: Topology, poses, n_modes: int, freqs: np.ndarray,
                         mechanism: np.ndarray) -> None:
    """``modal_sweep`` through ``CraigBamptonPlan``, all poses at once, filling ``freqs`` and
    ``mechanism``: one stack of reduced matrices (``CraigBamptonPlan.stacked``), one stacked
    eigen solve with the checks of a single solve (``stacked.stacked_modes``), and the
    truncation correction for every pose together; no model object is built per pose.

    The basis keeps every fixed-interface mode up to CUTOFF times the highest requested
    frequency. A sample spread over the sweep (every ceil(poses / SAMPLE)-th pose) is solved
    first, on the basis of CUTOFF^2 times the n_modes-th fixed-interface eigenvalue of all links
    together (a bound on what it needs: ``fixed_interface_bound``); the other poses are then
    solved on the basis the sample needs, with MARGIN to spare. Any pose whose highest requested
    frequency outgrows its basis (or with fewer elastic modes than requested, or whose
    truncation correction did not converge) is solved again, with the others like it, on a
    basis rebuilt for the largest of them. Every pose's answer thus comes from a basis that
    fits it."""
    if craig_bampton_refusal(topology):  # modal_sweep solves those on the full model
        raise AssertionError(craig_bampton_refusal(topology))
    poses = list(poses)
    if not poses:
        return
    fixed = layout(topology)
    model = pose_model(topology, poses[0], fixed)  # the plan's springs, masses, constraints
    angles, lengths = pose_geometry(topology, poses)
    if not np.all(lengths > 0):
        bad = int(np.argmax(~(lengths > 0).all(axis=1)))
        pose_model(topology, poses[bad], fixed, warn=False)  # raises, naming the link
    lambda_ref = np.min([s.EI / (s.mass_per_length * lengths[:, i] ** 4)
                         for i, s in enumerate(spec.section for spec in topology.links)], axis=0)
    lambda_cut = CUTOFF**2 * fixed_interface_bound(model.links, n_modes)
    sample = np.zeros(len(poses), dtype=bool)
    sample[::-(-len(poses) // SAMPLE)] = True
    todo, rest, plan = np.flatnonzero(sample), np.flatnonzero(~sample), None
    while todo.size:
        if plan is None or not plan.highest_kept <= lambda_cut < plan.reach:
            plan = CraigBamptonPlan(model, fixed, lambda_cut)
        elastic, n_mechanism, need, converged = _craig_bampton_poses(
            plan, angles[todo], lengths[todo], lambda_ref[todo], n_modes)
        fits = (need <= plan.reach) & converged
        freqs[todo[fits], :n_modes] = elastic[fits]
        mechanism[todo[fits]] = n_mechanism[fits]
        if rest is not None:  # the sample's needs set the basis of the other poses
            lambda_cut = MARGIN * need.max()
            todo, rest = np.concatenate([todo[~fits], rest]), None
        else:  # the basis for what is left: what it needs, 4 times as much if unconverged
            lambda_cut = max(MARGIN * need[~fits].max(initial=0.0),
                             4 * plan.reach if not converged.all() else 0.0)
            todo = todo[~fits]


def _craig_bampton_poses(plan: CraigBamptonPlan, angles, lengths, lambda_ref, n_modes: int):
    """``_craig_bampton_chunk`` for any number of poses, CHUNK at a time: the arrays of a whole
    cycle at once (10 MB and more) cost more in fresh memory pages than in arithmetic."""
    parts = [_craig_bampton_chunk(plan, angles[i:i + CHUNK], lengths[i:i + CHUNK],
                                  lambda_ref[i:i + CHUNK], n_modes)
             for i in range(0, len(angles), CHUNK)]
    return tuple(np.concatenate(column) for column in zip(*parts))


def _craig_bampton_chunk(plan: CraigBamptonPlan, angles, lengths, lambda_ref, n_modes: int):
    """(elastic frequencies [Hz] (poses, n_modes), NaN where fewer or not fitted; mechanism
    counts; the reach [rad^2/s^2] each pose needs of the basis, at the plan's link lengths;
    whether its truncation correction converged).

    A pose fits the basis when every truncated fixed-interface mode lies at least CUTOFF^2 times
    above its n_modes-th elastic eigenvalue, taken from the reduced pencil (an upper bound of
    the exact one: the reduction is a Ritz projection); at r times a link's reference length its
    fixed-interface eigenvalues are r^-2 (axial) or r^-4 (bending) times the reference ones, so
    the need is scaled up by the largest of r^2, r^4. Its truncation correction must also
    converge (``CONVERGED``; True where nothing was corrected). Needs are inf when fewer elastic
    modes were found and the basis is not yet complete, 0 once it is."""
    K, M = plan.stacked(angles, lengths)
    modes = stacked_modes(K, M, lambda_ref, checked=n_modes + SPARE_MODES,
                          factor=plan.mass_factor(M))
    n_mechanism = modes.mechanisms
    pick = n_mechanism[:, None] + np.arange(n_modes)
    found = pick < plan.n
    pick = np.minimum(pick, plan.n - 1)
    elastic = np.full(pick.shape, np.nan)
    if math.isinf(plan.reach):
        need = np.zeros(len(pick))
    else:
        highest = np.take_along_axis(modes.eigenvalues, pick[:, -1:], axis=1)[:, 0]
        r = lengths / plan.reference_lengths
        stretch = np.maximum(r**2, r**4).max(axis=1)
        need = np.where(found.all(axis=1), CUTOFF**2 * highest * stretch, math.inf)
    fits = need <= plan.reach
    converged = np.ones(len(need), dtype=bool)
    lam, change = corrected(plan, angles[fits], lengths[fits], modes.eigenvalues[fits],
                            modes.vectors[fits], pick[fits])
    if not math.isinf(plan.reach):  # else nothing is truncated
        converged[fits] = change.max(axis=1, initial=0.0) <= CONVERGED  # NaN is not
    elastic[fits] = np.where(found[fits], np.sqrt(np.clip(np.sort(lam, axis=1), 0.0, None))
                             / (2 * math.pi), np.nan)
    return elastic, n_mechanism, need, converged


def parallel_modal_sweep(topology: Topology, poses: Iterable[Mapping[str, tuple[float, float]]],
                         n_modes: int, solver: EigenSolver = SWEEP_SOLVER, n_jobs: int = -1,
                         reduction: Reduction | None = None) -> SweepResult:
    """``modal_sweep`` with the poses split into one contiguous chunk per worker
    (``parallel.run_tasks``: joblib processes, ``n_jobs`` = -1: one per core, or the dask
    cluster of ``parallel.use_scheduler``). Same result as the serial sweep for the full model;
    a Craig-Bampton chunk fits its basis to its own poses, so chunks agree with the serial sweep
    to the reduction's accuracy. Worth it from a few hundred full-model poses on; below that
    starting the workers costs more."""
    poses = list(poses)
    chunks = [c for c in np.array_split(np.arange(len(poses)), workers(n_jobs)) if len(c)]
    if not chunks:  # no poses: nothing to spread over workers
        return modal_sweep(topology, poses, n_modes, solver, reduction=reduction)
    parts = run_tasks(modal_sweep, [(topology, [poses[i] for i in chunk], n_modes, solver, None,
                                     reduction) for chunk in chunks], n_jobs=n_jobs)
    return SweepResult(frequencies=np.concatenate([p.frequencies for p in parts]),
                       mechanism_counts=np.concatenate([p.mechanism_counts for p in parts]),
                       note=parts[0].note)
