#!/usr/bin/env bash
# Speed of two xpl builds on the same decks, alternated in the same minutes so that the
# machine's noise hits both alike (a shared machine: never compare runs made at different
# times). For each deck, thread count and repetition it runs OLD then NEW (or NEW then OLD on
# odd repetitions) and records the element-cycles/s each run prints.
#   bash benchmarks/compare_builds.sh OLD/xpl NEW/xpl [REPS]
# Decks: the hex block (make_block.py -n 46), the S4R plate (make_plate_benchmark.py -n 316)
# and the contact block (make_contact_benchmark.py --n 40 --m 30), as in RESULTS.md.
# DECKS="hex shell" picks decks. Writes benchmarks/results/compare_builds.csv (appends) and prints best and median per build.
set -euo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: $0 OLD_XPL NEW_XPL [REPS]" >&2
  exit 2
fi
old=$1
new=$2
reps=${3:-3}
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
python=/usr/bin/python3
work=build/bench/compare
mkdir -p "$work"
csv=benchmarks/results/compare_builds.csv
[[ -f $csv ]] || echo "date,deck,threads,build,repetition,cycles_per_second" >"$csv"

"$python" benchmarks/make_block.py -n 46 --increments 300 --out "$work/hex.inp" >/dev/null
"$python" benchmarks/make_plate_benchmark.py -n 316 --increments 300 --out "$work/shell.inp" >/dev/null
"$python" benchmarks/make_contact_benchmark.py "$work/contact.inp" --n 40 --m 30 \
  --increments 200 >/dev/null

stamp=$(date -u +%Y-%m-%dT%H:%M)
run() { # deck threads build binary rep
  local rate
  local log summary="$work/out_$3/$1.summary.json"
  rm -f "$summary"
  log=$(OMP_NUM_THREADS=$2 "$4" run "$work/$1.inp" -o "$work/out_$3" --threads "$2" 2>&1)
  # A binary with the run summary writes JOB.summary.json; an older one only prints the figure.
  if [[ -f $summary ]]; then
    rate=$("$python" -c 'import json, sys; print(json.load(open(sys.argv[1]))["element_cycles_per_second"])' "$summary")
  else
    rate=$(sed -n 's/^xpl: element cycles per second: *\([0-9.e+-]*\).*/\1/p' <<<"$log")
  fi
  echo "$stamp,$1,$2,$3,$5,$rate" >>"$csv"
  echo "$1 threads=$2 $3 rep $5: $rate"
}
for deck in ${DECKS:-hex shell contact}; do
  for threads in 1 2; do
    for rep in $(seq 1 "$reps"); do
      if ((rep % 2)); then
        run "$deck" "$threads" old "$old" "$rep"
        run "$deck" "$threads" new "$new" "$rep"
      else
        run "$deck" "$threads" new "$new" "$rep"
        run "$deck" "$threads" old "$old" "$rep"
      fi
    done
  done
done

"$python" - "$csv" "$stamp" <<'PY'
import csv, statistics, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["date"] == sys.argv[2]]
print("| deck | threads | old best | old median | new best | new median | new/old (median) |")
print("|---|---:|---:|---:|---:|---:|---:|")
keys = sorted({(r["deck"], r["threads"]) for r in rows}, key=lambda k: (["hex", "shell", "contact"].index(k[0]), k[1]))
for deck, threads in keys:
    rate = {b: [float(r["cycles_per_second"]) / 1e6 for r in rows
                if r["deck"] == deck and r["threads"] == threads and r["build"] == b]
            for b in ("old", "new")}
    mo, mn = statistics.median(rate["old"]), statistics.median(rate["new"])
    print(f"| {deck} | {threads} | {max(rate['old']):.2f} | {mo:.2f} | {max(rate['new']):.2f} | {mn:.2f} | {mn / mo:.3f} |")
PY
