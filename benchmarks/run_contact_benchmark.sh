#!/usr/bin/env bash
# Contact benchmark: two N x N x M C3D8R blocks (h = 1 mm; default 2 x 48 000 = 96 000 hexes),
# one at 10 m/s into the other, general contact with ALL EXTERIOR, no output, run with 1 and 2
# threads, best of REPS runs each; and the same mesh without *CONTACT, for the element time
# alone. Writes benchmarks/results/contact_block.csv and contact_block_nocontact.csv (appends)
# with their plots, and prints markdown tables for benchmarks/RESULTS.md. The issue's target:
# contact search + contact force at most 50 % of the internal-force (element) time.
#
# Each run waits until the machine is quiet (see run_shell_benchmark.sh).
#
# Environment overrides: N (40), M (30), INCREMENTS (200), REPS (3), THREADS ("1 2"),
# SKIP_BUILD=1, XPL (build/release/apps/xpl), RESULTS_DIR (benchmarks/results), IDLE_MIN (90),
# WAIT_MAX (600).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

n="${N:-40}"
m="${M:-30}"
increments="${INCREMENTS:-200}"
reps="${REPS:-3}"
threads_list="${THREADS:-1 2}"
idle_min="${IDLE_MIN:-90}"
wait_max="${WAIT_MAX:-600}"
python=/usr/bin/python3 # Debian's python, which has matplotlib (a pyenv python may not)

if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  bash scripts/build.sh release
fi
xpl="${XPL:-build/release/apps/xpl}"
results_dir="${RESULTS_DIR:-benchmarks/results}"

bench_dir=build/bench
log_dir="$bench_dir/contact_logs"
mkdir -p "$log_dir"
rm -f "$log_dir"/run_*.log "$log_dir"/run_*.summary.json

bench_name=run_contact_benchmark
# shellcheck source=benchmarks/quiet_machine.sh
source benchmarks/quiet_machine.sh

# run_case NAME THREADS REP: one run, its log path on stdout.
run_case() {
  local name="$1" threads="$2" rep="$3"
  local log="$log_dir/run_${name}_t${threads}_r${rep}.log"
  echo "run_contact_benchmark: $name, $threads thread(s), repetition $rep of $reps" >&2
  wait_quiet >"$log"
  if ! OMP_NUM_THREADS="$threads" "$xpl" run "$bench_dir/$name.inp" -o "$bench_dir/out" \
    --threads "$threads" >>"$log" 2>&1; then
    echo "run_contact_benchmark: xpl failed, see $log:" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
  grep -h '^bench:\|^xpl: element cycles per second\|^xpl: phase' "$log" >&2 || true
  # The run's JOB.summary.json is what hex_benchmark.py reads (no stdout parsing).
  cp "$bench_dir/out/$name.summary.json" "${log%.log}.summary.json"
  echo "${log%.log}.summary.json"
}

"$python" benchmarks/make_contact_benchmark.py "$bench_dir/contact.inp" --n "$n" --m "$m" \
  --increments "$increments"
"$python" benchmarks/make_contact_benchmark.py "$bench_dir/nocontact.inp" --n "$n" --m "$m" \
  --increments "$increments" --no-contact
for name in contact nocontact; do
  logs=()
  for rep in $(seq 1 "$reps"); do
    for threads in $threads_list; do
      logs+=("$(run_case "$name" "$threads" "$rep")")
    done
  done
  suffix=""
  [[ "$name" == nocontact ]] && suffix="_nocontact"
  "$python" benchmarks/hex_benchmark.py "${logs[@]}" \
    --csv "$results_dir/contact_block$suffix.csv" --png "$results_dir/contact_block$suffix.png"
done
