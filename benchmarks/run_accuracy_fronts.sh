#!/usr/bin/env bash
# Error against run time over mesh refinement, xpl beside CalculiX 2.20 (issue 16, item 1).
# Installs CalculiX (Debian's calculix-ccx) when it is missing and the script runs as root,
# builds xpl, runs every case of benchmarks/accuracy/cases.py (each mesh level with both
# solvers, alternating, at 1 and 2 threads) and writes benchmarks/accuracy/results/:
# CASE.csv, CASE.png and fronts.md (the tables for benchmarks/RESULTS.md).
# Takes about 8 minutes of CPU (three quarters of it CalculiX's); on the shared 2-core
# machine under a load average of 20 that was 40 minutes of wall time.
# The committed results (2026-12-06) are from REPEAT=1, every case; those of 2026-12-02 (in
# benchmarks/RESULTS.md) had the bar cases from REPEAT=5 (the tables use the fastest repeat).
# Environment overrides: CASES (comma list, default all), REPEAT (runs per configuration,
# 1), SKIP_BUILD=1 (use the existing build), XPL (binary, build/release/apps/xpl),
# CCX (CalculiX binary; CCX=none: xpl only), WORK_DIR (build/accuracy),
# RESULTS_DIR (benchmarks/accuracy/results).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
python=/usr/bin/python3 # Debian's python, which has h5py and matplotlib

ccx="${CCX:-}"
if [[ -z "$ccx" ]]; then
  if ! command -v ccx >/dev/null 2>&1; then
    if [[ $(id -u) -eq 0 ]]; then
      echo "run_accuracy_fronts: installing calculix-ccx"
      export DEBIAN_FRONTEND=noninteractive
      apt_options=(-qq -y -o Dpkg::Use-Pty=0 -o APT::Install-Recommends=false)
      apt-get "${apt_options[@]}" install calculix-ccx >/dev/null </dev/null ||
        { apt-get "${apt_options[@]}" update >/dev/null &&
          apt-get "${apt_options[@]}" install calculix-ccx >/dev/null </dev/null; }
    else
      echo "run_accuracy_fronts: CalculiX (ccx) is missing; as root: apt-get install -y" \
        "calculix-ccx (or CCX=none for xpl only)" >&2
      exit 1
    fi
  fi
  ccx="$(command -v ccx)"
fi

if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  bash scripts/build.sh release xpl
fi
xpl="${XPL:-build/release/apps/xpl}"

args=("$xpl" --work "${WORK_DIR:-build/accuracy}" --results
  "${RESULTS_DIR:-benchmarks/accuracy/results}" --repeat "${REPEAT:-1}")
[[ "$ccx" == none ]] && args+=(--ccx "") || args+=(--ccx "$ccx")
[[ -n "${CASES:-}" ]] && args+=(--cases "$CASES")
exec "$python" benchmarks/accuracy/fronts.py "${args[@]}"
