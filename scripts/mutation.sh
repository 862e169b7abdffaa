#!/usr/bin/env bash
# Mutation testing on demand (not in CI): bash scripts/mutation.sh [PACKAGE_OR_MODULE ...]
#   e.g. bash scripts/mutation.sh flexlink/kinematics flexlink/materials flexlink/units.py
# Default: the stage packages, smallest first (kinematics, materials, scene, fe, analysis,
# studies, output).
#
# One scratch copy of the repository holds every mutant of the named packages. mutmut first
# runs the whole suite once with every mutated function instrumented (its "stats" phase) and
# records which tests reach which function, at any call depth; each mutant is then run against
# only those tests, fastest first, stopping at the first failure. No test table is kept here.
# Mutants in code no test reaches are counted as "no tests" (not killed): we do not use
# mutate_only_covered_lines, which would drop them from the count.
#
# Then one `mutmut run 'PACKAGE.*'` per package, in order, so the small packages have
# complete numbers first; SAMPLE=N runs N mutants per package drawn at random (SEED, default
# 1) instead, an unbiased estimate where the whole package does not fit the time at hand.
# After each package it prints, per module (scripts/mutation_table.py): mutants, checked,
# killed (a timeout counts as killed, as in mutmut's own score), survived, no tests, other,
# the kill rate over the checked mutants with its 95 % interval, and the module's wall time
# (the sum of its mutants' run times; with JOBS=1 that is the wall time spent on it).
#
# Settings (environment): SAMPLE and SEED (above), JOBS mutants in parallel (default 1; the
# machine is shared), NICE niceness (default 15), MUTATION_OUT the scratch folder (default /tmp/flexlink-mutation),
# KEEP=1 reuses an existing scratch copy: its cached verdicts and stats stay, new test files
# are copied in and only their stats are collected; a named package is always re-run.
# Inside the scratch copy `python -m mutmut results`, `python -m mutmut show NAME` and
# `python -m mutmut tests-for-mutant NAME` explain any verdict.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PY="${PYTHON:-$ROOT/.venv/bin/python}"
[ -x "$PY" ] || PY=python
OUT="${MUTATION_OUT:-/tmp/flexlink-mutation}"
JOBS="${JOBS:-1}"
NICE="${NICE:-15}"

packages=(flexlink/kinematics flexlink/materials flexlink/scene flexlink/fe flexlink/analysis
    flexlink/studies flexlink/output)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${packages[@]}")

# Everything the tests read besides flexlink/ and tests/ (which mutmut copies itself).
extras=(cases materials scenes benchmarks docs scripts README.md)

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
    # Always every stage package (plus any other named module): mutmut would overwrite the
    # mutants of a package left out with its plain source while keeping their records.
    echo "only_mutate ="
    for t in "${packages[@]}" "${targets[@]}"; do
        if [ -d "$ROOT/$t" ]; then echo "    ${t%/}/*"; else echo "    $t"; fi
    done | sort -u
    echo "also_copy ="
    for d in "${extras[@]}"; do echo "    $d"; done
    echo "pytest_add_cli_args = -p no:cacheprovider"
} > "$OUT/setup.cfg"

# The tests must import the mutated copy (mutants/flexlink), never this checkout nor the
# editable install: mutmut puts mutants/ first on sys.path; PYTHONPATH says the same to any
# subprocess a test starts.
export PYTHONPATH="$OUT/mutants"
mutmut() { (cd "$OUT" && nice -n "$NICE" "$PY" -m mutmut "$@"); }

# Stats phase once for all targets. mutmut has no stats-only command: a name filter that
# matches no mutant stops `mutmut run` right after generating the mutants and collecting the
# stats (with an assertion error, expected here), and the stats stay cached for the runs below.
start=$(date +%s)
mutmut run --max-children "$JOBS" "flexlink.__stats_only__" > "$OUT/stats.log" 2>&1 || true
[ -s "$OUT/mutants/mutmut-stats.json" ] || { echo "stats phase failed: see $OUT/stats.log"; exit 1; }
echo "setup (copy, mutant generation, stats over the suite): $(( $(date +%s) - start )) s"

for t in "${targets[@]}"; do
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
    mutmut run --max-children "$JOBS" "${names[@]}" > "$log" 2>&1 || echo "$t: mutmut failed, see $log"
    echo "== $t: $(( $(date +%s) - start )) s wall (its clean test run included)"
    (cd "$OUT" && "$PY" "$ROOT/scripts/mutation_table.py" table "$t")
done
echo "survivors: cd $OUT && $PY -m mutmut results"
