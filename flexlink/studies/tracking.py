"""Modes tracked through the crank cycle by their shapes, not by frequency order.

At each pose the modes are paired with the previous pose's tracked shapes by the MAC
(``analysis.mac``, in link frames with the pose-independent link-frame mass), so a tracked line
follows one shape as the poses change: where two modes' frequencies cross, the lines cross
instead of swapping shapes. A few modes more than the lines asked for are solved at every
pose, so a shape that climbs past a higher one can still be followed.

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

from flexlink.errors import InputError

from flexlink.analysis.identity import mode_identity
from flexlink.analysis.mac import link_frame, link_frame_mass, mac_matrix, pair_modes
from flexlink.analysis.modal import pose_modes
from flexlink.fe.model import layout
from flexlink.kinematics.linkage import crossings
from flexlink.parallel import on_cluster, run_tasks, workers
from flexlink.scene import Scene
from flexlink.studies.cycle import cycle_axes, kinematic_cycle, transmission_angles

SPARE = 2  # modes solved beyond the tracked lines at every pose
VEER_GAP = 0.1
VEER_MAC = 0.5


@dataclasses.dataclass(frozen=True)
class Event:
    """``kind`` ("crossing" or "veering") of tracked lines ``lines`` (1-based) at pose ``pose``
    (for a crossing: between ``pose - 1`` and ``pose``), ``gap``: relative frequency gap there."""

    kind: str
    lines: tuple[int, int]
    pose: int
    gap: float


@dataclasses.dataclass(frozen=True)
class Tracks:
    """frequencies[i, j] [Hz] and shapes[i][:, j] of tracked line j at pose i; mac[i, j]: MAC of
    that shape with the line's shape at pose i - 1 (1 at pose 0); rank[i, j]: its place in
    frequency order at pose i (0 = lowest elastic mode)."""

    frequencies: np.ndarray
    shapes: tuple[np.ndarray, ...]
    mac: np.ndarray
    rank: np.ndarray
    events: tuple[Event, ...]


def track(frequencies: np.ndarray, shapes, n_lines: int, W=None) -> Tracks:
    """Follow ``n_lines`` mode shapes through a sequence of poses.

    ``frequencies`` (P, m) [Hz], ascending per pose, NaN for modes not found; ``shapes``: P
    arrays (n, m) in coordinates comparable from pose to pose, weighted by ``W`` in the MAC.
    The lines start as the lowest ``n_lines`` modes of pose 0."""
    P, m = frequencies.shape
    if n_lines > m:
        raise ValueError(f"{n_lines} lines asked for from {m} modes per pose")
    index = np.zeros((P, n_lines), dtype=int)
    mac = np.ones((P, n_lines))
    index[0] = np.arange(n_lines)
    for i in range(1, P):
        found = np.flatnonzero(np.isfinite(frequencies[i]))
        previous = shapes[i - 1][:, index[i - 1]]
        pairs = pair_modes(np.nan_to_num(mac_matrix(previous, shapes[i][:, found], W)))
        index[i, pairs.a] = found[pairs.b]
        mac[i, pairs.a] = pairs.mac
    rows = np.arange(P)[:, None]
    f = frequencies[rows, index]
    kept = tuple(s[:, idx] for s, idx in zip(shapes, index))
    return Tracks(frequencies=f, shapes=kept, mac=mac, rank=index,
                  events=tuple(_events(f, kept, W)))


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
                          n_jobs=n_jobs, progress=progress is not None, label="pose chunks")
    freqs = np.concatenate([p[0] for p in parts])
    shapes = [U for p in parts for U in p[1]]
    mechanism = np.concatenate([p[2] for p in parts])
    W, labels = parts[0][3]
    tracks = track(freqs, shapes, n_modes, W)
    mu90 = {key: crossings(cycle.q, mu, math.pi / 2)
            for key, mu in transmission_angles(scene, cycle).items()}
    return TrackedMap(scene=scene.name, q=cycle.q, frequencies=tracks.frequencies,
                      tracks=tracks, mu90=mu90, labels=labels,
                      mechanism_counts=mechanism)


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
            first = (link_frame_mass(model), tuple(
                d["label"] for d in mode_identity(model, modes.shapes[:, elastic[:n_modes]])))
    return freqs, shapes, mechanism, first


def events_json(result: TrackedMap) -> list[dict]:
    """JSON-ready events: kind, lines (1-based), crank angle [deg], relative gap."""
    return [{"kind": e.kind, "lines": list(e.lines),
             "crank_deg": round(math.degrees(result.q[e.pose]) % 360.0, 3), "gap": e.gap}
            for e in result.tracks.events]


def tracked_csv(result: TrackedMap) -> str:
    """One row per pose: input angle [deg], tracked f1 ... fN [Hz], each line's MAC with the
    previous pose, and the events at that pose ("crossing 1-2; veering 2-3")."""
    n = result.frequencies.shape[1]
    at: dict[int, list[str]] = {}
    for e in result.tracks.events:
        at.setdefault(e.pose, []).append(f"{e.kind} {e.lines[0]}-{e.lines[1]}")
    lines = ["crank_angle_deg," + ",".join(f"f{j + 1}_Hz" for j in range(n)) + ","
             + ",".join(f"mac{j + 1}" for j in range(n)) + ",events"]
    for i, (q, row) in enumerate(zip(result.q, result.frequencies)):
        lines.append(f"{math.degrees(q):.6g}," + ",".join(f"{v:.8g}" for v in row) + ","
                     + ",".join(f"{v:.6f}" for v in result.tracks.mac[i]) + ","
                     + "; ".join(at.get(i, [])))
    return "\n".join(lines) + "\n"


def plot_tracked(result: TrackedMap, path, crank_speed: float | None = None, hits=()) -> None:
    """PNG of the tracked lines against crank angle (as ``cycle.plot_map``), with each line's
    label, crossings marked x and veerings o, the poses where mu = 90 deg and the resonating
    harmonics (``hits``: ``cycle.Resonance``) as dashes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.8))
    deg = np.degrees(result.q)
    f = result.frequencies
    for j in range(f.shape[1]):
        label = f"mode {j + 1}" + (f": {result.labels[j]}" if j < len(result.labels) else "")
        ax.plot(deg, f[:, j], label=label)
    for kind, marker in (("crossing", "x"), ("veering", "o")):
        events = [e for e in result.tracks.events if e.kind == kind]
        if events:
            x = [deg[e.pose] for e in events]
            y = [f[e.pose, [e.lines[0] - 1, e.lines[1] - 1]].mean() for e in events]
            ax.scatter(x, y, marker=marker, s=60, color="k", facecolors="none" if marker == "o"
                       else None, zorder=3, label=kind)
    cycle_axes(ax, deg, result.mu90, hits, result.scene + " (modes tracked by MAC)" + (
        f", crank {crank_speed * 60 / (2 * math.pi):g} rev/min" if crank_speed else ""))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
