#!/usr/bin/env bash
# Install the Debian packages named after PURPOSE that are not installed yet:
#   bash scripts/apt-missing.sh "what they are for" PACKAGE...
# apt-get needs root (as on CI); elsewhere, or off Debian, it says what to install and exits 0,
# leaving the rest of flexlink working. Used by system-deps.sh and browser-deps.sh.
set -euo pipefail
purpose=$1
shift
command -v dpkg-query >/dev/null 2>&1 || exit 0  # not Debian: nothing this script can do
missing=()
for package in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$package")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "flexlink set-up: missing ${missing[*]} ($purpose); install them as root:" \
         "apt-get install -y ${missing[*]}" >&2
    exit 0
fi
echo "flexlink set-up: installing ${missing[*]} ($purpose)" >&2
export DEBIAN_FRONTEND=noninteractive
if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >&2; then
    echo "flexlink set-up: apt-get failed; ${missing[*]} ($purpose) still missing" >&2
fi
