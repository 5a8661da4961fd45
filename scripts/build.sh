#!/usr/bin/env bash
# Configures and builds crtforge into build/ (Release). Used by the README's two commands.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
# Progress lines are noise in CI logs; warnings and errors still show.
cmake --build build -j "$jobs" 2>&1 | { grep -vE '^\[ *[0-9]+%\]' || true; }
