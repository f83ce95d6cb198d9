#!/usr/bin/env bash
# 1 rank x 2 threads against 2 ranks x 1 thread on the 100k-hex block (issue 37 acceptance:
# within 15 % of each other), run alternately, PAIRS pairs; prints each run's rate (element
# cycles per second of the time loop, every rank's elements), each rank's share of the loop in
# exchanges and collectives and in the neighbour exchange alone (JOB.msg; "total:neighbours"
# per rank, waits for the other rank included), the CPU time of the run (every rank, setup
# included), the load average before each run, and the medians.
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
mpirun_flags=(--oversubscribe --mca btl "self,vader")
if [[ $(id -u) -eq 0 ]]; then mpirun_flags+=(--allow-run-as-root); fi
export OMP_WAIT_POLICY=PASSIVE

# Element cycles per second of the time loop: the summary's on one rank; on N ranks every
# rank's elements (JOB.msg) x increments / rank 0's time loop, as the summary of a build
# before 2026-12-06 11:00 counted rank 0's elements only.
rate() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import json, re, sys
summary = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
elements = [int(x) for x in re.findall(r"mpi: rank \d+: (\d+) elements", text)]
loop = re.search(r"mpi: rank 0: exchanges and collectives \S+ s of (\S+) s", text)
if elements and loop:
    print(sum(elements) * summary["increments"] / float(loop.group(1)))
else:
    print(summary["element_cycles_per_second"])
PY
}
# Per rank: exchanges and collectives, then the neighbour exchange alone, as % of the time loop.
share() {
  /usr/bin/python3 - "$1" <<'PY'
import re, sys
out = []
for line in open(sys.argv[1]):
    m = re.search(r"exchanges and collectives (\S+) s of (\S+) s .*neighbours (\S+) s", line)
    if m:
        total, loop, neighbours = (float(x) for x in m.groups())
        out.append(f"{100 * total / loop:.0f}:{100 * neighbours / loop:.0f}")
print("/".join(out) or "-")
PY
}

for p in $(seq 1 "$pairs"); do
  for kind in 1x2 2x1; do
    dir="$out/${kind}_$p"
    rm -rf "$dir" && mkdir -p "$dir"
    load=$(cut -d' ' -f1 /proc/loadavg)
    # CPU time (user + system) of the run, every rank included, s.
    if [[ $kind == 1x2 ]]; then
      /usr/bin/time -o "$dir/time" -f "%U %S" "$xpl" run "$deck" -o "$dir" --quiet --threads 2 \
        > "$dir/stdout" 2>&1
    else
      /usr/bin/time -o "$dir/time" -f "%U %S" mpirun "${mpirun_flags[@]}" -np 2 "$xpl" run "$deck" \
        -o "$dir" --quiet --threads 1 > "$dir/stdout" 2>&1
    fi
    job=$(basename "$deck" .inp)
    cpu=$(awk '{print $1 + $2}' "$dir/time")
    echo "$label pair $p $kind rate $(rate "$dir/$job.summary.json" "$dir/$job.msg") load $load exchange% $(share "$dir/$job.msg") cpu_s $cpu"
  done
done | tee "$out/runs.txt"
/usr/bin/python3 - "$out/runs.txt" <<'EOF'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
rate = {k: [float(r[5]) for r in rows if r[3] == k] for k in ("1x2", "2x1")}
load = [float(r[7]) for r in rows]
share = [float(x.split(":")[0]) for r in rows if r[3] == "2x1" for x in r[9].split("/")]
neighbours = [float(x.split(":")[1]) for r in rows if r[3] == "2x1" for x in r[9].split("/")]
cpu = {k: [float(r[11]) for r in rows if r[3] == k] for k in ("1x2", "2x1")}
m12, m21 = statistics.median(rate["1x2"]), statistics.median(rate["2x1"])
print(f"median rate 1x2 {m12 / 1e6:.3f} M/s, 2x1 {m21 / 1e6:.3f} M/s: 2x1 is "
      f"{100 * (m21 / m12 - 1):+.1f} % of 1x2; load {min(load):.1f}-{max(load):.1f} "
      f"(median {statistics.median(load):.1f}); exchange share of 2x1 ranks median "
      f"{statistics.median(share):.0f} % ({min(share):.0f}-{max(share):.0f}), of which the "
      f"neighbour exchange {statistics.median(neighbours):.0f} % "
      f"({min(neighbours):.0f}-{max(neighbours):.0f}); CPU time median 1x2 "
      f"{statistics.median(cpu['1x2']):.1f} s, 2x1 {statistics.median(cpu['2x1']):.1f} s")
EOF
