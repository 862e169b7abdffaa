#!/usr/bin/env bash
# Debian packages for the browser test of the HTML report (tests/test_report_browser.py):
# headless Chromium, driven by playwright for Python through executable_path (playwright's own
# browser download cannot work without the wider network, so it is never used). Installs only
# what is missing (apt-get needs root, as on CI); elsewhere it warns and the browser test skips.
set -euo pipefail
PACKAGES=(chromium fonts-dejavu-core)

command -v dpkg-query >/dev/null 2>&1 || exit 0  # not Debian: nothing this script can do
missing=()
for package in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$package")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "browser-deps: missing ${missing[*]} (needed by the report's browser test); install" \
         "them as root: apt-get install -y ${missing[*]}" >&2
    exit 0
fi
echo "browser-deps: installing ${missing[*]} (headless browser for the report test)" >&2
export DEBIAN_FRONTEND=noninteractive
if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >&2; then
    echo "browser-deps: apt-get failed; the report's browser test will skip" >&2
fi
