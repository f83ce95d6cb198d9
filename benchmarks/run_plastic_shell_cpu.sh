#!/usr/bin/env bash
# Plastic vs elastic S4R element loop of two xpl builds in CPU time (issue 38 item 1): the
# stretched plate of make_plate_benchmark.py (N² shells, --load stretch), once elastic and
# once elastic–perfectly plastic at YIELD Pa (every section point yields in every increment),
# run REPS times per build, deck and thread count, builds and decks alternated in the same
# minutes. A shared machine's load stretches wall time several-fold; the CPU time of the
# element kernel (perf samples at 2 kHz, software clock, so no hardware counters are needed, in
# Shell4rBlock::compute_batch and the plastic return's functions where they are not inlined)
# is far steadier. Prints per build and thread count the median
# element-cycles per CPU-second of the kernel for both decks and their ratio, and the median
# element-cycles/s xpl itself prints (wall time of the internal-force phase).
#   bash benchmarks/run_plastic_shell_cpu.sh OLD/xpl NEW/xpl
# Environment: N (200), INCREMENTS (200), REPS (5), YIELD (50e6), THREADS ("1 2").
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
old=$1
new=$2
n=${N:-200}
increments=${INCREMENTS:-200}
reps=${REPS:-5}
yield=${YIELD:-50e6}
work=build/bench/plastic_shell_cpu
mkdir -p "$work"
/usr/bin/python3 benchmarks/make_plate_benchmark.py -n "$n" --increments "$increments" \
  --load stretch --out "$work/elastic.inp" >/dev/null
/usr/bin/python3 benchmarks/make_plate_benchmark.py -n "$n" --increments "$increments" \
  --load stretch --plastic "$yield" --out "$work/plastic.inp" >/dev/null
rows=$work/rows.txt
: >"$rows"
run() { # build xpl deck threads
  local log=$work/log_$1_$3_$4
  perf record -q -e cpu-clock -F 2000 -o "$work/perf.data" env OMP_NUM_THREADS="$4" "$2" run \
    "$work/$3.inp" -o "$work/out_$1_$3" --threads "$4" >"$log" 2>&1
  local samples rate cycles
  samples=$(perf report -q -n -i "$work/perf.data" --stdio --sort symbol 2>/dev/null |
    awk '/Shell4rBlock::compute_batch|ShellPlasticState::|return_lanes|newton_return_lanes|finish_unconverged|bisect_lane/ {s += $2} END {print s + 0}')
  rate=$(sed -n 's/^xpl: element cycles per second: *\([0-9.e+-]*\).*/\1/p' "$log")
  cycles=$(sed -n 's/^xpl: element cycles per second: [0-9.e+-]* (\([0-9]*\) elements x \([0-9]*\) increments.*/\1 \2/p' "$log")
  echo "$1 $3 $4 $samples $rate $cycles" >>"$rows"
}
for threads in ${THREADS:-1 2}; do
  for rep in $(seq 1 "$reps"); do
    if ((rep % 2)); then order="old new"; else order="new old"; fi
    for b in $order; do
      x=$old
      [[ $b == new ]] && x=$new
      if ((rep % 2)); then decks="elastic plastic"; else decks="plastic elastic"; fi
      for d in $decks; do run "$b" "$x" "$d" "$threads"; done
    done
  done
done
/usr/bin/python3 - "$rows" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
cpu, wall = {}, {}
for b, d, t, samples, rate, elements, increments in rows:
    key = (b, t, d)
    cpu.setdefault(key, []).append(int(elements) * int(increments) / (int(samples) / 2000.0))
    wall.setdefault(key, []).append(float(rate))
print("| build | threads | elastic kernel, M el-cycles per CPU-s | plastic | plastic / elastic | elastic, M/s wall | plastic, M/s wall | plastic / elastic (wall) |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for b in ("old", "new"):
    for t in sorted({r[2] for r in rows}):
        e, p = statistics.median(cpu[(b, t, "elastic")]), statistics.median(cpu[(b, t, "plastic")])
        we, wp = statistics.median(wall[(b, t, "elastic")]), statistics.median(wall[(b, t, "plastic")])
        print(f"| {b} | {t} | {e/1e6:.2f} | {p/1e6:.2f} | {p/e:.3f} | {we/1e6:.2f} | {wp/1e6:.2f} | {wp/we:.3f} |")
print(f"({len(cpu[('old', rows[0][2], 'elastic')])} runs each; CPU rates: elements x increments over the kernel's CPU seconds summed over threads)")
PY
