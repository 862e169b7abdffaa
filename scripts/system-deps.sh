#!/usr/bin/env bash
# Debian packages flexlink needs beyond PyPI: off-screen pictures. Without a display, VTK's
# wheels (pyvista) render through EGL with Mesa's software rasterizer; these packages provide
# it. Installs only what is missing; without them the rest of flexlink works
# (`flexlink export --no-pictures`).
set -euo pipefail
bash "$(dirname "$0")/apt-missing.sh" "off-screen rendering for pictures" \
    libegl1 libegl-mesa0 libgl1-mesa-dri
