"""What the HTML report shows of one scene beyond its summary: the modal map over the crank
cycle, or why there is none (a linkage that cannot turn a full cycle still gets its page)."""

from __future__ import annotations

import dataclasses

from flexlink.errors import FlexlinkError
from flexlink.studies.cycle import ModalMap, modal_map
from flexlink.studies.scene_summary import SceneSummary, SensitivityRun, scene_summary


@dataclasses.dataclass(frozen=True)
class ReportScene:
    """One scene of the report: its ``summary`` (the planar modes, with a note for another
    family), its ``cycle`` map (None when none was asked for or it could not be made) and
    ``cycle_unavailable``, the reason it could not."""

    summary: SceneSummary
    cycle: ModalMap | None
    cycle_unavailable: str | None = None

    def __post_init__(self):
        if self.cycle is not None and self.cycle_unavailable is not None:
            raise ValueError("ReportScene has a cycle map and a reason it is unavailable, "
                             "expected at most one")


def report_scene(path, n_modes: int, elements: int | None, tol: float | None, solver,
                 cycle_poses: int, sensitivity: SensitivityRun | None = None) -> ReportScene:
    """The scene file at ``path`` summarised (``scene_summary``, its in-plane modes) with its
    modal map over ``cycle_poses`` crank angles (none for 0) on the same mesh."""
    summary = scene_summary(path, n_modes, elements, tol, solver, in_plane_only="this page",
                            sensitivity=sensitivity)
    if not cycle_poses:
        return ReportScene(summary, None)
    try:
        cycle = modal_map(summary.case.scene, cycle_poses, n_modes, summary.mesh.elements)
    except FlexlinkError as exc:
        return ReportScene(summary, None, str(exc))
    return ReportScene(summary, cycle)
