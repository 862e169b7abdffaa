#!/usr/bin/env bash
# Run every command on every shipped scene with --json and keep each JSON document, so that a
# refactoring can be checked to change no result: run it before and after, then
#   python scripts/compare_outputs.py BEFORE AFTER
# Usage: bash scripts/output-snapshot.sh DEST [PYTHON]   (small meshes and few poses: minutes)
set -uo pipefail
dest=${1:?destination folder}
py=${2:-${PYTHON:-python}}
cd "$(dirname "$0")/.."
mkdir -p "$dest"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {  # name, then the command's arguments
    local name=$1; shift
    OPENBLAS_NUM_THREADS=1 "$py" -m flexlink.cli "$@" --json --out "$work/$name" \
        > "$dest/$name.json" 2> "$dest/$name.stderr"
    echo "exit $?" >> "$dest/$name.stderr"
}
scenes=(cases/case1.toml cases/case2.toml cases/case3.toml cases/case4.toml scenes/*.toml)
for s in "${scenes[@]}"; do
    n=$(basename "$s" .toml)
    run "modes-$n" modes "$s" -e 8
    run "export-$n" export "$s" -e 8 --no-pictures --phases 4
    run "cycle-$n" cycle "$s" -e 8 --poses 24 --speed "600 rev/min"
    run "cycle-sorted-$n" cycle "$s" -e 8 --poses 24 --sorted
    run "campbell-$n" campbell "$s" -e 8 --poses 24 --speeds "0:3000 rev/min"
    run "kinematics-$n" kinematics "$s" --poses 36 --speed "600 rev/min"
    run "prb-$n" prb "$s" -e 8
    run "converge-$n" converge "$s" --max-elements 16 --repeats 1
    run "mac-$n" mac "$s" cases/case3.toml -e 8
done
for c in cases/case1.toml cases/case3.toml; do
    run "stability-$(basename "$c" .toml)" stability "$c"
done
run "modes-sensitivity" modes cases/ -e 6 --sensitivity --samples 20
run "report" report cases/ -e 8 --cycle-poses 12
run "calibrate" calibrate cases/ --family planar --starts 1 --samples 10 -e 6
echo "wrote $(ls "$dest"/*.json | wc -l) documents to $dest"
