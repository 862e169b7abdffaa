"""What a mode picture draws, read from the meshes handed to the plotter rather than from
pixels: every joint spring is its own zig-zag from one displaced end to the other, and the
scale bar is as long as its label says, with end ticks short enough to stay clear of the two
label lines above and below it. A recording stand-in for pyvista's Plotter keeps each call;
the meshes are pyvista's own PolyData, so nothing is rendered (no OpenGL needed)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.analysis.modal import analyze
from flexlink.output.export_vtk import mode_set
from flexlink.output.pictures import SPRING, _draw_mode, joint_springs, scale_bar, zigzag
from flexlink.scene import load_scene

FRACTION = 0.1  # largest displacement drawn as 10 % of the mechanism size
MODE = 0


class Recorder:
    """Stands in for pyvista.Plotter: keeps every mesh, point set and label set it is given."""

    def __init__(self):
        self.meshes, self.labels = [], []
        self.camera = SimpleNamespace(zoom=lambda *a: None)

    def add_mesh(self, mesh, **options):
        self.meshes.append((mesh, options))

    def add_point_labels(self, points, labels, **options):
        self.labels.append((np.asarray(points), list(labels)))

    def __getattr__(self, name):  # add_points, add_text, view_xy, ...: nothing to keep
        return lambda *args, **kwargs: None


def _polylines(mesh) -> list[np.ndarray]:
    """Each poly-line of ``mesh`` as its (n, 2) points; every index must name a point."""
    lines, points, out, k = np.asarray(mesh.lines), np.asarray(mesh.points), [], 0
    while k < len(lines):
        n = lines[k]
        ids = lines[k + 1:k + 1 + n]
        assert ids.max() < len(points), f"a poly-line through point {ids.max()} of {len(points)}"
        out.append(points[ids, :2])
        k += n + 1
    return out


@pytest.fixture(scope="module")
def drawn():
    import pyvista

    # case 1's joints are finite springs (Kt = 1e6 N/m): the modes stretch them
    modes = mode_set(analyze(load_scene(CASES_DIR / "case1.toml"), 2, 2), 2, subdivisions=2)
    plotter = Recorder()
    _draw_mode(pyvista, plotter, "mode 1", modes, MODE, FRACTION, font_size=12)
    return modes, plotter


def test_each_joint_spring_is_a_zigzag_between_its_displaced_ends(drawn):
    modes, plotter = drawn
    [spring_mesh] = [m for m, o in plotter.meshes if o.get("color") == SPRING]
    springs = [s for s in joint_springs(modes, MODE, modes.scale(MODE, FRACTION))
               if np.linalg.norm(s.end - s.start) > 1e-9 * modes.size]
    assert len(springs) >= 4  # case 1: two bearings and two pins, each stretched
    lines = _polylines(spring_mesh)
    assert len(lines) == len(springs)
    for line, spring in zip(lines, springs):
        np.testing.assert_allclose(line, zigzag(spring.start, spring.end, 0.012 * modes.size),
                                   rtol=0, atol=1e-12 * modes.size)  # the same numbers, copied


def test_scale_bar_is_as_long_as_its_label_and_its_ticks_clear_the_labels(drawn):
    modes, plotter = drawn
    bar = scale_bar(modes, MODE, FRACTION)
    [(spots, texts)] = [(p, t) for p, t in plotter.labels if t == list(bar.labels())]
    [bar_mesh] = [m for m, o in plotter.meshes if o.get("color") == "black"]
    body, *ticks = _polylines(bar_mesh)
    assert np.linalg.norm(body[1] - body[0]) == pytest.approx(bar.length, rel=1e-12)
    gap = abs(spots[0, 1] - body[0, 1])  # the labels sit this far above and below the bar
    assert len(ticks) == 2
    for tick, end in zip(ticks, body):
        assert tick[:, 0] == pytest.approx([end[0], end[0]])  # upright, at the bar's ends
        half = np.abs(tick[:, 1] - end[1]).max()
        assert 0 < half < 0.5 * gap  # a tick, not a line through its label
