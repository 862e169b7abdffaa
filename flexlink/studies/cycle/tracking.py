"""Modes tracked through the crank cycle by their shapes, not by frequency order.

At each pose the modes are paired with the previous pose's tracked shapes by the MAC
(``analysis.mac``, in link frames with the pose-independent link-frame mass), so a tracked line
follows one shape as the poses change: where two modes' frequencies cross, the lines cross
instead of swapping shapes.

The lines at every pose are the lowest ``n`` elastic modes there, in some order: no line ever
leaves them, so the lowest mode is never lost and the tracked map holds at each pose the same
frequencies as the sorted one. A few spare modes are solved at every pose to see a shape
climb out of the lowest ``n``: that line is handed the mode that comes down into them, and
the pose is flagged.

Singular poses (a dead centre, a change point's flat pose, where mechanism modes appear or the
assembly branch can change) are where the shapes change too fast to pair: a line whose best
MAC is below ``PAIR_MAC`` (with mass-orthonormal modes, MAC >= 0.5 makes the pairing unique), or
a pose whose count of mechanism modes differs. There the lines are re-seeded by frequency
order (the line that was k-th lowest takes the k-th lowest mode), the pose is flagged, and the
next poses are paired with the last clear pose before it, so the tracking goes through.

After a full turn the map should come back to its start (``periodicity``): the lines of the
last pose paired with those of the first one by the MAC.

Events along a pair of tracked lines:
  - crossing: their frequencies change order between two poses;
  - veering: their frequencies come within ``VEER_GAP`` (relative) of each other without
    crossing, at a local minimum of the gap, and the shapes change there: the line's shape
    well before and well after (where the gap is back to twice its minimum) has a MAC below
    ``VEER_MAC``. The line itself follows the continuously changing shape through the veering.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexlink.errors import InputError, KinematicsError, NumericalError

from flexlink.analysis.identity import mode_identity
from flexlink.analysis.mac import link_frame, link_frame_mass, mac_matrix, pair_modes
from flexlink.analysis.modal import pose_modes
from flexlink.fe.model import layout
from flexlink.kinematics.linkage import crossings
from flexlink.parallel import on_cluster, run_tasks, workers
from flexlink.scene import Scene
from flexlink.studies.cycle.modal_map import kinematic_cycle, transmission_angles

SPARE = 2  # modes solved beyond the tracked lines at every pose
VEER_GAP = 0.1
VEER_MAC = 0.5
PAIR_MAC = 0.5  # a line paired below this is ambiguous: the pose is singular
THROUGH = 3  # poses paired with the last clear one before a fresh start is taken


@dataclasses.dataclass(frozen=True)
class Event:
    """``kind`` ("crossing" or "veering") of tracked lines ``lines`` (1-based) at pose ``pose``
    (for a crossing: between ``pose - 1`` and ``pose``), ``gap``: relative frequency gap there."""

    kind: str
    lines: tuple[int, int]
    pose: int
    gap: float


@dataclasses.dataclass(frozen=True)
class Reseed:
    """Tracked lines ``lines`` (1-based) re-seeded at pose ``pose``: ``reason`` says why (a
    singular pose, or a shape leaving the lowest modes); ``vanishing``: the lines whose mode
    turns into a mechanism mode there, so that their frequency falls to 0 Hz near the pose."""

    pose: int
    lines: tuple[int, ...]
    reason: str
    vanishing: tuple[int, ...] = ()  # lines whose mode becomes a mechanism (0 Hz) here


@dataclasses.dataclass(frozen=True)
class Periodicity:
    """How the map closes after a full turn: ``permutation[j]``, the line (0-based) whose start
    shape line j's end shape pairs with, ``mac[j]`` of that pair, ``step[j]`` the relative
    frequency step of line j from the last pose to the first; ``closes`` when every line comes
    back to itself with MAC >= ``PAIR_MAC``; ``note`` says why not."""

    closes: bool
    permutation: tuple[int, ...]
    mac: np.ndarray
    step: np.ndarray
    note: str


@dataclasses.dataclass(frozen=True)
class Tracks:
    """frequencies[i, j] [Hz] and shapes[i][:, j] of tracked line j at pose i; mac[i, j]: MAC of
    that shape with the line's shape at the pose it was paired with (1 at pose 0); rank[i, j]:
    its place in frequency order at pose i (0 = lowest elastic mode); ``reseeds``: the poses
    where lines were re-seeded."""

    frequencies: np.ndarray
    shapes: tuple[np.ndarray, ...]
    mac: np.ndarray
    rank: np.ndarray
    events: tuple[Event, ...]
    reseeds: tuple[Reseed, ...] = ()


def track(frequencies: np.ndarray, shapes, n_lines: int, W=None, mechanism=None) -> Tracks:
    """Follow ``n_lines`` mode shapes through a sequence of poses.

    ``frequencies`` (P, m) [Hz], ascending per pose, NaN for modes not found; ``shapes``: P
    arrays (n, m) in coordinates comparable from pose to pose, weighted by ``W`` in the MAC;
    ``mechanism`` (P,): rigid-body/mechanism modes found per pose (a change marks a singular
    pose). The lines start as the lowest ``n_lines`` modes of pose 0 and hold the lowest
    ``n_lines`` modes at every pose (see the module docstring)."""
    P, m = frequencies.shape
    if n_lines > m:
        raise ValueError(f"{n_lines} lines asked for from {m} modes per pose")
    mechanism = np.zeros(P, dtype=int) if mechanism is None else np.asarray(mechanism)
    index = np.zeros((P, n_lines), dtype=int)
    mac = np.ones((P, n_lines))
    index[0] = np.arange(n_lines)
    reseeds, clear = [], 0  # clear: the last pose paired without ambiguity
    for i in range(1, P):
        found = np.flatnonzero(np.isfinite(frequencies[i]))
        if len(found) < n_lines:
            raise NumericalError(f"{n_lines} modes tracked, but pose {i} has only {len(found)}: "
                                 "ask for fewer modes or use more elements per link")
        reasons = []
        for r in [clear] if clear == i - 1 else [clear, i - 1]:
            M = np.nan_to_num(mac_matrix(shapes[r][:, index[r]], shapes[i][:, found], W))
            pairs = pair_modes(M)
            reasons.append(_ambiguous(pairs.mac, mechanism[r], mechanism[i]))
            if reasons[-1] is None:
                break
        why = reasons[0] if reasons[-1] is not None else None
        if why is None:
            index[i], mac[i], left = _kept(pairs, M, found, n_lines)
            clear = i
            if left:
                reseeds.append(Reseed(i, left, (
                    f"the shape of line{'s' if len(left) > 1 else ''} "
                    f"{', '.join(map(str, left))} leaves the lowest {n_lines} modes: handed the "
                    "mode that comes down into them")))
        else:  # re-seed by frequency order, from the last clear pose
            r = clear
            order = np.argsort(frequencies[r, index[r]], kind="stable")
            index[i, order] = found[:n_lines]
            mac[i] = np.diag(np.nan_to_num(mac_matrix(shapes[r][:, index[r]],
                                                      shapes[i][:, index[i]], W)))
            new = max(0, int(mechanism[i]) - int(mechanism[r]))
            vanishing = tuple(sorted(int(j) + 1 for j in order[:new]))
            if vanishing:  # the near-mechanism modes are the lowest before the pose
                why += (f" (line {', '.join(map(str, vanishing))} turns into it: its frequency "
                        "falls to 0 Hz approaching this pose, below every sampled value)")
            reseeds.append(Reseed(i, tuple(range(1, n_lines + 1)),
                                  why + "; lines re-seeded by frequency order", vanishing))
            if i - clear >= THROUGH:  # the singular stretch is long: start afresh from here
                clear = i
    rows = np.arange(P)[:, None]
    f = frequencies[rows, index]
    kept = tuple(s[:, idx] for s, idx in zip(shapes, index))
    return Tracks(frequencies=f, shapes=kept, mac=mac, rank=index,
                  events=tuple(_events(f, kept, W)), reseeds=tuple(reseeds))


def _ambiguous(paired: np.ndarray, mechanism_before: int, mechanism_now: int) -> str | None:
    """Why a pairing cannot be trusted (None if it can)."""
    if mechanism_now != mechanism_before:
        return (f"singular pose: {mechanism_now} rigid-body/mechanism mode"
                f"{'s' if mechanism_now != 1 else ''} where the pose before had "
                f"{mechanism_before}")
    if paired.min() < PAIR_MAC:
        j = int(np.argmin(paired))
        return (f"singular pose: the shapes change too fast to pair (line {j + 1}'s best MAC "
                f"{paired[j]:.3f} < {PAIR_MAC})")
    return None


def _kept(pairs, M: np.ndarray, found: np.ndarray, n_lines: int):
    """(mode index per line, MAC per line, lines handed over): lines paired with a spare mode
    (beyond the lowest ``n_lines``) take the lowest modes left unpaired, in frequency order.
    ``M``: the lines' MAC with the ``found`` modes."""
    column = np.array(pairs.b)
    out = [int(j) for j in np.flatnonzero(column >= n_lines)]
    free = [k for k in range(n_lines) if k not in set(column)]
    for j, k in zip(out, free):
        column[j] = k
    return found[column], M[np.arange(len(column)), column], tuple(j + 1 for j in out)


