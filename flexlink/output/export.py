"""Everything a person looks at for one analysed case, written into one folder:

    <stem>.vtu                    all modes as point data on the undeformed linkage (ParaView)
    <stem>_mode<n>.pvd            animation of mode n over one period, frames in <stem>_mode<n>/
    <stem>_mode<n>.png            picture of mode n (pyvista, off screen)
    <stem>_modes.png              overview sheet of all modes
    <stem>_frequencies.png        computed vs reference frequencies (matplotlib)
    <stem>_modes.uff              with a UFF setting: the modes for test software (UFF 164,
                                  15 or 2411, 55 per mode) at every node or at a test's points
    export.json                   the list of these files (``flexlink export``, not ``report``)

``<stem>`` is the scene file's name without ``.toml``. The folder is written as a whole: into a
staging folder that then replaces ``<stem>/`` (``fileio.staged_folder``), so an interrupted
export leaves the previous folder as it was, never a mix of two runs. Other commands' files in
the folder are carried over; export's own files from an earlier run are not.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable
from pathlib import Path

from flexlink.analysis.modal import CaseResult
from flexlink.errors import InputError
from flexlink.fileio import staged_folder, write_atomic
from flexlink.output.counts import counted
from flexlink.output.export_vtk import mode_set, modes_mesh, write_animation, write_vtu
from flexlink.stopping import signals_deferred
from flexlink.studies.correlation.measured import ModalTest
from flexlink.studies.pose.scene_summary import SceneSummary


@dataclasses.dataclass(frozen=True)
class UffSettings:
    """The modes as a UFF file: geometry dataset 15 or 2411; at every node (``points``
    None) or at the sensor points of a test or layout file read by
    ``studies.correlation.measured`` (placed by the scene's [test] table)."""

    geometry: int = 15
    points: ModalTest | None = None


@dataclasses.dataclass(frozen=True)
class ExportSettings:
    """n_modes: elastic modes exported; subdivisions: segments per element; phases: animation
    frames per period; amplitude: largest drawn displacement as a fraction of the mechanism
    size (the diagonal of the joints' bounding box); pictures/plot: draw PNGs; common_phase:
    animation time as the fraction of the period (0 ... 1 for every mode), not seconds."""

    n_modes: int = 4
    subdivisions: int = 4
    phases: int = 24
    amplitude: float = 0.1
    pictures: bool = True
    plot: bool = True
    common_phase: bool = False
    uff: UffSettings | None = None

    def __post_init__(self):
        checks = (("n_modes", 1, 200), ("subdivisions", 1, 64), ("phases", 2, 1000))
        for field, low, high in checks:
            value = getattr(self, field)
            if not (isinstance(value, int) and low <= value <= high):
                raise InputError(f"got {value!r}", field=field, expected=f"a whole number in [{low}, {high}]")
        if not 0 < self.amplitude <= 1:
            raise InputError(f"got {self.amplitude!r}", field="amplitude",
                             expected="a fraction of the mechanism size in (0, 1]")


def case_stem(result: CaseResult) -> str:
    return Path(result.scene.path).stem


RECORD = "export.json"  # the scene folder's own list of what its export wrote


def export_case(summary: SceneSummary, out: Path, settings: ExportSettings,
                record: Callable[[dict], str] | None = None) -> dict:
    """Write the files of one scene's summary (``studies.pose.scene_summary``) into ``out/<stem>/``,
    replacing that folder as a whole. Returns {"folder": ..., kind: [paths]} with
    kinds vtu, pvd, frames, pictures, plot (paths as strings, in the final folder), and with
    ``record`` also "record": the folder's ``export.json``, holding ``record(those files)``, so
    it is swapped in with the files it lists."""
    result = summary.case
    stem = case_stem(result)
    folder = out / stem
    with staged_folder(folder, keep=lambda name: not _is_export_file(stem, name, settings)) \
            as stage:
        files = _write_case(summary, stage, stem, settings)
        written = {"folder": str(folder),
                   **{k: [str(folder / p.relative_to(stage)) for p in v] for k, v in files.items()}}
        if record is not None:
            written["record"] = [str(folder / RECORD)]
            write_atomic(stage / RECORD, record(written))
    return written


def _is_export_file(stem: str, name: str, settings: ExportSettings) -> bool:
    """Whether ``name`` in a scene's folder is a file of a kind this export writes (any number
    of modes), so the old one goes; everything else is carried over: other commands' files
    (``modes``, ``cycle``...), and the pictures or plot of an earlier export when this one
    writes none (``flexlink report`` writes only the .vtu and .pvd files)."""
    if name == f"{stem}.vtu" or re.fullmatch(rf"{re.escape(stem)}_mode\d+(\.pvd)?", name):
        return True
    if settings.pictures and (name == f"{stem}_modes.png"
                              or re.fullmatch(rf"{re.escape(stem)}_mode\d+\.png", name)):
        return True
    if settings.uff is not None and name == f"{stem}_modes.uff":
        return True
    return settings.plot and name == f"{stem}_frequencies.png"


def _write_uff(summary: SceneSummary, path: Path, settings: ExportSettings) -> Path:
    """The exported modes (in-plane, mass-normalised) at every node or at the test's points."""
    from flexlink.output.correlation.measured import write_uff
    from flexlink.studies.correlation.correlation import modes_at_nodes, modes_at_test_points

    result = summary.case
    chosen = result.modes.elastic[:settings.n_modes]
    shapes, freqs = result.modes.shapes[:, chosen], result.modes.frequencies[chosen]
    if settings.uff.points is None:
        at = modes_at_nodes(result.model, shapes, freqs)
    else:
        at = modes_at_test_points(result.scene, settings.uff.points, result.model, shapes, freqs)
    damping = summary.damping_ratio[:len(chosen)] if len(summary.damping_ratio) else None
    title = f"flexlink model modes: {result.scene.name}"
    return write_uff(path, at, title, damping, settings.uff.geometry)


def _write_case(summary: SceneSummary, folder: Path, stem: str, settings: ExportSettings
                ) -> dict[str, list[Path]]:
    result = summary.case
    modes = mode_set(result, settings.n_modes, settings.subdivisions)
    files: dict[str, list[Path]] = {"vtu": [], "pvd": [], "frames": [], "pictures": [], "plot": []}
    if settings.uff is not None:
        files["uff"] = [_write_uff(summary, folder / f"{stem}_modes.uff", settings)]
    files["vtu"].append(write_vtu(folder / f"{stem}.vtu",
                                  modes_mesh(result, modes, settings.amplitude)))
    for i in range(len(modes.numbers)):
        *frames, pvd = write_animation(folder, stem, modes, i, settings.phases, settings.amplitude,
                                       settings.common_phase)
        files["frames"] += frames
        files["pvd"].append(pvd)
    if settings.pictures:
        from flexlink.output.pictures import mode_picture, overview_sheet

        name = result.scene.name
        for i, (n, f) in enumerate(zip(modes.numbers, modes.frequencies)):
            with signals_deferred():  # VTK renders in native code that a signal must not cut
                png = mode_picture(f"{name}: mode {n}, {f:.1f} Hz", modes, i, settings.amplitude)
            files["pictures"].append(write_atomic(folder / f"{stem}_mode{n}.png", png))
        with signals_deferred():
            sheet = overview_sheet(name, modes, settings.amplitude)
        files["pictures"].append(write_atomic(folder / f"{stem}_modes.png", sheet))
    if settings.plot:
        from flexlink.output.plots import frequency_plot

        with signals_deferred():  # matplotlib, likewise
            plot = frequency_plot(summary)
        files["plot"].append(write_atomic(folder / f"{stem}_frequencies.png", plot))
    return files


def export_entry(summary: SceneSummary, files: dict | None = None) -> dict:
    """One scene of the export's JSON document: its frequencies [Hz], mesh, why its modes are
    the in-plane ones (with another family) and, once written, ``export_case``'s files."""
    scene = summary.case.scene
    out = {"scene": scene.name, "file": scene.path, "mesh": summary.mesh.as_dict(),
           "frequencies_Hz": summary.frequencies.tolist()}
    if summary.note:
        out["note"] = summary.note
    return out if files is None else {**out, "files": files}


def export_document(out: Path, entries: list[dict], failures: list[dict], complete: bool
                    ) -> dict:
    """The JSON document of ``flexlink export``: ``entries`` (``export_entry``) and the
    ``failures``; ``complete`` when every scene asked for is in it."""
    return {"command": "export", "out": str(out), "complete": complete, "cases": entries,
            "failures": failures}


def export_text(done: list[tuple[SceneSummary, dict]], combined: Path | None) -> str:
    """What ``flexlink export`` prints for each (summary, its files) and where it wrote."""
    lines = []
    for summary, f in done:
        if summary.note:
            lines.append(summary.note)
        lines.append(f"{summary.case.scene.name}: {counted(len(summary.frequencies), 'mode')} -> "
                     f"{f['folder']}/  ({len(f['vtu'])} .vtu, {len(f['pvd'])} .pvd with "
                     f"{counted(len(f['frames']), 'frame')}, "
                     f"{counted(len(f['pictures']), 'picture')}, {counted(len(f['plot']), 'plot')}"
                     + "".join(f", {p}" for p in f.get("uff", ())) + ")"
                     f"\n  {summary.mesh.describe()}")
    if done:
        lines.append("written: " + ", ".join([*(f["record"][0] for _, f in done),
                                              *([str(combined)] if combined else [])]))
    return "".join(line + "\n" for line in lines)
