"""Export of mode shapes: the Hermite sampling, the .vtu/.pvd files read back with meshio, the
pictures and plot, the command and its atomic writes."""

import io
import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest
from click.testing import CliRunner

from flexlink.analysis.modal import analyze
from flexlink.cli import main
from flexlink.errors import OutputError
from flexlink.output.export_vtk import mode_set, modes_mesh, write_animation, write_vtu
from flexlink.fileio import write_atomic_with
from flexlink.fe.modeshape import sample_shapes
from flexlink.analysis.mesh import COMMAND_LINE, MeshRule
from flexlink.scene import load_scene
from flexlink.studies.pose.scene_summary import summary_of

from helpers import single_beam

from conftest import ROOT
CASE3 = ROOT / "cases" / "case3.toml"
FRACTION = 0.1


@pytest.fixture(scope="module")
def case3():
    return analyze(load_scene(CASE3), 3, elements_per_link=6)


@pytest.fixture(scope="module")
def modes(case3):
    return mode_set(case3, 3, subdivisions=3)


def cubic_through(v1, r1, v2, r2, h):
    """Coefficients of the cubic with values v1, v2 and slopes r1, r2 at x = 0 and h, found by
    solving the 4x4 conditions directly (independent of the shape-function formulas)."""
    A = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [1, h, h**2, h**3], [0, 1, 2 * h, 3 * h**2]])
    return np.linalg.solve(A, [v1, r1, v2, r2])


def test_sampling_reproduces_a_cubic_field_exactly():
    # Nodal values of u = a + b x (axial) and v = cubic (bending) on an inclined beam: the
    # element's shape functions contain both, so every sampled point must be exact.
    angle, L = 0.7, 1.0
    model = single_beam("free-free", 5, angle=angle)
    x_nodes = np.linspace(0, L, 6)
    u = lambda x: 1e-3 + 2e-3 * x  # noqa: E731
    v = lambda x: 3e-3 - 1e-3 * x + 4e-3 * x**2 - 5e-3 * x**3  # noqa: E731
    dv = lambda x: -1e-3 + 8e-3 * x - 15e-3 * x**2  # noqa: E731
    t, n = np.array([math.cos(angle), math.sin(angle)]), np.array([-math.sin(angle), math.cos(angle)])
    nodal = np.column_stack([u(x_nodes) * t[0] + v(x_nodes) * n[0],
                             u(x_nodes) * t[1] + v(x_nodes) * n[1], dv(x_nodes)]).ravel()
    s = sample_shapes(model, nodal, subdivisions=7)
    x = np.linalg.norm(s.points - s.points[0], axis=1)  # distance along the beam
    assert len(x) == 5 * 7 + 1
    exact = np.outer(u(x), t) + np.outer(v(x), n)
    np.testing.assert_allclose(s.displacement[:, :, 0], exact, rtol=0, atol=1e-15)
    np.testing.assert_allclose(s.rotation[:, 0], dv(x), rtol=0, atol=1e-15)


