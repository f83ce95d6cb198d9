#!/usr/bin/env bash
# Install missing dependencies, configure and build xpl with a CMake preset.
# Usage: scripts/build.sh [preset [target...]]
#   preset: release by default (see CMakePresets.json)
#   target: build only these CMake targets (e.g. xpl, the program); all targets by default
#   XPL_WERROR=ON|OFF  configure with warnings as errors, or without (the CMake option
#                      XPL_WERROR; unset leaves the build directory's setting, OFF when new)
set -euo pipefail

preset="${1:-release}"
shift || true
targets=("$@")
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/install_deps.sh
configure_args=()
if [[ -n ${XPL_WERROR:-} ]]; then configure_args+=(-DXPL_WERROR="$XPL_WERROR"); fi
cmake --preset "$preset" "${configure_args[@]}"
if [[ ${#targets[@]} -gt 0 ]]; then
  cmake --build --preset "$preset" -j"$(nproc)" --target "${targets[@]}"
else
  cmake --build --preset "$preset" -j"$(nproc)"
fi
