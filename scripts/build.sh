#!/usr/bin/env bash
# Install missing dependencies, configure and build xpl with a CMake preset.
# Usage: scripts/build.sh [preset]    (release by default; see CMakePresets.json)
set -euo pipefail

preset="${1:-release}"
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/install_deps.sh
cmake --preset "$preset"
cmake --build --preset "$preset" -j"$(nproc)"
