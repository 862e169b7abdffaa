"""``flexlink stability [SCENE]``: the old name of ``flexlink verify``, kept for one release so
that scripts written for it keep running; it says so on stderr. Parametric stability of the
running linkage is ``flexlink stability-map``."""

from __future__ import annotations

import logging

import click

from flexlink.commands.verify import run_self_checks, self_check_options

RENAMED = ("`flexlink stability` is now `flexlink verify` (the numerical "
           "self-checks); the old name will be removed in the next release. For the running "
           "linkage's parametric stability use `flexlink stability-map`.")


@click.command("stability")
@self_check_options
def command(scene_path, slow, as_json, out_dir):
    """Deprecated name of `flexlink verify` (the numerical self-checks)."""
    logging.getLogger(__name__).warning(RENAMED)
    run_self_checks(scene_path, slow, as_json, out_dir)
