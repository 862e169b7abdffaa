#!/usr/bin/env bash
# Headline outputs of the issue-5 scenes (a few minutes: the modal maps solve 360 poses each).
set -euo pipefail
cd "$(dirname "$0")/.."
FL=.venv/bin/flexlink
OUT=${1:-out}
$FL synth minimax "100 deg" "20 deg"
$FL synth minimax "90 deg" "30 deg"
$FL synth brodell-soni "60 deg" "30 deg" --ground "400 mm"
$FL kinematics scenes/wiper.toml --out "$OUT"
$FL kinematics scenes/extended_rocker.toml --out "$OUT"
$FL prb scenes/compliant_wiper.toml --out "$OUT"
$FL cycle cases/case1.toml --out "$OUT"
$FL cycle scenes/wiper.toml --out "$OUT"
$FL cycle scenes/kineto_aluminium.toml --out "$OUT"
$FL cycle scenes/change_point.toml --out "$OUT"
