#!/usr/bin/env bash
# Mutation testing on demand (not in CI): bash scripts/mutation.sh [PACKAGE_OR_MODULE ...]
#   e.g. bash scripts/mutation.sh flexlink/kinematics flexlink/materials flexlink/units.py
# Default: the stage packages, smallest first (kinematics, materials, scene, fe, analysis,
# studies, output).
#
# One scratch copy of the repository holds every mutant of the named packages. mutmut first
# runs the selected tests (TESTS, default the whole suite) once with every mutated function
# instrumented (its "stats" phase) and records which tests reach which function, at any call
# depth; each mutant is then run against only those tests, fastest first, stopping at the
# first failure. Mutants in code no selected test reaches count as "no tests" (not killed):
# mutate_only_covered_lines is not used, since it would drop them from the count.
#
# Then one `mutmut run 'PACKAGE.*'` per package, in order, so the small packages have
# complete numbers first; SAMPLE=N runs N mutants per package drawn at random (SEED, default
# 1) instead, an unbiased estimate where the whole package does not fit the time at hand.
# After each package it prints, per module (scripts/mutation_table.py): mutants, checked,
# killed (a timeout counts as killed, as in mutmut's own score), survived, no tests, other,
# the kill rate over the checked mutants with its 95 % interval, and the module's wall time
# (the sum of its mutants' run times: the wall time spent on it when JOBS=1).
#
# Settings (environment):
#   TESTS     test files or folders mutmut may choose from (default: tests)
#   SAMPLE    mutants per package drawn at random (SEED, default 1); unset: every mutant
#   JOBS      mutants run in parallel (default 1: the machine is shared); NICE (default 15)
#   MUTATION_OUT  the scratch folder (default /tmp/flexlink-mutation)
#   KEEP=1    reuse the scratch copy: cached verdicts and stats stay, new tests are copied in
#             and only their stats collected; the targets and TESTS must be as first given
#   ONLY      a subset of the targets to run (with KEEP, e.g. ONLY=flexlink/materials)
#   NO_CLEAN=1  skip mutmut's clean run of the selected tests before the mutants, which
#             repeats the stats phase (that phase fails unless every selected test passes);
#             only when the stats ran on the same sources, as without KEEP
# Inside the scratch copy `python -m mutmut results`, `python -m mutmut show NAME` and
# `python -m mutmut tests-for-mutant NAME` explain any verdict.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PY="${PYTHON:-$ROOT/.venv/bin/python}"
[ -x "$PY" ] || PY=python
OUT="${MUTATION_OUT:-/tmp/flexlink-mutation}"
JOBS="${JOBS:-1}"
NICE="${NICE:-15}"

targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(flexlink/kinematics flexlink/materials flexlink/scene
    flexlink/fe flexlink/analysis flexlink/studies flexlink/output)

# Everything the tests read besides flexlink/ and tests/ (which mutmut copies itself).
extras=(cases materials scenes benchmarks docs scripts README.md .taplo.toml)

if [ "${KEEP:-0}" != 1 ] || [ ! -d "$OUT/mutants" ]; then
    rm -rf "$OUT" && mkdir -p "$OUT"
fi
for item in flexlink tests "${extras[@]}" pyproject.toml; do
    # -p keeps the times: mutmut regenerates the mutants of a source newer than they are.
    rm -rf "${OUT:?}/$item"
    [ -e "$ROOT/$item" ] && cp -rp "$ROOT/$item" "$OUT/"
done
# mutmut copies the tests into mutants/ only once; refresh them for a KEEP run.
[ -d "$OUT/mutants/tests" ] && rm -rf "$OUT/mutants/tests" && cp -rp "$ROOT/tests" "$OUT/mutants/"

