#!/usr/bin/env bash
# Mutation testing on demand (not in CI): bash scripts/mutation.sh [MODULE ...]
# Each module is mutated by mutmut in its own scratch copy of the repository, against only the
# tests that exercise it, so a run takes minutes, not hours. Needs the "mutation" extra
# (pip install -e '.[mutation]'). Prints killed/survived counts per module and leaves the
# scratch copies (with `mutmut results` / `mutmut show NAME` usable inside) under $OUT.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PY="${PYTHON:-$ROOT/.venv/bin/python}"
[ -x "$PY" ] || PY=python
OUT="${MUTATION_OUT:-/tmp/flexlink-mutation}"

# module -> the tests that exercise it
declare -A TESTS=(
    [flexlink/studies/comparison.py]="tests/test_calibration_synthetic.py tests/test_calibration_failures.py"
    [flexlink/studies/calibration.py]="tests/test_calibration_synthetic.py tests/test_calibration.py tests/test_calibration_failures.py"
    [flexlink/studies/uncertainty.py]="tests/test_uncertainty.py tests/test_calibration_synthetic.py"
    [flexlink/materials/mixtures.py]="tests/test_materials.py tests/test_uncertainty.py"
    [flexlink/units.py]="tests/test_units.py"
    [flexlink/fileio.py]="tests/test_fileio.py tests/test_export_interrupted.py tests/test_cycle_plot_atomic.py"
)
modules=("$@")
[ ${#modules[@]} -gt 0 ] || modules=(flexlink/units.py flexlink/materials/mixtures.py
    flexlink/studies/uncertainty.py flexlink/studies/calibration.py
    flexlink/studies/comparison.py flexlink/fileio.py)

for module in "${modules[@]}"; do
    name="$(basename "$module" .py)"
    work="$OUT/$name"
    rm -rf "$work" && mkdir -p "$work"
    (cd "$ROOT" && cp -r flexlink tests cases materials scenes benchmarks pyproject.toml "$work/")
    tests=""
    for t in ${TESTS[$module]}; do [ -f "$ROOT/$t" ] && tests="$tests $t"; done
    {
        echo "[mutmut]"
        echo "source_paths = flexlink"
        echo "only_mutate = $module"
        echo "also_copy ="
        for d in cases materials scenes benchmarks; do echo "    $d"; done
        echo "pytest_add_cli_args_test_selection ="
        for t in $tests; do echo "    $t"; done
    } > "$work/setup.cfg"
    (cd "$work" && "$PY" -m mutmut run --max-children "${JOBS:-4}" > run.log 2>&1 || true)
    (cd "$work" && "$PY" -m mutmut results --all true > results.txt 2>&1 || true)
    killed=$(grep -c ": killed" "$work/results.txt" || true)
    survived=$(grep -c ": survived" "$work/results.txt" || true)
    other=$(grep -vcE ": (killed|survived)$" "$work/results.txt" || true)
    echo "$module: killed $killed, survived $survived, other $other ($work/results.txt)"
done
