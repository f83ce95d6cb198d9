#!/usr/bin/env bash
# Install missing dependencies, build xpl with a preset and run its test suite.
# Usage: scripts/run_tests.sh [preset]    (release by default)
# Exit code: ctest's.
set -euo pipefail

preset="${1:-release}"
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/build.sh "$preset"

# CMakePresets.json has test presets for release and sanitize only; other presets are
# tested straight from their build directory.
case "$preset" in
  release | sanitize) ctest_target=(--preset "$preset") ;;
  *) ctest_target=(--test-dir "build/$preset") ;;
esac

set +e
ctest "${ctest_target[@]}" --output-on-failure -j2
status=$?
set -e
exit "$status"
