#!/usr/bin/env bash
# Open every .vtu and .pvd of an export folder in ParaView itself (Debian's pvpython, not the VTK
# wheel the tests use), check the cells flexlink writes (link elements, ground line, joint
# springs, joints) and that Warp By Vector on the .vtu gives each animation's frame 0.
# Usage: bash scripts/paraview-check.sh [OUT/<scene>]  (default: a fresh export of case 3 into
# a temporary folder). Debian's paraview package has the GUI and pvbatch only; pvpython and
# ParaView's Python modules are in python3-paraview. Installs both when missing and run as root
# (about 200 packages, a few minutes; run apt-get update first on a fresh machine); elsewhere
# says how.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
packages=(paraview python3-paraview)
missing=()
for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
        || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -ne 0 ]; then
        echo "paraview-check: install as root: apt-get install -y --no-install-recommends ${missing[*]}" >&2
        exit 2
    fi
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi
if ! command -v pvpython >/dev/null; then
    echo "paraview-check: no pvpython on PATH although ${packages[*]} are installed" >&2
    exit 2
fi
folder=${1:-}
if [ -z "$folder" ]; then
    source "$here/venv.sh"
    out=$(mktemp -d)
    trap 'rm -rf "$out"' EXIT
    flexlink export cases/case3.toml -n 2 --phases 4 --no-pictures --out "$out" >/dev/null
    folder="$out/case3"
fi
# pvpython's own Python, not the venv's: ParaView's modules live in Debian's python3
cd /tmp && pvpython "$here/paraview_check.py" "$(cd "$folder" && pwd)"
