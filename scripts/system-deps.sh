#!/usr/bin/env bash
# Debian packages flexlink needs beyond PyPI: off-screen pictures. Without a display, VTK's
# wheels (pyvista) render through EGL with Mesa's software rasterizer; these packages provide
# it. Installs only what is missing (apt-get needs root, as on CI); elsewhere it warns and
# leaves the rest of flexlink working (`flexlink export --no-pictures`).
set -euo pipefail
PACKAGES=(libegl1 libegl-mesa0 libgl1-mesa-dri)

command -v dpkg-query >/dev/null 2>&1 || exit 0  # not Debian: nothing this script can do
missing=()
for package in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$package")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "system-deps: missing ${missing[*]} (needed for pictures); install them as root:" \
         "apt-get install -y ${missing[*]}" >&2
    exit 0
fi
echo "system-deps: installing ${missing[*]} (off-screen rendering for pictures)" >&2
export DEBIAN_FRONTEND=noninteractive
if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >&2; then
    echo "system-deps: apt-get failed; pictures will not render until ${missing[*]} are installed" >&2
fi
