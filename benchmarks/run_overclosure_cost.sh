#!/usr/bin/env bash
# Cost of the initial-overclosure pass (issue 5, P2) on the contact benchmark deck (two blocks
# of N x N x M C3D8R, ALL EXTERIOR, no overclosure): `xpl check` runs the pass once and stops.
# Prints the .sta summary per thread count and appends to
# benchmarks/results/overclosure_cost.csv (threads, faces pass s, crossed-check s).
# Environment: N (40), M (30), THREADS ("1 2"), XPL (build/release/apps/xpl), IDLE_MIN (90),
# WAIT_MAX (600).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
xpl="${XPL:-build/release/apps/xpl}"
idle_min="${IDLE_MIN:-90}"
wait_max="${WAIT_MAX:-600}"
bench_name=run_overclosure_cost
# shellcheck source=benchmarks/quiet_machine.sh
source benchmarks/quiet_machine.sh
dir=build/bench/overclosure
mkdir -p "$dir"
/usr/bin/python3 benchmarks/make_contact_benchmark.py "$dir/contact_block.inp" \
  --n "${N:-40}" --m "${M:-30}"
csv=benchmarks/results/overclosure_cost.csv
[[ -f "$csv" ]] || echo "date,elements,threads,pass_s,crossed_check_s" >"$csv"
for t in ${THREADS:-1 2}; do
  wait_quiet
  "$xpl" check "$dir/contact_block.inp" -o "$dir/t$t" --threads "$t" -q
  line="$(grep 'initial overclosures' "$dir/t$t/contact_block.sta")"
  echo "threads $t: $line"
  pass="$(sed -E 's/.*; pass ([0-9.e+-]+) s.*/\1/' <<<"$line")"
  crossed="$(sed -E 's/.*check ([0-9.e+-]+) s\).*/\1/' <<<"$line")"
  echo "$(date -u +%F),$((2 * ${N:-40} * ${N:-40} * ${M:-30})),$t,$pass,$crossed" >>"$csv"
done
