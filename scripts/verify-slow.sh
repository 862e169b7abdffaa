#!/usr/bin/env bash
# The full numerical self-checks, slow checks included (1e5-DOF sparse solves in fresh processes,
# about 10 s on an idle machine): prints expected / got / pass per check; exit code 1 on a FAIL.
source "$(dirname "$0")/venv.sh"
flexlink verify --slow "$@"
