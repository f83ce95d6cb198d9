#!/usr/bin/env bash
# 1 rank x 2 threads against 2 ranks x 1 thread on the 100k-hex block (issue 37 acceptance:
# within 15 % of each other), run alternately, PAIRS pairs; prints each run's rate (element
# cycles per second of the time loop, JOB.summary.json), each rank's share of the loop in
# exchanges and collectives (JOB.msg), the load average before each run, and the medians.
# Usage: benchmarks/run_mpi_pairs.sh XPL [LABEL]   (XPL: an XPL_MPI=ON build's xpl)
#   N (elements per edge, 46: 97 336 C3D8R), INCREMENTS (150), PAIRS (5), OUT (build/bench_mpi)
set -euo pipefail

xpl="$1"
label="${2:-run}"
n="${N:-46}"
increments="${INCREMENTS:-150}"
pairs="${PAIRS:-5}"
out="${OUT:-build/bench_mpi}/$label"
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

mkdir -p "$out"
deck="$out/block_$n.inp"
/usr/bin/python3 "$repo_root/benchmarks/make_block.py" -n "$n" --increments "$increments" \
  --out "$deck" > /dev/null
mpirun_flags=(--oversubscribe --mca btl self,vader)
if [[ $(id -u) -eq 0 ]]; then mpirun_flags+=(--allow-run-as-root); fi
export OMP_WAIT_POLICY=PASSIVE

rate() { /usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['element_cycles_per_second'])" "$1"; }
share() { grep -o 'in the time loop ([0-9.]* %' "$1" | grep -o '[0-9.]* ' | tr -d ' ' | paste -sd/; }

for p in $(seq 1 "$pairs"); do
  for kind in 1x2 2x1; do
    dir="$out/${kind}_$p"
    rm -rf "$dir" && mkdir -p "$dir"
    load=$(cut -d' ' -f1 /proc/loadavg)
    if [[ $kind == 1x2 ]]; then
      "$xpl" run "$deck" -o "$dir" --quiet --threads 2 > "$dir/stdout" 2>&1
    else
      mpirun "${mpirun_flags[@]}" -np 2 "$xpl" run "$deck" -o "$dir" --quiet --threads 1 \
        > "$dir/stdout" 2>&1
    fi
    job=$(basename "$deck" .inp)
    echo "$label pair $p $kind rate $(rate "$dir/$job.summary.json") load $load exchange% $(share "$dir/$job.msg")"
  done
done | tee "$out/runs.txt"
/usr/bin/python3 - "$out/runs.txt" <<'EOF'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
rate = {k: [float(r[5]) for r in rows if r[3] == k] for k in ("1x2", "2x1")}
load = [float(r[7]) for r in rows]
share = [float(x) for r in rows if r[3] == "2x1" for x in r[9].split("/")]
m12, m21 = statistics.median(rate["1x2"]), statistics.median(rate["2x1"])
print(f"median rate 1x2 {m12 / 1e6:.3f} M/s, 2x1 {m21 / 1e6:.3f} M/s: 2x1 is "
      f"{100 * (m21 / m12 - 1):+.1f} % of 1x2; load {min(load):.1f}-{max(load):.1f} "
      f"(median {statistics.median(load):.1f}); exchange share of 2x1 ranks median "
      f"{statistics.median(share):.0f} % ({min(share):.0f}-{max(share):.0f})")
EOF