def periodicity(tracks: Tracks, W=None, closed_pose: bool = True, why_open: str = "") -> Periodicity:
    """Pair the lines' shapes at the last pose with those at the first (the step that closes a
    full turn). ``closed_pose``: whether the linkage itself comes back to its start pose;
    ``why_open`` says why not."""
    first, last = tracks.shapes[0], tracks.shapes[-1]
    pairs = pair_modes(np.nan_to_num(mac_matrix(last, first, W)))
    perm = tuple(int(b) for b in pairs.b)
    f0, f1 = tracks.frequencies[0], tracks.frequencies[-1]
    step = np.abs(f1 - f0) / f0
    closes = closed_pose and perm == tuple(range(len(perm))) and pairs.mac.min() >= PAIR_MAC
    if closes:
        note = (f"the tracked map closes after one turn: every line's shape at the last pose "
                f"pairs with its own at the first (MAC >= {pairs.mac.min():.3f}); largest "
                f"frequency step {100 * step.max():.2g} %")
    elif not closed_pose:
        note = (f"the tracked map does not close after one turn: {why_open}; the frequencies "
                f"step by at most {100 * step.max():.2g} % from the last pose to the first, the "
                f"shapes pair with MAC down to {pairs.mac.min():.2f}")
    elif perm != tuple(range(len(perm))):
        moved = ", ".join(f"line {j + 1} ends as line {b + 1} began" for j, b in enumerate(perm)
                          if b != j)
        note = f"the tracked map closes only up to a permutation of its lines: {moved}"
    else:
        j = int(np.argmin(pairs.mac))
        note = (f"the tracked map does not close after one turn: line {j + 1}'s shape at the "
                f"last pose pairs with its start shape with MAC {pairs.mac[j]:.2f} only "
                "(too few poses for the shapes' changes?)")
    return Periodicity(closes, perm, pairs.mac, step, note)


