#!/usr/bin/env bash
# Set up (if needed) and run the main job on the shipped Table II scenes.
source "$(dirname "$0")/venv.sh"
flexlink modes cases/ --out "${OUT:-out}" "$@"