def test_vtu_round_trip_matches_the_solver(case3, modes, tmp_path):
    path = write_vtu(tmp_path / "case3.vtu", modes_mesh(case3, modes, FRACTION))
    back = meshio.read(path)
    model, solved = case3.model, case3.modes
    elastic = solved.elastic[:3]
    shapes = solved.shapes[:, elastic].reshape(-1, 3, 3)  # node, (ux, uy, rz), mode
    s = modes.sampled

    # geometry: z = 0, the model's nodes where the samples sit on nodes, links straight between
    assert np.all(back.points[:, 2] == 0)
    np.testing.assert_allclose(back.points[:len(s.points), :2], s.points, rtol=0, atol=1e-15)
    on_node = np.flatnonzero(s.point_node >= 0)
    np.testing.assert_array_equal(back.points[on_node, :2], model.nodes[s.point_node[on_node]])
    assert len(on_node) == len(model.nodes)

    # connectivity: one Lagrange curve per element, its two end points on the element's nodes
    block = back.cells[0]
    assert block.type == "VTK_LAGRANGE_CURVE" and block.data.shape == (3 * 6, 4)
    ends = s.point_node[block.data[:, :2]]
    starts = np.concatenate([link.nodes[:-1] for link in model.links])
    np.testing.assert_array_equal(ends, np.column_stack([starts, starts + 1]))
    np.testing.assert_array_equal(back.cell_data["element_id"][0], np.arange(18))
    np.testing.assert_array_equal(back.cell_data["link_id"][0], np.repeat([0, 1, 2], 6))
    for i, link in enumerate(model.links):
        assert back.field_data[f"link_{link.name}"][0] == i

    # mode arrays: the solver's vectors at the nodes, named by number only (stable names for
    # ParaView state files), the frequency in field data
    np.testing.assert_allclose(back.field_data["frequencies_Hz"], solved.frequencies[elastic],
                               rtol=1e-15)
    for k in range(3):
        name = f"mode{k + 1}"
        assert back.field_data[f"{name}_frequency_Hz"][0] == solved.frequencies[elastic[k]]
        disp, rot = back.point_data[f"{name}_displacement"], back.point_data[f"{name}_rotation"]
        assert disp.shape == (len(back.points), 3) and np.all(disp[:, 2] == 0)
        # (rotated to the link frame and back: a few ulps of round-off)
        np.testing.assert_allclose(disp[on_node, :2], shapes[s.point_node[on_node], :2, k],
                                   rtol=0, atol=4 * np.finfo(float).eps * np.abs(shapes).max())
        np.testing.assert_array_equal(rot[on_node], shapes[s.point_node[on_node], 2, k])
        # between nodes: the element's cubic, checked in the link frame of every element
        element = 0
        for link in model.links:
            c, sn = math.cos(link.angle), math.sin(link.angle)
            h = link.length / link.elements
            transverse = lambda d, c=c, sn=sn: -sn * d[..., 0] + c * d[..., 1]  # noqa: E731
            for a in link.nodes[:-1]:
                coef = cubic_through(transverse(shapes[a, :2, k]), shapes[a, 2, k],
                                     transverse(shapes[a + 1, :2, k]), shapes[a + 1, 2, k], h)
                pts = block.data[element]
                along = np.concatenate([[pts[0]], pts[2:], [pts[1]]])  # VTK order -> along
                np.testing.assert_allclose(transverse(disp[along, :2]),
                                           np.polyval(coef[::-1], np.linspace(0, h, len(along))),
                                           rtol=0, atol=1e-12 * np.abs(shapes[..., k]).max())
                element += 1
        assert element == len(block.data)
        # the fixed ground pivots after the sampled points never move
        np.testing.assert_array_equal(disp[len(s.points):], 0)


def test_pvd_animation_references_its_frames(case3, modes, tmp_path):
    phases = 6
    written = write_animation(tmp_path, "case3", modes, 1, phases, FRACTION)
    pvd = written[-1]
    assert pvd.name == "case3_mode2.pvd"
    entries = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    assert len(entries) == phases
    period = 1 / modes.frequencies[1]
    times = [float(e.get("timestep")) for e in entries]
    np.testing.assert_allclose(times, np.arange(phases) * period / phases, rtol=1e-8)
    frames = [meshio.read(pvd.parent / e.get("file")) for e in entries]
    assert [pvd.parent / e.get("file") for e in entries] == written[:-1]
    # frame 0 is the largest deflection, FRACTION of the mechanism size; half a period later
    # the shape is reversed; the points are the deformed positions themselves: the .vtu's
    # undeformed points warped by its mode2_displacement times warp_scale, ParaView's Warp By
    # Vector, exactly
    grid = modes_mesh(case3, modes, FRACTION)
    warped = grid.points + grid.field_data["warp_scale"][1] * grid.point_data["mode2_displacement"]
    np.testing.assert_allclose(frames[0].points, warped, rtol=0, atol=1e-15)  # [m], round-off
    moved = frames[0].points - grid.points
    assert np.linalg.norm(moved, axis=1).max() == pytest.approx(FRACTION * modes.size, rel=1e-12)
    np.testing.assert_allclose(frames[3].points - grid.points, -moved, rtol=0, atol=1e-15)
    np.testing.assert_allclose(frames[0].point_data["applied_displacement_magnitude"],
                               np.linalg.norm(moved, axis=1), rtol=0, atol=1e-15)
    # no vector a second Warp By Vector could apply on top of the applied deformation
    assert all(np.ndim(a) == 1 for a in frames[0].point_data.values())


