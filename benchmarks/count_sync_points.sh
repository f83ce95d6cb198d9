#!/usr/bin/env bash
# OpenMP synchronisation points per increment (issue 17, item 1): runs each model type with
# 2 threads under benchmarks/omp_count.c (LD_PRELOAD, counts forked parallel regions and
# the barriers inside them) at two run lengths, and prints the difference per increment, so
# that setup and output do not count.
#   bash benchmarks/count_sync_points.sh BUILD/apps/xpl
# MODELS="hex c3d8" (a subset of hex c3d8 shell contact) limits the run.
set -euo pipefail
xpl=$(realpath "$1")
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
gcc -O2 -shared -fPIC -o "$work/omp_count.so" "$repo/benchmarks/omp_count.c" -ldl

# deck generators: name and command writing $work/NAME_INC.inp for about INC increments
make_deck() {
  local name=$1 inc=$2 out=$work/${1}_$2.inp
  case $name in
    hex) "$python" "$repo/benchmarks/make_block.py" -n 20 --increments "$inc" --out "$out" ;;
    c3d8) "$python" "$repo/benchmarks/make_block.py" -n 20 --element-type C3D8 --increments "$inc" --out "$out" ;;
    shell) "$python" "$repo/benchmarks/make_plate_benchmark.py" -n 60 --increments "$inc" --out "$out" ;;
    contact) "$python" "$repo/benchmarks/make_contact_benchmark.py" --n 12 --m 9 --increments "$inc" "$out" ;;
  esac >/dev/null
  echo "$out"
}

measure() {  # deck -> "increments regions barriers"
  local deck=$1
  OMP_COUNT_FILE=$work/count LD_PRELOAD=$work/omp_count.so OMP_WAIT_POLICY=PASSIVE \
    "$xpl" run "$deck" -o "$work/out" --threads 2 >"$work/log" 2>&1
  local inc
  inc=$(sed -n 's/.*completed: \([0-9]*\) increments.*/\1/p' "$work/log")
  echo "$inc $(awk '/^parallel_regions/ {r=$2} /^barrier_calls/ {b=$2} END {print r, b}' "$work/count")"
}

echo "| model | increments | parallel regions per increment | barriers in regions per increment (per thread) |"
echo "|---|---:|---:|---:|"
for name in ${MODELS:-hex c3d8 shell contact}; do
  read -r i1 r1 b1 <<<"$(measure "$(make_deck $name 50)")"
  read -r i2 r2 b2 <<<"$(measure "$(make_deck $name 150)")"
  printf '| %s | %s, %s | %.2f | %.2f |\n' "$name" "$i1" "$i2" \
    "$(echo "($r2 - $r1) / ($i2 - $i1)" | bc -l)" "$(echo "($b2 - $b1) / ($i2 - $i1) / 2" | bc -l)"
done
