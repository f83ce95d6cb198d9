#!/usr/bin/env bash
# Plastic vs elastic S4R element pass by instruction count (issue 38 item 1): callgrind counts
# the instructions of Shell4rBlock::forces_of_part (everything it calls) on the 64² plate with
# the 316² benchmark plate's elements (side 0.2025 m), elastic, plastic with nothing yielding
# (σ_y = 1e12) and plastic at YIELD; 1 thread. Counts are exactly repeatable on one binary, so
# they decide where wall times on a shared host cannot. valgrind cannot run AVX-512: build xpl
# for AVX2 first, e.g.
#   cmake -S . -B build/avx2 -DCMAKE_BUILD_TYPE=Release -DXPL_NATIVE=OFF \
#     -DCMAKE_CXX_FLAGS=-march=x86-64-v3 && cmake --build build/avx2 -j2 --target xpl
# Environment: XPL (build/avx2/apps/xpl), LOAD (drive: the edges driven at the stretch rate,
# every section point yields in every increment after the first 19; stretch: the initial
# stretch alone, which yields in ~12 % of the batch-increments), N (64), SIDE (0.2025),
# INCREMENTS (400: 95 % of them return everywhere with LOAD drive), YIELD (50e6), DECKS (the
# decks to count: elastic nothing_yielding plastic), CALLGRIND_ARGS (more valgrind options, e.g.
# --dump-instr=yes for per-instruction counts; the totals do not change), WORK (the output
# directory, build/bench/plastic_callgrind). Prints instructions per element-increment and the
# elastic / plastic ratio (the plastic / elastic element rate at equal instructions per second).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
python=/usr/bin/python3
xpl=${XPL:-build/avx2/apps/xpl}
load=${LOAD:-drive}
n=${N:-64}
side=${SIDE:-0.2025}
increments=${INCREMENTS:-400}
yield=${YIELD:-50e6}
work=${WORK:-build/bench/plastic_callgrind}
mkdir -p "$work"

count() { # name [--plastic value]
  local name=$1 deck=$work/$1.inp
  shift
  "$python" benchmarks/make_plate_benchmark.py -n "$n" --side "$side" --increments "$increments" \
    --load "$load" "$@" --out "$deck" >/dev/null
  OMP_WAIT_POLICY=PASSIVE OMP_NUM_THREADS=1 valgrind --tool=callgrind \
    --callgrind-out-file="$work/callgrind_$name.out" \
    --toggle-collect='*Shell4rBlock::forces_of_part*' ${CALLGRIND_ARGS:-} \
    "$xpl" run "$deck" -o "$work/out_$name" --threads 1 >"$work/log_$name" 2>&1
  local instructions steps
  instructions=$(sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$work/callgrind_$name.out")
  steps=$(sed -n 's/^xpl: .* \([0-9][0-9]*\) increments.*/\1/p' "$work/log_$name" | head -n 1)
  "$python" -c "import sys; i, s, e = map(int, sys.argv[1:]); \
print(f'$name: {i} instructions, {s} increments, {i / (s * e):.1f} per element-increment')" \
    "$instructions" "$steps" "$((n * n))"
}
: >"$work/summary"
for deck in ${DECKS:-elastic nothing_yielding plastic}; do
  case $deck in
    elastic) count elastic | tee -a "$work/summary" ;;
    nothing_yielding) count nothing_yielding --plastic 1e12 | tee -a "$work/summary" ;;
    plastic) count plastic --plastic "$yield" | tee -a "$work/summary" ;;
    *) echo "unknown deck $deck" >&2; exit 2 ;;
  esac
done
"$python" - "$work/summary" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
per = {m[1]: float(m[2]) for m in re.finditer(r"^(\w+): .* ([0-9.]+) per element", text, re.M)}
for name in ("nothing_yielding", "plastic"):
    if "elastic" in per and name in per:
        print(f"elastic / {name}: {per['elastic'] / per[name]:.3f}")
PY
