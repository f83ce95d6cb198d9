#!/usr/bin/env bash
# Install missing dependencies, configure and build xpl with a CMake preset.
# Usage: scripts/build.sh [preset [target...]]
#   preset: release by default (see CMakePresets.json)
#   target: build only these CMake targets (e.g. xpl, the program); all targets by default
set -euo pipefail

preset="${1:-release}"
shift || true
targets=("$@")
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/install_deps.sh
cmake --preset "$preset"
if [[ ${#targets[@]} -gt 0 ]]; then
  cmake --build --preset "$preset" -j"$(nproc)" --target "${targets[@]}"
else
  cmake --build --preset "$preset" -j"$(nproc)"
fi