def test_common_phase_puts_every_mode_on_one_normalised_period(modes, tmp_path):
    phases = 5
    for i in range(3):
        pvd = write_animation(tmp_path, "case3", modes, i, phases, FRACTION, common_phase=True)[-1]
        entries = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
        # the same times for modes of different frequencies: k / phases, no seconds
        assert [float(e.get("timestep")) for e in entries] == pytest.approx(
            np.arange(phases) / phases, rel=0, abs=1e-12)


def test_vtu_has_the_ground_and_the_joints(case3, modes, tmp_path):
    from flexlink.output.export_vtk import PARTS

    path = write_vtu(tmp_path / "case3.vtu", modes_mesh(case3, modes, FRACTION))
    back = meshio.read(path)
    s, n = modes.sampled, len(modes.sampled.points)
    cells = {name: [] for name in PARTS}
    for block, part, joint in zip(back.cells, back.cell_data["part"], back.cell_data["joint_id"]):
        for code, cell, j in zip(part, block.data, joint):
            cells[next(k for k, v in PARTS.items() if v == code)].append((block.type, cell, j))
    # names travel as field data: joint_<name> = joint_id, part_<name> = part code
    names = [j.name for j in modes.joints]
    assert names == ["O2", "A", "B", "O4"]
    for k, name in enumerate(names):
        assert back.field_data[f"joint_{name}"][0] == k
    for name, code in PARTS.items():
        assert back.field_data[f"part_{name}"][0] == code
    assert len(cells["link"]) == len(s.cells)
    # the ground line O2 - O4 between the two pivots, appended after the sampled points
    ((kind, ground, _),) = cells["ground"]
    assert kind == "line"
    np.testing.assert_allclose(back.points[ground, :2], [case3.pose.joints["O2"],
                                                         case3.pose.joints["O4"]], atol=1e-15)
    assert set(ground) == {n, n + 1}
    # one vertex per joint: the pivot of a bearing, the first link end of a pin
    vertices = {names[j]: cell for kind, cell, j in cells["joint"] if kind == "vertex"}
    assert len(vertices) == len(cells["joint"]) == 4
    for name in names:
        np.testing.assert_allclose(back.points[vertices[name][0], :2], case3.pose.joints[name],
                                   atol=1e-12)
    # springs: one per bearing (pivot to link end), one per pin (link end to link end); each
    # joins points that sit on the joint at rest, from different links
    springs = [(names[j], cell) for kind, cell, j in cells["joint_spring"]]
    assert sorted(name for name, _ in springs) == sorted(names)
    for name, (a, b) in springs:
        np.testing.assert_allclose(back.points[[a, b], :2], [case3.pose.joints[name]] * 2,
                                   atol=1e-12)
        assert a != b
    # VTK's own reader (the one ParaView uses) opens the file with every cell and array
    import pyvista

    grid = pyvista.read(path)
    assert grid.n_cells == sum(len(block.data) for block in back.cells)
    assert grid.n_points == len(back.points)
    np.testing.assert_array_equal(grid.cell_data["part"], np.concatenate(back.cell_data["part"]))
    assert "joint_O4" in grid.field_data and "mode3_displacement" in grid.point_data


