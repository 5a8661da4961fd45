#!/usr/bin/env bash
# The main job: install what is missing, build, export every preset to every target into out/export,
# then validate everything that was exported, writing the report into out/report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
export CRTFORGE_CACHE="${CRTFORGE_CACHE:-$PWD/build/cache}"
build/crtforge export --out out/export
build/crtforge validate --report out/report -j "$(nproc 2>/dev/null || echo 2)"
