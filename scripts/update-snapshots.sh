#!/usr/bin/env bash
# Rewrites the snapshot tests' expected files from the current build, then shows what changed so
# the change can be reviewed before it is committed (tests/snapshots/README.md).
#   scripts/update-snapshots.sh [BUILD_DIR]    (default: build/, built by scripts/build.sh if missing)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
# A build dir given on the command line is relative to where the script was started.
if [[ $# -ge 1 ]]; then build_dir="$(realpath -m -- "$1")"; else build_dir="$root/build"; fi
cd "$root"

if [[ ! -x "$build_dir/crtforge" ]]; then
  if [[ "$build_dir" != "$root/build" ]]; then
    echo "update-snapshots: $build_dir/crtforge not found (build it first)" >&2
    exit 2
  fi
  scripts/build.sh
fi
tests_bin="$build_dir/tests/crtforge_tests"
if [[ ! -x "$tests_bin" ]]; then
  echo "update-snapshots: $tests_bin not found (build the tests first)" >&2
  exit 2
fi

snap=tests/snapshots
# The export, from the source root with a relative --templates path (the test loads the templates
# through an absolute one, so a path leaking into an output fails it). Written beside the old set
# and swapped in only when it succeeded, so files no longer exported disappear.
fresh="$snap/expected.tmp-update"
rm -rf "$fresh"
"$build_dir/crtforge" --templates "$snap/templates" --no-cache export --out "$fresh" >/dev/null
rm -rf "$snap/expected"
mv "$fresh" "$snap/expected"

# The raw WGSL cases: the snapshot test writes the .wgsl files instead of comparing when asked to
# (and removes those whose .frag is gone).
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! CRTFORGE_UPDATE_SNAPSHOTS=1 "$tests_bin" "[snapshot][wgsl]" >"$log" 2>&1; then
  cat "$log" >&2
  echo "update-snapshots: writing the WGSL case files failed" >&2
  exit 1
fi

echo "== git diff --stat -- $snap"
git --no-pager diff --stat -- "$snap"
echo "== git status --short -- $snap"
git status --short -- "$snap"
echo "Review: git diff -- $snap   (untracked files are listed by git status above)"
