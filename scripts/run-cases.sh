#!/usr/bin/env bash
# Set up (if needed) and run the main job on the shipped Table II scenes: the frequency table,
# then mode shapes for ParaView (.vtu, .pvd), pictures and plots in OUT/<case>/, and the HTML
# report OUT/report.html.
source "$(dirname "$0")/venv.sh"
flexlink modes cases/ --out "${OUT:-out}" "$@"
flexlink export cases/ --out "${OUT:-out}"
flexlink report cases/ --out "${OUT:-out}"  # out/report.html: one page to send