def _events(f: np.ndarray, shapes, W) -> list[Event]:
    P, n = f.shape
    found = []
    for a in range(n):
        for b in range(a + 1, n):
            d = f[:, b] - f[:, a]
            gap = np.abs(d) / np.minimum(f[:, a], f[:, b])
            sign = np.sign(d)
            for i in range(1, P):  # a pose exactly at the crossing takes the sign before it
                sign[i] = sign[i] or sign[i - 1]
            flips = np.flatnonzero(sign[1:] * sign[:-1] < 0) + 1
            found += [Event("crossing", (a + 1, b + 1), int(i), float(gap[i])) for i in flips]
            for i in range(1, P - 1):
                if not (gap[i] < VEER_GAP and gap[i] <= gap[i - 1] and gap[i] < gap[i + 1]):
                    continue
                if any(abs(i - k) <= 1 for k in flips):
                    continue
                lo, hi = i, i
                while lo > 0 and gap[lo] < 2 * gap[i]:
                    lo -= 1
                while hi < P - 1 and gap[hi] < 2 * gap[i]:
                    hi += 1
                change = mac_matrix(shapes[lo][:, [a]], shapes[hi][:, [a]], W)[0, 0]
                if change < VEER_MAC:
                    found.append(Event("veering", (a + 1, b + 1), i, float(gap[i])))
    return sorted(found, key=lambda e: (e.pose, e.lines))


