#!/usr/bin/env bash
# The package as a user gets it: build a wheel from a copy of the files it is made of, install
# it into a clean temporary venv, and run flexlink from a folder outside the source tree.
# Catches anything the package reads but does not ship (the material files). pip's cache keeps
# the dependency install short after the first run.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
unset PYTHONPATH  # the installed wheel alone must do
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
start=$SECONDS
mkdir "$tmp/src"
cp -r pyproject.toml README.md flexlink materials "$tmp/src/"  # no build/ left in the checkout
# The throwaway venv gets no pip of its own (ensurepip took 8 s of 27): the pip of the
# project's .venv (scripts/venv.sh, which .ci/run has run by now) installs into it through
# --python. Without that venv, the throwaway venv's own pip does.
if [ -x .venv/bin/python ]; then
    "${PYTHON:-python3}" -m venv --without-pip "$tmp/venv"
    pip=(.venv/bin/python -m pip --python "$tmp/venv/bin/python")
else
    "${PYTHON:-python3}" -m venv "$tmp/venv"
    pip=("$tmp/venv/bin/python" -m pip)
fi
# --no-compile: one short run imports a fraction of what pip would byte-compile (13 s of 40)
"${pip[@]}" install --quiet --no-compile --disable-pip-version-check "$tmp/src"
cd "$tmp"
"$tmp/venv/bin/flexlink" --version
"$tmp/venv/bin/flexlink" modes "$repo/cases/case1.toml" -e 8 --out "$tmp/out" > "$tmp/modes.txt"
grep -q "Table II case 1" "$tmp/modes.txt"
test -s "$tmp/out/case1/modes.json"
echo "wheel check: built, installed and ran in $((SECONDS - start)) s" >&2
