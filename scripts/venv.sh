# Sourced by the other scripts: make .venv (if missing) and install flexlink into it.
# Works on a fresh machine that has only Python 3.11 and the package registries.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/system-deps.sh
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    "$PY" -m venv .venv
fi
stamp=.venv/.flexlink-installed
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
    .venv/bin/python -m pip install --quiet --upgrade pip
    .venv/bin/python -m pip install --quiet -e ".[draw,test,dask]"
    touch "$stamp"
fi
export PATH="$PWD/.venv/bin:$PATH"
