#!/usr/bin/env bash
# Open every .vtu and .pvd of an export folder in ParaView itself (Debian's pvbatch, not the VTK
# wheel the tests use) and check the cells flexlink writes: link elements, ground line, joint
# springs, joints. Usage: bash scripts/paraview-check.sh [OUT/<scene>]  (default: a fresh
# export of case 3 into a temporary folder). Installs Debian's paraview and python3-paraview
# when missing and run as root (about 200 packages, a few minutes); elsewhere says how.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
missing=()
for package in paraview python3-paraview; do
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
folder=${1:-}
if [ -z "$folder" ]; then
    source "$here/venv.sh"
    out=$(mktemp -d)
    trap 'rm -rf "$out"' EXIT
    flexlink export cases/case3.toml -n 2 --phases 4 --no-pictures --out "$out" >/dev/null
    folder="$out/case3"
fi
# pvbatch's own Python, not the venv's: ParaView's modules live in Debian's python3
cd /tmp && pvbatch "$here/paraview_check.py" "$(cd "$folder" && pwd)"
