"""``flexlink modes SCENE --speed ...``: the modes at an operating point, beside the static ones."""

from __future__ import annotations


def run_operating(files, folders, n_modes, elements, tol, at, as_json) -> None:
    """Modes at the operating point ``at`` (a ``studies.running.modes_at_speed.OperatingRequest``) of
    each scene file, on ``elements`` per link or the mesh rule at ``tol``; writes
    modes_at_speed.json and .csv to each file's folder in ``folders``."""
    from flexlink.output.running.modes_at_speed import operating_files, operating_text
    from flexlink.studies.running.modes_at_speed import scene_operating_modes

    from ._analysed import each_scene
    from ._failures import finish
    from ._written import publish_files

    failures: list[dict] = []
    done = list(each_scene(files, lambda path: scene_operating_modes(
        path, n_modes, elements, tol, at), failures))
    documents, tables, document = operating_files([(folders[p], op) for p, op in done],
                                                  failures)
    publish_files(documents, tables, document, operating_text([op for _, op in done]), as_json)
    finish(failures, len(files))