def test_joint_springs_join_the_displaced_link_ends():
    from flexlink.output.pictures import joint_springs

    # case 3 with edgewise strips, whose mode 2 is the coupler sliding on the joint springs
    case3 = analyze(load_scene(CASE3, overrides={"section.bending": "edgewise"}), 3,
                    elements_per_link=6)
    modes = mode_set(case3, 3, subdivisions=3)
    model, solved = case3.model, case3.modes
    i, factor = 1, modes.scale(1, FRACTION)
    shape = solved.shapes[:, solved.elastic[i]].reshape(-1, 3)
    displaced = model.nodes + factor * shape[:, :2]
    springs = joint_springs(modes, i, factor)
    assert [sp.name for sp in springs] == ["O2", "A", "B", "O4"]
    for sp in springs:
        nodes = model.joint_nodes[sp.name]
        # (displacements rotated to the link frame and back: a few ulps)
        if sp.ground:
            np.testing.assert_array_equal(sp.start, case3.pose.joints[sp.name])
            np.testing.assert_allclose(sp.end, displaced[nodes[0]], rtol=0, atol=1e-15)
        else:
            np.testing.assert_allclose([sp.start, sp.end], displaced[list(nodes)], rtol=0,
                                       atol=1e-15)
    # the drawn stretch of pin A is the solver's relative displacement of its two nodes, and
    # in this joint-spring mode it is a visible part of the drawing (docs/export.md: about 40 %
    # of the peak displacement)
    a = next(sp for sp in springs if sp.name == "A")
    a_nodes = model.joint_nodes["A"]
    stretch = factor * np.linalg.norm(shape[a_nodes[0], :2] - shape[a_nodes[1], :2])
    assert np.linalg.norm(a.end - a.start) == pytest.approx(stretch, rel=1e-9)
    assert stretch > 0.2 * FRACTION * modes.size


def test_zigzag_runs_between_its_ends():
    from flexlink.output.pictures import zigzag

    start, end, width = np.array([1.0, 2.0]), np.array([4.0, 6.0]), 0.1
    points = zigzag(start, end, width, teeth=4)
    assert len(points) == 2 * 4 + 3
    np.testing.assert_array_equal(points[[0, -1]], [start, end])
    unit = (end - start) / 5.0
    normal = np.array([-unit[1], unit[0]])
    offset = (points - start) @ normal
    along = (points - start) @ unit
    assert np.all(np.diff(along) > 0)  # it goes forward
    teeth = offset[2:-2]
    np.testing.assert_allclose(np.abs(teeth), width, rtol=1e-12)
    assert np.all(teeth[:-1] * teeth[1:] < 0)  # alternating sides
    # a short spring keeps its shape: teeth at most 0.4 of its length
    short = zigzag(start, start + 0.05 * unit, width)
    assert np.abs((short - start) @ normal).max() == pytest.approx(0.4 * 0.05, rel=1e-12)


def test_scale_bar_states_the_amplitude_scale(modes):
    from flexlink.output.pictures import scale_bar

    for i in range(3):
        bar = scale_bar(modes, i, FRACTION)
        mantissa = bar.length / 10 ** math.floor(math.log10(bar.length))
        assert min(abs(mantissa - m) for m in (1, 2, 5)) < 1e-9  # a round length
        assert 0.08 * modes.size < bar.length <= 0.2 * modes.size
        # the factor draws the mode's largest mass-normalised displacement at FRACTION of the
        # size; the bar stands for its length divided by that factor
        peak = np.linalg.norm(modes.sampled.displacement[:, :, i], axis=1).max()
        assert bar.factor * peak == pytest.approx(FRACTION * modes.size, rel=1e-12)
        assert bar.displacement == pytest.approx(bar.length * peak / (FRACTION * modes.size),
                                                 rel=1e-12)
        above, below = bar.labels()
        assert f"{1e3 * bar.length:.3g} mm" in above
        shown = bar.displacement if bar.displacement >= 1 else 1e3 * bar.displacement
        assert f"{shown:.3g}" in below and "/sqrt(kg)" in below and "mass-normalised" in below