{
    echo "[mutmut]"
    echo "source_paths = flexlink"
    echo "only_mutate ="
    for t in "${targets[@]}"; do
        if [ -d "$ROOT/$t" ]; then echo "    ${t%/}/*"; else echo "    $t"; fi
    done
    echo "also_copy ="
    for d in "${extras[@]}"; do echo "    $d"; done
    echo "pytest_add_cli_args_test_selection ="
    for t in ${TESTS:-tests}; do echo "    $t"; done
    # The layout test counts public names per module, and mutmut adds its own names
    # (x_f__mutmut_1, ...) to every mutated module: it fails on any mutated copy.
    echo "pytest_add_cli_args ="
    echo "    -p"
    echo "    no:cacheprovider"
    echo "    --deselect"
    echo "    tests/project/test_layout.py::test_one_module_per_public_name"
} > "$OUT/setup.cfg.new"
# mutmut keeps the mutants of a module it no longer mutates in name only (it overwrites the
# code with the plain source), so a KEEP run needs the same targets and settings.
if [ -f "$OUT/setup.cfg" ] && ! cmp -s "$OUT/setup.cfg" "$OUT/setup.cfg.new"; then
    echo "KEEP needs the targets and TESTS of the scratch copy's last run ($OUT/setup.cfg)"
    exit 1
fi
mv "$OUT/setup.cfg.new" "$OUT/setup.cfg"

# The tests must import the mutated copy (mutants/flexlink), never this checkout nor the
# editable install: mutmut puts mutants/ first on sys.path; PYTHONPATH says the same to any
# subprocess a test starts. The folder must exist before Python starts: Python caches a
# missing sys.path folder as "nothing here" for the whole process, and the editable install
# then served flexlink from the main checkout (the old text of a message came back). So a
# sitecustomize also removes the editable install's finders from every Python started here,
# which turns any such slip into an import error; flexlink then reads the shipped materials
# from the copy's materials/ folder, as a source checkout does.
mkdir -p "$OUT/site" "$OUT/mutants"
cat > "$OUT/site/sitecustomize.py" <<'PY'
import sys

sys.meta_path[:] = [f for f in sys.meta_path if "_EditableFinder" not in repr(f)]
sys.path_hooks[:] = [h for h in sys.path_hooks if "_EditableNamespaceFinder" not in repr(h)]
sys.path_importer_cache.clear()
PY
export PYTHONPATH="$OUT/mutants:$OUT/site"
mutmut() { (cd "$OUT" && nice -n "$NICE" "$PY" -m mutmut "$@"); }

# Stats phase once for all targets. mutmut has no stats-only command: a name filter that
# matches no mutant stops `mutmut run` right after generating the mutants and collecting the
# stats (with an assertion error, expected here), and the stats stay cached for the runs below.
start=$(date +%s)
mutmut run --max-children "$JOBS" "flexlink.__stats_only__" > "$OUT/stats.log" 2>&1 || true
[ -s "$OUT/mutants/mutmut-stats.json" ] || { echo "stats phase failed: see $OUT/stats.log"; exit 1; }
echo "setup (copy, mutant generation, stats over the suite): $(( $(date +%s) - start )) s"

read -ra run_targets <<< "${ONLY:-${targets[*]}}"
for t in "${run_targets[@]}"; do
    t="${t%/}"
    if [ -n "${SAMPLE:-}" ]; then
        mapfile -t names < <(cd "$OUT" && "$PY" "$ROOT/scripts/mutation_table.py" pick "$t" \
            "$SAMPLE" "${SEED:-1}")
    else
        pattern="$(echo "${t%.py}" | tr / .)"
        [ -d "$ROOT/$t" ] && names=("$pattern.*") || names=("$pattern.x*")
    fi
    log="$OUT/run-$(echo "$t" | tr / .).log"
    start=$(date +%s)
    if [ "${NO_CLEAN:-0}" = 1 ]; then
        (cd "$OUT" && nice -n "$NICE" "$PY" "$ROOT/scripts/mutation_table.py" run "$JOBS" \
            "${names[@]}") > "$log" 2>&1 || echo "$t: mutmut failed, see $log"
    else
        mutmut run --max-children "$JOBS" "${names[@]}" > "$log" 2>&1 || echo "$t: mutmut failed, see $log"
    fi
    echo "== $t: $(( $(date +%s) - start )) s wall (its clean test run included)"
    (cd "$OUT" && "$PY" "$ROOT/scripts/mutation_table.py" table "$t")
done
echo "survivors: cd $OUT && $PY -m mutmut results"
