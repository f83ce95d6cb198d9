#!/usr/bin/env bash
# Cost of per-contribution slots against today's direct scatter (issue 37 item 3,
# benchmarks/slot_assembly_micro.cpp), on the hex block of the element benchmark.
# Usage: bash benchmarks/run_slot_assembly_micro.sh [N (46)] [PARTS ("2 8")] [REPS (7)]
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
n="${1:-46}"
parts="${2:-2 8}"
reps="${3:-7}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
g++ -std=c++20 -O3 -march=native -DNDEBUG -DXPL_HAVE_METIS=0 -I. -I/usr/include/eigen3 \
  benchmarks/slot_assembly_micro.cpp partition/exchange_plan.cpp partition/mesh_partition.cpp \
  partition/element_graph.cpp partition/bisection.cpp partition/metis_graph.cpp -o "$work/micro"
for p in $parts; do
  "$work/micro" "$n" "$p" "$reps"
done