def test_pictures_draw_every_stretched_spring_and_the_bar(modes, monkeypatch):
    import flexlink.output.pictures as pictures

    drawn, labels = [], []
    zigzag, add_labels = pictures.zigzag, None

    def counting(start, end, width, teeth=6):
        drawn.append((tuple(start), tuple(end)))
        return zigzag(start, end, width, teeth)

    monkeypatch.setattr(pictures, "zigzag", counting)
    import pyvista

    add_labels = pyvista.Plotter.add_point_labels

    def recording(self, points, texts, *args, **kwargs):
        labels.extend(texts)
        return add_labels(self, points, texts, *args, **kwargs)

    monkeypatch.setattr(pyvista.Plotter, "add_point_labels", recording)
    pictures.mode_picture("case 3: mode 2", modes, 1, FRACTION, size=(240, 160))
    factor = modes.scale(1, FRACTION)
    expected = {(tuple(sp.start), tuple(sp.end)) for sp in pictures.joint_springs(modes, 1, factor)}
    assert set(drawn) == expected and len(drawn) == 4
    assert list(pictures.scale_bar(modes, 1, FRACTION).labels()) == labels[-2:]


def png_pixels(data):
    from PIL import Image

    image = Image.open(io.BytesIO(data))
    return image.size, np.asarray(image.convert("RGB"), dtype=float)


def coloured_fraction(pixels):
    """Share of pixels that are clearly not grey (the deformed shape's colour map)."""
    return float(((pixels.max(axis=2) - pixels.min(axis=2)) > 60).mean())


def test_mode_picture_and_sheet_are_drawn(case3, modes):
    from flexlink.output.pictures import mode_picture, overview_sheet

    size, pixels = png_pixels(mode_picture("case 3: mode 1", modes, 0, FRACTION, size=(480, 320)))
    assert size == (480, 320)
    assert pixels.std() > 10 and coloured_fraction(pixels) > 0.005
    size, pixels = png_pixels(overview_sheet("case 3", modes, FRACTION, tile=(300, 200)))
    assert size == (600, 400)  # three modes: two per row, two rows
    for tile in (pixels[:200, :300], pixels[:200, 300:], pixels[200:, :300]):
        assert tile.std() > 10 and coloured_fraction(tile) > 0.002
    assert pixels[200:, 300:].std() == 0  # the unused fourth tile is blank


def test_failed_rendering_check_is_a_clear_error(modes, case3, monkeypatch):
    import flexlink.output.pictures as pictures

    pictures._check_rendering.cache_clear()
    monkeypatch.setattr(pictures, "_PROBE", "import sys; sys.exit(3)")
    try:
        with pytest.raises(OutputError, match="system-deps.sh"):
            pictures.mode_picture("x", modes, 0, FRACTION)
    finally:
        pictures._check_rendering.cache_clear()


def test_frequency_plot(case3):
    from flexlink.output.plots import frequency_plot

    size, pixels = png_pixels(frequency_plot(summary_of(case3, 3, MeshRule(6, COMMAND_LINE)), size=(6, 4), dpi=50))
    assert size == (300, 200)
    # points, not bars: a few hundred coloured pixels at this size (0.45 % measured), none
    # when nothing is drawn
    assert pixels.std() > 10 and coloured_fraction(pixels) > 0.002


