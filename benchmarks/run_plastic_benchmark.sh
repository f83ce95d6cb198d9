#!/usr/bin/env bash
# Plastic vs elastic C3D8R element rate on the same mesh (issue 14, Deliver 6): the block of
# make_block.py (N^3 elements, face x = 0 fixed, every other node at -10 m/s transverse), once
# elastic and once with *PLASTIC (yield YIELD Pa, 1 GPa hardening), run alternately (elastic
# then plastic, or plastic then elastic on even repetitions) with 1 and 2 threads, so that a
# shared machine's noise hits both alike. Prints best and median element-cycles/s per deck and
# thread count, and the plastic/elastic ratio; appends to benchmarks/results/plastic_block.csv.
# Environment: N (46), INCREMENTS (300), REPS (3), YIELD (1e8), XPL (build/release/apps/xpl).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
python=/usr/bin/python3
n=${N:-46}
increments=${INCREMENTS:-300}
reps=${REPS:-3}
yield=${YIELD:-1e8}
xpl=${XPL:-build/release/apps/xpl}
work=build/bench/plastic
mkdir -p "$work" benchmarks/results
csv=benchmarks/results/plastic_block.csv
[[ -f $csv ]] || echo "date,deck,threads,repetition,cycles_per_second" >"$csv"
"$python" benchmarks/make_block.py -n "$n" --increments "$increments" --out "$work/elastic.inp" >/dev/null
"$python" benchmarks/make_block.py -n "$n" --increments "$increments" --yield-stress "$yield" \
  --out "$work/plastic.inp" >/dev/null

stamp=$(date -u +%Y-%m-%dT%H:%M)
run() { # deck threads rep
  local rate
  rate=$(OMP_NUM_THREADS=$2 "$xpl" run "$work/$1.inp" -o "$work/out_$1" --threads "$2" 2>&1 |
    sed -n 's/^xpl: element cycles per second: *\([0-9.e+-]*\).*/\1/p')
  echo "$stamp,$1,$2,$3,$rate" >>"$csv"
  echo "$1 threads=$2 rep $3: $rate"
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
PY