@dataclasses.dataclass(frozen=True)
class TrackedMap:
    """The modal map of ``cycle.ModalMap`` with lines tracked by shape: frequencies[i, j] [Hz]
    of line j at input angle q[i] [rad], ``tracks`` with the MAC and events; mu90 as there."""

    scene: str
    q: np.ndarray
    frequencies: np.ndarray
    tracks: Tracks
    mu90: dict[str, np.ndarray]
    labels: tuple[str, ...] = ()  # each line's identity label at the first pose
    mechanism_counts: np.ndarray | None = None  # rigid-body/mechanism modes found per pose
    periodicity: Periodicity | None = None
    unsampled: tuple[float, ...] = ()  # dead centres [rad] between the sampled poses


def tracked_map(scene: Scene, n_poses: int = 360, n_modes: int = 3,
                elements_per_link: int | None = None, progress=None,
                n_jobs: int = 1) -> TrackedMap:
    """The first ``n_modes`` elastic modes over the cycle, each line tracked by its shape; the
    full model of ``analysis.modal.pose_modes`` at every pose (the same as `flexlink modes`).

    ``n_jobs`` = 1 solves the poses in this process (``progress`` wraps them); otherwise, or
    on the cluster of ``parallel.use_scheduler``, the poses go out in contiguous chunks through
    ``parallel.run_tasks`` (``progress`` then only switches its bar on). Every pose is solved
    on its own, so the result is the same whatever the chunks; the tracking runs here."""
    cycle = kinematic_cycle(scene, n_poses)
    topology = scene.topology(elements_per_link)
    k = n_modes + SPARE
    try:  # spare lines help the tracking, but a model with only n_modes modes still tracks
        pose_modes(topology, cycle.states[0].points, k)
    except InputError:
        k = n_modes  # and if even these are too many, the first pose below says so
    points = [state.points for state in cycle.states]
    if n_jobs == 1 and not on_cluster():
        parts = [_pose_lines(topology, points, k, n_modes, progress)]
    else:
        chunks = np.array_split(np.arange(len(points)),
                                min(len(points), CHUNKS_PER_WORKER * workers(n_jobs)))
        parts = run_tasks(_pose_lines, [(topology, [points[i] for i in chunk], k, n_modes)
                                        for chunk in chunks],
                          n_jobs=n_jobs, show_progress=progress is not None, label="pose chunks")
    freqs = np.concatenate([p[0] for p in parts])
    shapes = [U for p in parts for U in p[1]]
    mechanism = np.concatenate([p[2] for p in parts])
    W, labels = parts[0][3]
    mu = transmission_angles(scene, cycle)
    tracks = track(freqs, shapes, n_modes, W, mechanism)
    tracks = dataclasses.replace(tracks, reseeds=tuple(
        dataclasses.replace(r, reason=r.reason.replace("singular pose", "singular pose"
                                                       + _dead_centres(mu, r.pose), 1))
        for r in tracks.reseeds))
    mu90 = {key: crossings(cycle.q, values, math.pi / 2) for key, values in mu.items()}
    back, why = _back_at_start(scene, cycle, tracks)
    return TrackedMap(scene=scene.name, q=cycle.q, frequencies=tracks.frequencies,
                      tracks=tracks, mu90=mu90, labels=labels,
                      mechanism_counts=mechanism,
                      periodicity=periodicity(tracks, W, back, why),
                      unsampled=_unsampled_dead_centres(scene, cycle.q))


def _unsampled_dead_centres(scene: Scene, q: np.ndarray) -> tuple[float, ...]:
    """A four-bar's dead centres (``FourBar.dead_centres``) that no sampled pose lands on: a
    mode may fall towards 0 Hz there without any pose showing it."""
    if scene.four_bar is None:
        return ()
    sampled = np.remainder(q, 2 * math.pi)
    step = 2 * math.pi / len(q)
    return tuple(a for a in scene.four_bar.dead_centres()
                 if np.min(np.abs(np.remainder(sampled - a + math.pi, 2 * math.pi) - math.pi))
                 > 1e-9 * step)


def unsampled_note(result: TrackedMap) -> str | None:
    """A sentence on the dead centres between sampled poses, or None."""
    if not result.unsampled:
        return None
    where = ", ".join(f"{math.degrees(a):.3f}" for a in result.unsampled)
    return (f"dead centre at crank {where} deg lies between the sampled poses: a mode may fall "
            "towards 0 Hz there (a mechanism mode at the pose itself) without any pose showing "
            "it; choose --poses so that a pose lands on it")


