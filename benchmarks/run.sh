#!/usr/bin/env bash
# Set up the benchmark's optional tools, then run it: bash benchmarks/run.sh [--repeats N] [--only 1,2b,...] [--skip-full-calibration]
# OpenSeesPy (PyPI) links the system's libblas.so.3 and liblapack.so.3, which a bare Debian lacks;
# they are installed only when missing. pyinstrument is for benchmarks/profile_sweep.py.
source "$(dirname "$0")/../scripts/venv.sh"
python -c "import pyinstrument" >/dev/null 2>&1 || python -m pip install --quiet pyinstrument
if ! python -c "import openseespy.opensees" >/dev/null 2>&1; then
    python -m pip install --quiet openseespy
    missing=()
    for lib in libblas.so.3 liblapack.so.3; do
        ldconfig -p | grep -q "$lib" || missing+=("${lib%%.so.3}3")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null; then
            echo "benchmark: OpenSeesPy needs ${missing[*]} (Debian packages); install them" >&2
            exit 1
        fi
        apt-get update -qq && apt-get install -y -qq "${missing[@]}" >/dev/null
    fi
    python -c "import openseespy.opensees" >/dev/null
fi
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1
exec python benchmarks/bench.py "$@"
