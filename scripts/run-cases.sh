#!/usr/bin/env bash
# Set up (if needed) and run the main job on the shipped Table II scenes: the frequency table,
# then mode shapes for ParaView (.vtu, .pvd), pictures and plots in OUT/<case>/.
source "$(dirname "$0")/venv.sh"
flexlink modes cases/ --out "${OUT:-out}" "$@"
flexlink export cases/ --out "${OUT:-out}"
