"""Pictures of mode shapes with pyvista, rendered off screen (no display needed): per mode the
undeformed linkage in grey and the deformed one coloured by displacement magnitude, joints as
markers, the frequency in the title; and one overview sheet of all modes. Functions return PNG
bytes; the caller writes them (``fileio.write_atomic``).

Off screen without a display, VTK's wheels render through EGL with Mesa's software rasterizer
(Debian packages libegl1, libegl-mesa0, libgl1-mesa-dri: ``scripts/system-deps.sh``). VTK would
first try an X display and log a warning, so without one we ask for EGL directly.
"""

from __future__ import annotations

import dataclasses
import functools
import io
import math
import os
import re
import subprocess
import sys

import numpy as np

from flexlink.errors import OutputError
from flexlink.output.export_vtk import ModeSet

UNDEFORMED = "#9a9a9a"
GROUND_LINE = "#4a4a4a"
SPRING = "#d62728"
COLORMAP = "viridis"
MODE_SIZE = (1200, 800)  # [px] one mode
SHEET_TILE = (800, 520)  # [px] one mode on the overview sheet


# Rendered in a child process first: without an OpenGL library VTK crashes the process
# (segmentation fault) instead of raising, which would take the caller down with it.
_PROBE = """
import sys, pyvista
plotter = pyvista.Plotter(off_screen=True, window_size=[32, 32])
plotter.add_mesh(pyvista.Sphere())
sys.exit(0 if plotter.screenshot(return_img=True).std() > 0 else 3)
"""


@functools.cache
def _check_rendering() -> None:
    try:
        probe = subprocess.run([sys.executable, "-c", _PROBE], capture_output=True, text=True,
                               timeout=300)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise OutputError(f"cannot start the off-screen rendering check: {exc}") from None
    if probe.returncode != 0:
        last = re.sub(r"\x1b\[[0-9;]*m", "", (probe.stderr.strip().splitlines() or ["-"])[-1])
        last = last.split("| ")[-1]  # VTK's log prefix
        how = (f"crashed with signal {-probe.returncode}" if probe.returncode < 0
               else f"exited with {probe.returncode}")
        raise OutputError(
            f"pyvista cannot render off screen here (check {how}: {last}); without a display "
            "it needs EGL and Mesa: run bash scripts/system-deps.sh (Debian packages libegl1 "
            "libegl-mesa0 libgl1-mesa-dri), or use --no-pictures")


def _pyvista():
    if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    _check_rendering()
    import pyvista

    return pyvista


def _polylines(pv, points: np.ndarray, groups: list[np.ndarray], scalars=None, z: float = 0.0):
    """PolyData of one poly-line per group of point indices, points (P, 2) padded to ``z``."""
    cells = np.concatenate([np.concatenate([[len(g)], g]) for g in groups])
    mesh = pv.PolyData(np.column_stack([points, np.full(len(points), z)]), lines=cells)
    if scalars is not None:
        mesh.point_data["relative |u|"] = scalars
    return mesh


def _link_groups(modes: ModeSet) -> list[np.ndarray]:
    s = modes.sampled
    groups = []
    for link in range(len(s.link_names)):
        cells = s.cells[s.cell_link == link]
        groups.append(np.concatenate([cells[:, :-1].ravel(), cells[-1:, -1]]))
    return groups


@dataclasses.dataclass(frozen=True)
class JointSpring:
    """One spring of joint ``name`` as drawn: from ``start`` to ``end`` [m, drawing], both
    displaced, except a ground bearing's ``start``, the fixed pivot."""

    name: str
    ground: bool
    start: np.ndarray
    end: np.ndarray


def joint_springs(modes: ModeSet, i: int, factor: float) -> list[JointSpring]:
    """The joint springs of mode i with the shape drawn ``factor`` times [sqrt(kg)]: a pin's
    from its first link end to each other one, a bearing's from the pivot to each link end
    (the springs of ``fe/model.py``). A spring's length is the joint's drawn stretch."""
    s = modes.sampled
    drawn = s.points + factor * s.displacement[:, :, i]
    springs = []
    for joint in modes.joints:
        start = np.array(joint.position) if joint.ground else drawn[joint.points[0]]
        ends = joint.points if joint.ground else joint.points[1:]
        springs += [JointSpring(joint.name, joint.ground, start, drawn[p]) for p in ends]
    return springs


