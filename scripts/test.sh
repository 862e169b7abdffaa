#!/usr/bin/env bash
# Set up (if needed) and run the test suite.
source "$(dirname "$0")/venv.sh"
bash scripts/browser-deps.sh  # headless Chromium for the report's browser test
python -m pytest -q "$@"
