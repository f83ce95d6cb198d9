#!/usr/bin/env bash
# S4R element-loop benchmark: a simply supported square plate of N x N S4R elements under a
# suddenly applied pressure, no output, run with 1 and 2 threads, best of REPS runs each.
# Writes benchmarks/results/shell_plate.csv (appends) and shell_plate.png and prints a
# markdown table for benchmarks/RESULTS.md. With SWEEP="100 224 316 ..." it then also runs
# plates of those sizes (all THREADS, best of REPS) into shell_plate_sweep.csv and .png;
# SWEEP_ONLY=1 skips the N x N measurement.
#
# Each run waits until the machine is quiet: the CPUs must be at least IDLE_MIN percent idle
# over a 2-second sample (other builds steal cycles from the OpenMP threads and stall them at
# the colour barriers); after WAIT_MAX seconds it runs anyway and says so.
#
# Environment overrides: N (elements per side, 316), INCREMENTS (300), REPS (5),
# THREADS ("1 2"), SWEEP (mesh sizes, none), SWEEP_ONLY=1, SKIP_BUILD=1 (use the existing
# build), XPL (binary, build/release/apps/xpl), RESULTS_DIR (benchmarks/results),
# IDLE_MIN (90), WAIT_MAX (600), DECK_ARGS (more options of make_plate_benchmark.py, e.g.
# "--load stretch --plastic 50e6" for the plastic plate of issue 14).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

n="${N:-316}"
increments="${INCREMENTS:-300}"
reps="${REPS:-5}"
threads_list="${THREADS:-1 2}"
sweep="${SWEEP:-}"
idle_min="${IDLE_MIN:-90}"
wait_max="${WAIT_MAX:-600}"
python=/usr/bin/python3 # Debian's python, which has matplotlib (a pyenv python may not)

if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  bash scripts/build.sh release
fi
xpl="${XPL:-build/release/apps/xpl}"
results_dir="${RESULTS_DIR:-benchmarks/results}"

bench_dir=build/bench
log_dir="$bench_dir/shell_logs"
mkdir -p "$log_dir"
rm -f "$log_dir"/run_n*_t*_r*.log "$log_dir"/run_n*_t*_r*.summary.json

bench_name=run_shell_benchmark
# shellcheck source=benchmarks/quiet_machine.sh
source benchmarks/quiet_machine.sh

# run_plate N THREADS REP: one run, its log path on stdout.
run_plate() {
  local size="$1" threads="$2" rep="$3"
  local deck="$bench_dir/plate_$size.inp"
  local log="$log_dir/run_n${size}_t${threads}_r${rep}.log"
  echo "run_shell_benchmark: plate $size x $size, $threads thread(s), repetition $rep of $reps" >&2
  wait_quiet >"$log"
  if ! OMP_NUM_THREADS="$threads" "$xpl" run "$deck" -o "$bench_dir/out" \
    --threads "$threads" >>"$log" 2>&1; then
    echo "run_shell_benchmark: xpl failed, see $log:" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
  grep -h '^bench:\|^xpl: element cycles per second' "$log" >&2 || true
  # The run's JOB.summary.json is what shell_benchmark.py reads (no stdout parsing).
  cp "$bench_dir/out/plate_$size.summary.json" "${log%.log}.summary.json"
  echo "${log%.log}.summary.json"
}

if [[ "${SWEEP_ONLY:-0}" != 1 ]]; then
  # shellcheck disable=SC2086 # DECK_ARGS is a list of options
  "$python" benchmarks/make_plate_benchmark.py -n "$n" --increments "$increments" \
    ${DECK_ARGS:-} --out "$bench_dir/plate_$n.inp"
  logs=()
  for threads in $threads_list; do
    for rep in $(seq 1 "$reps"); do
      logs+=("$(run_plate "$n" "$threads" "$rep")")
    done
  done
  "$python" benchmarks/shell_benchmark.py "${logs[@]}" \
    --csv "$results_dir/shell_plate.csv" --png "$results_dir/shell_plate.png"
fi

if [[ -n "$sweep" ]]; then
  for size in $sweep; do
    "$python" benchmarks/make_plate_benchmark.py -n "$size" --increments "$increments" \
      --out "$bench_dir/plate_$size.inp"
  done
  # Repetitions outermost: a noisy minute slows one repetition of every size, not every
  # repetition of one size.
  sweep_logs=()
  for rep in $(seq 1 "$reps"); do
    for size in $sweep; do
      for threads in $threads_list; do
        sweep_logs+=("$(run_plate "$size" "$threads" "$rep")")
      done
    done
  done
  "$python" benchmarks/shell_benchmark.py --sweep "${sweep_logs[@]}" \
    --csv "$results_dir/shell_plate_sweep.csv" --png "$results_dir/shell_plate_sweep.png"
fi