DEAD_CENTRE_DEG = 1.0  # a transmission angle this close to 0 or 180 deg is named at a reseed
CLOSED_POSE = 1e-6  # joints back within this fraction of the largest body: the pose closes


def _dead_centres(mu: dict[str, np.ndarray], pose: int) -> str:
    """" (dead centre: mu pair = 180.0 deg)" for the transmission angles near a dead centre at
    ``pose``, else ""."""
    near = [f"mu {pair} = {math.degrees(v[pose]):.1f} deg" for pair, v in mu.items()
            if min(v[pose], math.pi - v[pose]) < math.radians(DEAD_CENTRE_DEG)]
    return f" (dead centre: {', '.join(near)})" if near else ""


def _back_at_start(scene: Scene, cycle, tracks: Tracks) -> tuple[bool, str]:
    """Whether the linkage comes back to its start pose after one turn, continued from the
    last pose as the cycle continues every pose, and if not, why (a sentence)."""
    last = cycle.states[-1]
    h = cycle.q[0] + 2 * math.pi - last.q
    moving = scene.linkage.moving
    guess = {j: np.asarray(last.points[j]) + last.dpoints[j] * h + 0.5 * last.ddpoints[j] * h * h
             for j in moving}
    try:
        end = scene.linkage.solve(cycle.q[0] + 2 * math.pi, guess)
    except KinematicsError as exc:
        return False, f"the linkage cannot be continued to the start angle ({exc})"
    gaps = {j: math.dist(end.points[j], cycle.states[0].points[j]) for j in moving}
    worst = max(gaps, key=gaps.get)
    if gaps[worst] <= CLOSED_POSE * scene.linkage.size:
        return True, ""
    singular = {round(math.degrees(cycle.q[r.pose]) % 360.0, 1) for r in tracks.reseeds
                if "mechanism" in r.reason or "dead centre" in r.reason}
    if scene.four_bar is not None:  # sampled or not
        singular |= {round(math.degrees(a), 1) for a in scene.four_bar.dead_centres()}
    singular = sorted(singular)
    where = (f"; it passed {'a singular pose' if len(singular) == 1 else 'singular poses'} "
             f"at crank {', '.join(f'{a:g}' for a in singular)} deg, where the assembly branch "
             "can change") if singular else ""
    return False, (f"the linkage does not come back to its start pose after one turn (joint "
                   f"{worst} ends {1e3 * gaps[worst]:.1f} mm from where it began){where}")


CHUNKS_PER_WORKER = 4  # chunks of poses per worker: a slow chunk holds up less of the map


def _pose_lines(topology, points, k: int, n_modes: int, progress=None):
    """(frequencies [Hz] (poses, k), NaN where fewer; link-frame shapes per pose; mechanism
    modes per pose; (link-frame mass matrix, the first ``n_modes`` lines' labels) at the first
    pose) of the poses ``points`` (joint name -> (x, y) [m])."""
    freqs = np.full((len(points), k), np.nan)
    shapes, first = [], None
    mechanism = np.zeros(len(points), dtype=int)
    layout(topology)  # warm the cache once
    for i, pose in enumerate(progress(points) if progress else points):
        model, modes, _ = pose_modes(topology, pose, k)
        elastic = modes.elastic[:k]
        mechanism[i] = len(modes.kinds) - len(modes.elastic)
        freqs[i, :len(elastic)] = modes.frequencies[elastic]
        U = np.zeros((model.n_dofs, k))
        U[:, :len(elastic)] = link_frame(model, modes.shapes[:, elastic])
        shapes.append(U)
        if first is None:
            first = (link_frame_mass(model),
                     mode_identity(model, modes.shapes[:, elastic[:n_modes]]).labels)
    return freqs, shapes, mechanism, first


def vanishing_lines(result: TrackedMap) -> tuple[int, ...]:
    """Lines (1-based) whose mode turns into a mechanism mode at some singular pose: their
    frequency reaches 0 Hz in the cycle, whatever the sampled poses show."""
    return tuple(sorted({j for r in result.tracks.reseeds for j in r.vanishing}))
