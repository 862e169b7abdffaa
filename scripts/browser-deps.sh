#!/usr/bin/env bash
# Debian packages for the browser test of the HTML report (tests/output/test_report_browser.py):
# headless Chromium, driven by playwright for Python through executable_path (playwright's own
# browser download cannot work without the wider network, so it is never used). Installs only
# what is missing; without them the browser test skips.
set -euo pipefail
bash "$(dirname "$0")/apt-missing.sh" "headless browser for the report test" \
    chromium fonts-dejavu-core
