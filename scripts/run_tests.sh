#!/usr/bin/env bash
# Install missing dependencies, build xpl with a preset and run its test suite, then fuzz the
# deck reader under address+undefined sanitizers.
# Usage: scripts/run_tests.sh [preset]    (release by default)
#   XPL_FUZZ_DECKS=N  mutated decks for the sanitizer fuzz stage (default 1000, 0 skips it;
#                     about 0.25 s of CPU per deck under the sanitizers, so 1000 keep CI short);
#                     the stage builds only the xpl program with the sanitize preset.
# Exit code: ctest's, else the fuzzer's (1 when it found a crash, hang or sanitizer report).
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
if [[ $status -ne 0 ]]; then exit "$status"; fi

fuzz_decks="${XPL_FUZZ_DECKS:-1000}"
if [[ $fuzz_decks -gt 0 ]]; then
  [[ $preset == sanitize ]] || bash scripts/build.sh sanitize xpl
  python3 tests/fuzz/fuzz_decks.py --xpl build/sanitize/apps/xpl --count "$fuzz_decks" \
    --seed 1 --timeout 10 --keep build/sanitize/fuzz-findings
fi
