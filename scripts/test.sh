#!/usr/bin/env bash
# Set up (if needed), lint and run the test suite.
source "$(dirname "$0")/venv.sh"
bash scripts/browser-deps.sh  # headless Chromium for the report's browser test
ruff check flexlink tests benchmarks scripts  # the rules and their reasons: pyproject.toml
# flexlink byte-compiled once (0.3 s): where PYTHONDONTWRITEBYTECODE is set, each worker and
# each process the tests start would compile what it imports afresh (about 0.15 s a run).
python -m compileall -q flexlink
# One pytest-xdist worker per core; each file's tests stay on one worker, so a module's fixtures
# are built once. (--dist loadgroup would not group: pytest-xdist 3.8 renames the tests of a
# group through an attribute that pytest 9 no longer reads.)
python -m pytest -q -n logical --dist loadfile "$@"
