# Sourced by the other scripts: make .venv (if missing) and install flexlink into it.
# Works on a fresh machine that has only Python 3.11 and the package registries.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/system-deps.sh
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    # a venv made without pip, given the current pip by the interpreter's own pip: 5 s less
    # than ensurepip and an upgrade of its bundled pip; those where the interpreter has no
    # pip (or one older than 22.3, without --python)
    if ! { "$PY" -m venv --without-pip .venv &&
           "$PY" -m pip --python .venv/bin/python install --quiet --upgrade pip; } 2>/dev/null; then
        rm -rf .venv
        "$PY" -m venv .venv
        .venv/bin/python -m pip install --quiet --upgrade pip
    fi
fi
stamp=.venv/.flexlink-installed
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
    .venv/bin/python -m pip install --quiet -e ".[draw,test,dask]"
    touch "$stamp"
fi
export PATH="$PWD/.venv/bin:$PATH"