def zigzag(start: np.ndarray, end: np.ndarray, width: float, teeth: int = 6) -> np.ndarray:
    """(2 teeth + 3, 2) points of a spring symbol from ``start`` to ``end``: straight lead-ins,
    then ``teeth`` zig-zags of half-width at most ``width`` [m] (narrower on a short spring, so
    it stays a zig-zag, not a bar across the line)."""
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    along = end - start
    length = float(np.linalg.norm(along))
    normal = (np.array([-along[1], along[0]]) / length) if length > 0 else np.zeros(2)
    half = min(width, 0.4 * length)
    t = np.concatenate([[0.0], np.linspace(0.15, 0.85, 2 * teeth + 1), [1.0]])
    side = np.zeros(len(t))
    side[1:-1] = [0.0] + [(-1.0) ** k for k in range(2 * teeth - 1)] + [0.0]
    return start + t[:, None] * along + (half * side)[:, None] * normal


@dataclasses.dataclass(frozen=True)
class ScaleBar:
    """A bar ``length`` [m] long in the drawing; the displacement it stands for,
    ``length / factor`` [m/sqrt(kg)] of the mass-normalised shape (phi^T M phi = 1), drawn
    ``factor`` [sqrt(kg)] times."""

    length: float
    factor: float

    @property
    def displacement(self) -> float:
        """The mass-normalised displacement the bar stands for [m/sqrt(kg)]."""
        return self.length / self.factor

    def labels(self) -> tuple[str, str]:
        """(above the bar, below it)."""
        return (f"{_length(self.length)} of the linkage",
                f"= {_length(self.displacement)}/sqrt(kg) of the mass-normalised shape")


def _length(metres: float) -> str:
    return f"{metres:.3g} m" if metres >= 1 else f"{1e3 * metres:.3g} mm"


def scale_bar(modes: ModeSet, i: int, fraction: float) -> ScaleBar:
    """A bar of a round length (1, 2 or 5 times a power of ten) near a fifth of the mechanism
    size, with mode i's drawing factor (``ModeSet.scale``)."""
    target = 0.2 * modes.size
    power = 10.0 ** math.floor(math.log10(target))
    length = max(m * power for m in (1, 2, 5) if m * power <= target)
    return ScaleBar(length=length, factor=modes.scale(i, fraction))


def _draw_springs(pv, plotter, modes: ModeSet, springs: list[JointSpring], line: float) -> None:
    pieces = [zigzag(sp.start, sp.end, 0.012 * modes.size) for sp in springs
              if np.linalg.norm(sp.end - sp.start) > 1e-9 * modes.size]
    if pieces:
        points = np.vstack(pieces)
        groups, first = [], 0
        for piece in pieces:
            groups.append(np.arange(first, first + len(piece)))
            first += len(piece)
        plotter.add_mesh(_polylines(pv, points, groups, z=modes.size * 0.02), color=SPRING,
                         line_width=max(1.5, line * 0.6))


def _draw_scale_bar(pv, plotter, modes: ModeSet, bar: ScaleBar, bounds: np.ndarray,
                    font_size: int) -> None:
    (x0, y0), (x1, y1) = bounds
    y = y0 - 0.1 * modes.size
    ends = np.array([[x1 - bar.length, y], [x1, y]])
    tick = 0.015 * modes.size
    ticks = np.array([[x1 - bar.length, y - tick], [x1 - bar.length, y + tick],
                      [x1, y - tick], [x1, y + tick]])
    plotter.add_mesh(_polylines(pv, np.vstack([ends, ticks]),
                                [np.arange(2), np.arange(2, 4), np.arange(4, 6)]),
                     color="black", line_width=3)
    above, below = bar.labels()
    spots = np.array([[x1 - bar.length / 2, y + 0.045 * modes.size, 0.0],
                      [x1 - bar.length / 2, y - 0.045 * modes.size, 0.0]])
    plotter.add_point_labels(spots, [above, below], font_size=max(8, int(font_size * 0.8)),
                             text_color="black", shape=None, show_points=False,
                             always_visible=True, justification_horizontal="center",
                             justification_vertical="center")


