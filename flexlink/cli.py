"""Command-line interface: the ``flexlink`` group. Each command is a module in
``flexlink/commands/`` (file name = command name, hyphens for underscores) defining ``command``;
it is imported only when used, so ``flexlink --help`` and light commands stay light.

Conventions for every command: ``--json`` prints one JSON document on stdout, ``--out DIR``
chooses where files go (default ``out/``); human-readable tables otherwise; long work shows a
progress bar on stderr. SIGTERM and SIGINT stop any command with one line and exit status
128 + the signal's number (``flexlink.stopping``), never a traceback or click's "Aborted!".
"""

from __future__ import annotations

import importlib
import os
import pkgutil
import sys

import click

from flexlink import commands as _commands_pkg
from flexlink import logbook
from flexlink.errors import FlexlinkError
from flexlink.stopping import Terminated, stop_on_signals

# flexlink's dense matrices are small (tens to a few hundred rows): BLAS threads give little
# there, and where the cores are shared they spin against the other work (a 300 x 300
# Cholesky took 0.55 ms on one OpenBLAS thread and 197 ms on two at load average 3). One
# thread unless the user's environment says otherwise; set before numpy is first imported
# (nothing imported above loads it: the commands are imported when used).
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")


class FlexlinkGroup(click.Group):
    """Finds commands in flexlink/commands/ lazily; turns flexlink's own errors into one clear
    line on stderr and exit code 2, with no traceback; a signal into one line and exit code
    128 + its number."""

    def __call__(self, *args, **kwargs):
        # the process's own entry point: the signals stay caught (and ignored once the command
        # has ended) until the interpreter is gone
        return self.main(*args, restore_signals=False, **kwargs)

    def main(self, *args, restore_signals: bool = True, **kwargs):
        with stop_on_signals(restore=restore_signals):
            try:
                return super().main(*args, **kwargs)
            except Terminated as exc:  # temporary files are gone by now (fileio's finally clauses)
                click.echo(f"flexlink: {exc}", err=True)
                sys.exit(128 + exc.signum)

    def list_commands(self, ctx):
        return sorted(m.name.replace("_", "-") for m in pkgutil.iter_modules(_commands_pkg.__path__)
                      if not m.name.startswith("_"))

    def get_command(self, ctx, name):
        if name not in self.list_commands(ctx):
            return None
        module = importlib.import_module(f"{_commands_pkg.__name__}.{name.replace('-', '_')}")
        return module.command

    def invoke(self, ctx):
        try:
            return super().invoke(ctx)
        except FlexlinkError as exc:
            click.echo(f"flexlink: error: {exc}", err=True)
            sys.exit(2)


@click.group(cls=FlexlinkGroup)
@click.version_option(package_name="flexlink", prog_name="flexlink")  # from installed metadata
@click.option("-v", "--verbose", is_flag=True, help="Log details to stderr.")
@click.pass_context
def main(ctx, verbose):
    """flexlink: natural frequencies and mode shapes of planar linkages with flexible links."""
    once = logbook.configure(verbose)
    ctx.call_on_close(lambda: logbook.report_repeats(once))


if __name__ == "__main__":
    main()
