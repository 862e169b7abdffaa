"""Pictures of mode shapes with pyvista, rendered off screen (no display needed): per mode the
undeformed linkage in grey and the deformed one coloured by displacement magnitude, joints as
markers, the frequency in the title; and one overview sheet of all modes. Functions return PNG
bytes; the caller writes them (``fileio.write_atomic``).

Off screen without a display, VTK's wheels render through EGL with Mesa's software rasterizer
(Debian packages libegl1, libegl-mesa0, libgl1-mesa-dri: ``scripts/system-deps.sh``). VTK would
first try an X display and log a warning, so without one we ask for EGL directly.
"""

from __future__ import annotations

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


def _polylines(pv, points: np.ndarray, groups: list[np.ndarray], scalars=None):
    """PolyData of one poly-line per group of point indices, points (P, 2) padded to z = 0."""
    cells = np.concatenate([np.concatenate([[len(g)], g]) for g in groups])
    mesh = pv.PolyData(np.column_stack([points, np.zeros(len(points))]), lines=cells)
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


def _draw_mode(pv, plotter, title: str, modes: ModeSet, i: int, joints: dict, ground: set,
               fraction: float, font_size: int) -> None:
    s = modes.sampled
    groups = _link_groups(modes)
    disp = s.displacement[:, :, i]
    magnitude = np.linalg.norm(disp, axis=1)
    peak = magnitude.max()
    relative = magnitude / peak if peak > 0 else magnitude
    deformed = s.points + modes.scale(i, fraction) * disp
    line = max(2.0, font_size / 4)

    grounded = [p for name, p in joints.items() if name in ground]
    if len(grounded) >= 2:
        base = np.array(grounded[:2], dtype=float)
        plotter.add_mesh(_polylines(pv, base, [np.arange(2)]), color=GROUND_LINE,
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
    names = list(joints)
    xy = np.array([joints[n] for n in names], dtype=float)
    # markers and labels sit in front of the tubes (the camera looks down the z axis)
    front = modes.size * 0.05
    xyz = np.column_stack([xy, np.full(len(xy), front)])
    is_ground = np.array([n in ground for n in names])
    marker = font_size * 1.1
    if is_ground.any():
        plotter.add_points(xyz[is_ground], color="black", point_size=marker,
                           render_points_as_spheres=False)  # squares: bearings to the frame
    if (~is_ground).any():
        plotter.add_points(xyz[~is_ground], color="#d62728", point_size=marker,
                           render_points_as_spheres=True)  # discs: pins between links
    away = xy - xy.mean(axis=0)
    away /= np.maximum(np.linalg.norm(away, axis=1, keepdims=True), 1e-300)
    labels = np.column_stack([xy + 0.045 * modes.size * away, np.full(len(xy), front)])
    plotter.add_point_labels(labels, names, font_size=font_size, text_color="black",
                             shape=None, show_points=False, always_visible=True,
                             justification_horizontal="center",
                             justification_vertical="center")
    plotter.add_text(title, position="upper_edge", font_size=font_size, color="black")
    plotter.add_text(f"grey: rest pose;  colour: mode shape, largest displacement drawn as "
                     f"{100 * fraction:g} % of the mechanism size", position="lower_left",
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


def mode_picture(title: str, modes: ModeSet, i: int, joints: dict, ground: set,
                 fraction: float, size: tuple[int, int] = MODE_SIZE) -> bytes:
    """PNG of mode i: ``title`` on top, joint positions ``joints`` (name -> (x, y) [m]) with
    ``ground`` names drawn as bearings; the shape scaled so its largest displacement is
    ``fraction`` of the mechanism size. ``size`` [px] (width, height)."""
    pv = _pyvista()
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    _draw_mode(pv, plotter, title, modes, i, joints, ground, fraction,
               font_size=max(10, size[1] // 50))
    return _png(_screenshot(plotter))


def overview_sheet(name: str, modes: ModeSet, joints: dict, ground: set, fraction: float,
                   tile: tuple[int, int] = SHEET_TILE) -> bytes:
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
                   modes, i, joints, ground, fraction, font_size=max(10, tile[1] // 40))
    for j in range(n, rows * cols):
        plotter.subplot(j // cols, j % cols)
        plotter.set_background("white")
    return _png(_screenshot(plotter))