def _draw_mode(pv, plotter, title: str, modes: ModeSet, i: int, fraction: float,
               font_size: int) -> None:
    s = modes.sampled
    groups = _link_groups(modes)
    disp = s.displacement[:, :, i]
    magnitude = np.linalg.norm(disp, axis=1)
    peak = magnitude.max()
    relative = magnitude / peak if peak > 0 else magnitude
    factor = modes.scale(i, fraction)
    deformed = s.points + factor * disp
    line = max(2.0, font_size / 4)

    ground = [j for j in modes.joints if j.ground]
    if len(ground) >= 2:  # the frame, between consecutive ground pivots
        base = np.array([j.position for j in ground], dtype=float)
        plotter.add_mesh(_polylines(pv, base, [np.arange(len(base))]), color=GROUND_LINE,
                         line_width=line / 2)
    plotter.add_mesh(_polylines(pv, s.points, groups), color=UNDEFORMED, line_width=line,
                     render_lines_as_tubes=True)
    plotter.add_mesh(_polylines(pv, deformed, groups, relative), scalars="relative |u|",
                     cmap=COLORMAP, clim=(0.0, 1.0), line_width=line * 2.5,
                     render_lines_as_tubes=True,
                     scalar_bar_args={"title": "relative displacement", "color": "black",
                                      "vertical": True, "position_x": 0.88, "position_y": 0.2,
                                      "height": 0.6, "width": 0.06, "fmt": "%.1f",
                                      "title_font_size": font_size, "label_font_size": font_size})
    springs = joint_springs(modes, i, factor)
    _draw_springs(pv, plotter, modes, springs, line)
    # markers and labels sit in front of the tubes (the camera looks down the z axis)
    front = modes.size * 0.05
    marker = font_size * 1.1
    if ground:  # squares: bearings, at the fixed pivots
        pivots = np.array([j.position for j in ground], dtype=float)
        plotter.add_points(np.column_stack([pivots, np.full(len(pivots), front)]), color="black",
                           point_size=marker, render_points_as_spheres=False)
    pins = [deformed[j.points[0]] for j in modes.joints if not j.ground and j.points]
    if pins:  # discs: pins between links, on the displaced link end the others hang from
        pins = np.array(pins)
        plotter.add_points(np.column_stack([pins, np.full(len(pins), front)]), color=SPRING,
                           point_size=marker * 0.8, render_points_as_spheres=True)
    names = [j.name for j in modes.joints]
    xy = np.array([j.position for j in modes.joints], dtype=float).reshape(-1, 2)
    away = xy - xy.mean(axis=0)
    away /= np.maximum(np.linalg.norm(away, axis=1, keepdims=True), 1e-300)
    labels = np.column_stack([xy + 0.045 * modes.size * away, np.full(len(xy), front)])
    plotter.add_point_labels(labels, names, font_size=font_size, text_color="black",
                             shape=None, show_points=False, always_visible=True,
                             justification_horizontal="center",
                             justification_vertical="center")
    everything = np.vstack([s.points, deformed, xy])
    _draw_scale_bar(pv, plotter, modes, scale_bar(modes, i, fraction),
                    np.array([everything.min(axis=0), everything.max(axis=0)]), font_size)
    plotter.add_text(title, position="upper_edge", font_size=font_size, color="black")
    plotter.add_text(f"grey: rest pose;  colour: mode shape drawn x{factor:.3g} sqrt(kg) "
                     f"(largest displacement {100 * fraction:g} % of the mechanism size);  "
                     "red zig-zags: joint springs", position="lower_left",
                     font_size=max(7, int(font_size * 0.7)), color="#333333")
    plotter.set_background("white")
    plotter.view_xy()
    plotter.enable_parallel_projection()
    plotter.reset_camera()
    plotter.camera.zoom(1.05)


def _png(image: np.ndarray) -> bytes:
    from PIL import Image

    if float(image.std()) == 0.0:
        raise OutputError("off-screen rendering gave a blank image: is EGL/Mesa installed? "
                          "(bash scripts/system-deps.sh)")
    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()


def _screenshot(plotter) -> np.ndarray:
    try:
        return plotter.screenshot(return_img=True)
    finally:
        plotter.close()


def mode_picture(title: str, modes: ModeSet, i: int, fraction: float,
                 size: tuple[int, int] = MODE_SIZE) -> bytes:
    """PNG of mode i: ``title`` on top, the joints of ``modes`` (bearings as squares at their
    pivots, pins as discs, every joint spring a zig-zag between its displaced ends), a scale
    bar; the shape scaled so its largest displacement is ``fraction`` of the mechanism size.
    ``size`` [px] (width, height)."""
    pv = _pyvista()
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    _draw_mode(pv, plotter, title, modes, i, fraction,
               font_size=max(10, size[1] // 50))
    return _png(_screenshot(plotter))


def overview_sheet(name: str, modes: ModeSet, fraction: float, tile: tuple[int, int] = SHEET_TILE) -> bytes:
    """PNG with every mode of ``modes`` side by side, two or three per row."""
    pv = _pyvista()
    n = len(modes.numbers)
    cols = 2 if n <= 4 else 3
    rows = math.ceil(n / cols)
    plotter = pv.Plotter(off_screen=True, shape=(rows, cols), border=False,
                         window_size=[tile[0] * cols, tile[1] * rows])
    for i in range(n):
        plotter.subplot(i // cols, i % cols)
        _draw_mode(pv, plotter, f"{name}: mode {modes.numbers[i]}, {modes.frequencies[i]:.1f} Hz",
                   modes, i, fraction, font_size=max(10, tile[1] // 40))
    for j in range(n, rows * cols):
        plotter.subplot(j // cols, j % cols)
        plotter.set_background("white")
    return _png(_screenshot(plotter))