def test_export_command_writes_and_lists_everything(tmp_path):
    args = ["export", str(CASE3), "-e", "8", "-n", "2", "--phases", "3", "--subdivide", "2",
            "--common-phase", "--json", "--out", str(tmp_path)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    # one scene: its folder holds the record (listing itself); no combined file, as for modes
    assert json.loads((tmp_path / "case3" / "export.json").read_text()) == {**doc, "complete": True}
    assert not (tmp_path / "export.json").exists()
    (case,) = doc["cases"]
    assert case["files"]["record"] == [str(tmp_path / "case3" / "export.json")]
    files = case["files"]
    assert [Path(p).name for p in files["vtu"]] == ["case3.vtu"]
    assert [Path(p).name for p in files["pvd"]] == ["case3_mode1.pvd", "case3_mode2.pvd"]
    assert len(files["frames"]) == 6
    assert sorted(Path(p).name for p in files["pictures"]) == [
        "case3_mode1.png", "case3_mode2.png", "case3_modes.png"]
    assert [Path(p).name for p in files["plot"]] == ["case3_frequencies.png"]
    for pvd in files["pvd"]:  # --common-phase: time is the fraction of the period
        entries = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
        assert [float(e.get("timestep")) for e in entries] == pytest.approx([0, 1 / 3, 2 / 3])
    every = [p for kind in ("vtu", "pvd", "frames", "pictures", "plot", "record")
             for p in files[kind]]
    assert all(Path(p).is_file() and Path(p).stat().st_size > 0 for p in every)
    assert sorted(str(p) for p in (tmp_path / "case3").rglob("*") if p.is_file()) == sorted(every)
    grid = meshio.read(files["vtu"][0])
    # the frequencies written into the .vtu are the frame's: at 8 elements per link they are the
    # OpenSees ones recorded for tests/analysis/test_table2_pin.py (same tolerance and reason there)
    record = json.loads((Path(__file__).resolve().parents[1] / "data" / "table2_opensees.json").read_text())
    assert record["elements_per_link"] == 8
    opensees = record["cases"]["cases/case3.toml"]["frequencies_Hz"][:2]
    np.testing.assert_allclose(grid.field_data["frequencies_Hz"], opensees, rtol=1e-8)


def test_unwritable_out_fails_before_any_solve(tmp_path, monkeypatch):
    import flexlink.analysis.modal

    def no_solve(*args, **kwargs):
        raise AssertionError("solved before checking the output folder")

    monkeypatch.setattr(flexlink.analysis.modal, "analyze", no_solve)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    result = CliRunner().invoke(main, ["export", str(CASE3), "--out", str(blocker / "o")])
    assert result.exit_code == 2 and "not writable" in result.output


def test_the_combined_record_lists_a_multi_scene_run_and_each_folder_its_own(tmp_path):
    """As modes.json: OUT/<scene>/export.json for each scene, OUT/export.json with all of a
    run over several scenes; a later one-scene run leaves the other folders' records whole.
    Counts read "1 mode", "1 plot" (not "1 modes")."""
    quick = ["-e", "2", "-n", "1", "--phases", "2", "--no-pictures", "--out", str(tmp_path)]
    case1 = ROOT / "cases" / "case1.toml"
    both = CliRunner().invoke(main, ["export", str(case1), str(CASE3), *quick])
    assert both.exit_code == 0, both.output
    combined = json.loads((tmp_path / "export.json").read_text())
    assert [Path(c["file"]).stem for c in combined["cases"]] == ["case1", "case3"]
    assert combined["complete"] is True
    again = CliRunner().invoke(main, ["export", str(CASE3), *quick])
    assert again.exit_code == 0, again.output
    assert "Table II case 3: 1 mode -> " in again.stdout and "1 .pvd with 2 frames" in again.stdout
    assert "0 pictures, 1 plot)" in again.stdout
    for stem in ("case1", "case3"):
        own = json.loads((tmp_path / stem / "export.json").read_text())
        assert [Path(c["file"]).stem for c in own["cases"]] == [stem]
        assert all(Path(p).is_file() for kind, paths in own["cases"][0]["files"].items()
                   if kind != "folder" for p in paths)


def test_failed_write_keeps_the_old_file(tmp_path):
    target = tmp_path / "a.vtu"
    target.write_text("old")

    def half_then_fail(tmp):
        tmp.write_text("half")
        raise OSError(28, "No space left on device")

    with pytest.raises(OutputError, match="No space left"):
        write_atomic_with(target, half_then_fail)
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["a.vtu"]


def test_frequency_plot_draws_points_not_bars(case3, monkeypatch):
    from matplotlib.axes import Axes

    from flexlink.output.plots import frequency_plot

    def no_bars(*args, **kwargs):
        raise AssertionError("a bar on a log axis has no meaningful base")

    monkeypatch.setattr(Axes, "bar", no_bars)
    assert frequency_plot(summary_of(case3, 3, MeshRule(6, COMMAND_LINE)), size=(6, 4), dpi=50)[:4] == b"\x89PNG"
