"""``flexlink modes SCENE --speed ...``: the modes at an operating point, beside the static ones."""

from __future__ import annotations


def run_operating(files, folders, n_modes, elements, tol, at, as_json) -> None:
    """Modes at the operating point ``at`` (a ``studies.running.modes_at_speed.OperatingRequest``) of
    each scene file, on ``elements`` per link or the mesh rule at ``tol``; writes
    modes_at_speed.json and .csv to each file's folder in ``folders``."""
    import dataclasses

    from flexlink.output.running.modes_at_speed import operating_files, operating_text
    from flexlink.scene import load_scene
    from flexlink.scene.plausibility import check_speeds
    from flexlink.studies.running.modes_at_speed import scene_operating_modes

    from ._analysed import each_scene
    from ._failures import finish
    from ._speeds import operating_speed
    from ._written import publish_files

    def operating(path):
        scene = load_scene(path)
        if at.speed is not None:
            check_speeds(scene, [at.speed], "--speed")
        speed, acceleration = operating_speed(scene, at.speed, at.crank_acceleration)
        resolved = dataclasses.replace(at, speed=speed, crank_acceleration=acceleration)
        return scene_operating_modes(scene, n_modes, elements, tol, resolved)

    failures: list[dict] = []
    done = list(each_scene(files, operating, failures))
    documents, tables, document = operating_files([(folders[p], op) for p, op in done],
                                                  failures)
    publish_files(documents, tables, document, operating_text([op for _, op in done]), as_json)
    finish(failures, len(files))
