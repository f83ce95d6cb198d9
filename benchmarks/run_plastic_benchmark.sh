#!/usr/bin/env bash
# Plastic vs elastic C3D8R element rate on the same mesh (issue 14, Deliver 6): the block of
# make_block.py (N^3 elements, face x = 0 fixed, every other node at -10 m/s transverse), once
# elastic and once with *PLASTIC (yield YIELD Pa, 1 GPa hardening), run alternately (elastic
# then plastic, or plastic then elastic on even repetitions) with 1 and 2 threads, so that a
# shared machine's noise hits both alike. Prints best and median element-cycles/s per deck and
# thread count, and the plastic/elastic ratio; appends to benchmarks/results/plastic_block.csv.
# Environment: N (46), INCREMENTS (300), REPS (3), YIELD (1e8), XPL (build/release/apps/xpl).
# MODEL=shell runs the S4R plate of make_plate_benchmark.py instead (N 316, the 100k-shell
# plate; LOAD drive, the default: stretched at 20/s with the edges driven at the stretch's
# velocity, YIELD 50e6, every section point yields in every increment after the first 19, so
# INCREMENTS defaults to 400 there (95 % of the increments return everywhere); LOAD stretch: the
# same stretch as an initial velocity alone, which the release waves from the free edges stop,
# so the plate yields here and there (~12 % of the batch-increments of the 64² copy); LOAD
# pressure: 3 MPa on the plate, YIELD 250e6, the plate yields in bending) and appends to
# benchmarks/results/plastic_plate.csv. Each run also records the process's user CPU seconds,
# which a shared machine disturbs far less than the wall-clock rate (needs /usr/bin/time,
# Debian's package time).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
python=/usr/bin/python3
model=${MODEL:-hex}
if [[ $model == shell ]]; then n=${N:-316}; else n=${N:-46}; fi
reps=${REPS:-3}
load=${LOAD:-drive}
if [[ $model == shell && $load == drive ]]; then increments=${INCREMENTS:-400}; else increments=${INCREMENTS:-300}; fi
if [[ $model == shell && $load == pressure ]]; then yield=${YIELD:-250e6}; elif [[ $model == shell ]]; then yield=${YIELD:-50e6}; else yield=${YIELD:-1e8}; fi
xpl=${XPL:-build/release/apps/xpl}
work=build/bench/plastic_$model
mkdir -p "$work" benchmarks/results
if [[ $model == shell ]]; then
  csv=benchmarks/results/plastic_plate.csv
  [[ -f $csv ]] || echo "date,deck,threads,repetition,cycles_per_second,user_cpu_s,load" >"$csv"
  if [[ $load == pressure ]]; then plate_args=(--pressure 3e6); else plate_args=(--load "$load"); fi
  "$python" benchmarks/make_plate_benchmark.py -n "$n" --increments "$increments" "${plate_args[@]}" \
    --out "$work/elastic.inp" >/dev/null
  "$python" benchmarks/make_plate_benchmark.py -n "$n" --increments "$increments" "${plate_args[@]}" \
    --plastic "$yield" --out "$work/plastic.inp" >/dev/null
else
  csv=benchmarks/results/plastic_block.csv
  [[ -f $csv ]] || echo "date,deck,threads,repetition,cycles_per_second" >"$csv"
  "$python" benchmarks/make_block.py -n "$n" --increments "$increments" --out "$work/elastic.inp" >/dev/null
  "$python" benchmarks/make_block.py -n "$n" --increments "$increments" --yield-stress "$yield" \
    --out "$work/plastic.inp" >/dev/null
fi

stamp=$(date -u +%Y-%m-%dT%H:%M)
run() { # deck threads rep
  local rate cpu
  /usr/bin/time -f %U -o "$work/time_$1" env OMP_NUM_THREADS="$2" "$xpl" run "$work/$1.inp" \
    -o "$work/out_$1" --threads "$2" >"$work/log_$1" 2>&1
  rate=$(sed -n 's/^xpl: element cycles per second: *\([0-9.e+-]*\).*/\1/p' "$work/log_$1")
  cpu=$(tail -n 1 "$work/time_$1")
  if [[ $model == shell ]]; then
    echo "$stamp,$1,$2,$3,$rate,$cpu,$(cut -d' ' -f1 /proc/loadavg)" >>"$csv"
  else
    echo "$stamp,$1,$2,$3,$rate" >>"$csv"
  fi
  echo "$1 threads=$2 rep $3: $rate element-cycles/s, $cpu s user CPU"
}
for threads in 1 2; do
  for rep in $(seq 1 "$reps"); do
    if ((rep % 2)); then
      run elastic "$threads" "$rep"
      run plastic "$threads" "$rep"
    else
      run plastic "$threads" "$rep"
      run elastic "$threads" "$rep"
    fi
  done
done

"$python" - "$csv" "$stamp" <<'PY'
import csv, statistics, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["date"] == sys.argv[2]]
print("| threads | elastic best | elastic median | plastic best | plastic median | plastic/elastic (median) |")
print("|---:|---:|---:|---:|---:|---:|")
for threads in sorted({r["threads"] for r in rows}):
    rates = {d: [float(r["cycles_per_second"]) for r in rows
                 if r["threads"] == threads and r["deck"] == d] for d in ("elastic", "plastic")}
    e, p = rates["elastic"], rates["plastic"]
    print(f"| {threads} | {max(e):.4g} | {statistics.median(e):.4g} | {max(p):.4g} | "
          f"{statistics.median(p):.4g} | {statistics.median(p) / statistics.median(e):.3f} |")
if "user_cpu_s" in rows[0]:
    for threads in sorted({r["threads"] for r in rows}):
        cpu = {d: [float(r["user_cpu_s"]) for r in rows
                   if r["threads"] == threads and r["deck"] == d] for d in ("elastic", "plastic")}
        e, p = cpu["elastic"], cpu["plastic"]
        print(f"user CPU, {threads} thread(s): elastic best {min(e):.2f} s median "
              f"{statistics.median(e):.2f} s, plastic best {min(p):.2f} s median "
              f"{statistics.median(p):.2f} s, elastic/plastic CPU (median) "
              f"{statistics.median(e) / statistics.median(p):.3f}")
PY
