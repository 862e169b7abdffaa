#!/usr/bin/env bash
# Check every shipped scene against the editor schema (docs/scene.schema.json) with taplo, the
# checker behind TOML editors (Even Better TOML). taplo comes from PyPI (the `taplo` wheel, in
# the `test` extra, so scripts/test.sh installs it); tests/scene/test_editor_schema.py runs the same
# check and typo files. Usage: bash scripts/taplo-check.sh [FILES...]
set -euo pipefail
source "$(dirname "$0")/venv.sh"
if ! command -v taplo >/dev/null; then
    python -m pip install --quiet "taplo>=0.9"
fi
taplo check "$@"
