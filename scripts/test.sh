#!/usr/bin/env bash
# Set up (if needed) and run the test suite.
source "$(dirname "$0")/venv.sh"
python -m pytest -q "$@"
