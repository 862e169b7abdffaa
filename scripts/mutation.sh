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
# complete numbers first. After each package it prints, per module: mutants, killed (a
# timeout counts as killed, as in mutmut's own score), survived, no tests, other (suspicious,
# segfault, not checked), the kill rate (killed over all mutants, so "no tests" counts against
# it) and the module's wall time (the sum of its mutants' run times; with JOBS=1 that is the
# wall time spent on it).
#
# Settings (environment): JOBS mutants in parallel (default 1; the machine is shared),
# NICE niceness (default 15), MUTATION_OUT the scratch folder (default /tmp/flexlink-mutation),
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

targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(flexlink/kinematics flexlink/materials flexlink/scene
    flexlink/fe flexlink/analysis flexlink/studies flexlink/output)

# Everything the tests read besides flexlink/ and tests/ (which mutmut copies itself).
extras=(cases materials scenes benchmarks docs scripts README.md)

if [ "${KEEP:-0}" != 1 ] || [ ! -d "$OUT/mutants" ]; then
    rm -rf "$OUT" && mkdir -p "$OUT"
fi
for item in flexlink tests "${extras[@]}" pyproject.toml; do
    [ -e "$ROOT/$item" ] && cp -r "$ROOT/$item" "$OUT/"
done
# mutmut copies the tests into mutants/ only once; refresh them for a KEEP run.
[ -d "$OUT/mutants/tests" ] && rm -rf "$OUT/mutants/tests" && cp -r "$ROOT/tests" "$OUT/mutants/"

{
    echo "[mutmut]"
    echo "source_paths = flexlink"
    echo "only_mutate ="
    for t in "${targets[@]}"; do
        if [ -d "$ROOT/$t" ]; then echo "    ${t%/}/*"; else echo "    $t"; fi
    done
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
    pattern="$(echo "${t%.py}" | tr / .)"
    [ -d "$ROOT/$t" ] && pattern="$pattern.*" || pattern="$pattern.x*"
    log="$OUT/run-$(echo "$pattern" | tr -d '*').log"
    start=$(date +%s)
    mutmut run --max-children "$JOBS" "$pattern" > "$log" 2>&1 || echo "$t: mutmut failed, see $log"
    echo "== $t: $(( $(date +%s) - start )) s wall (clean run of its tests included)"
    (cd "$OUT" && "$PY" - "$t" <<'EOF'
import json
import sys
from pathlib import Path

from mutmut.stats import status_by_exit_code

target = Path(sys.argv[1])
metas = sorted(Path("mutants").joinpath(target).rglob("*.py.meta")) if not target.suffix \
    else [Path("mutants") / (str(target) + ".meta")]
total = {k: 0 for k in ("mutants", "killed", "survived", "no tests", "other")}
print(f"{'module':42} mutants killed survived no-tests other  rate   wall")
for meta in metas:
    data = json.loads(meta.read_text())
    counts = dict.fromkeys(total, 0)
    for code in data["exit_code_by_key"].values():
        status = status_by_exit_code[code]
        counts["mutants"] += 1
        key = status if status in ("killed", "survived", "no tests") else "other"
        counts["killed" if status == "timeout" else key] += 1
    if not counts["mutants"]:
        continue
    wall = sum(data.get("durations_by_key", {}).values())
    for k in total:
        total[k] += counts[k]
    rate = 100 * counts["killed"] / counts["mutants"]
    name = str(meta.relative_to("mutants"))[: -len(".meta")]
    print(f"{name:42} {counts['mutants']:7} {counts['killed']:6} {counts['survived']:8} "
          f"{counts['no tests']:8} {counts['other']:5} {rate:4.0f} % {wall:5.0f} s")
if total["mutants"]:
    rate = 100 * total["killed"] / total["mutants"]
    print(f"{'total ' + str(target):42} {total['mutants']:7} {total['killed']:6} "
          f"{total['survived']:8} {total['no tests']:8} {total['other']:5} {rate:4.0f} %")
EOF
    )
done
echo "survivors: cd $OUT && $PY -m mutmut results"
