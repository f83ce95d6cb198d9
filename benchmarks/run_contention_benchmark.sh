#!/usr/bin/env bash
# Busy-machine benchmark (issue 17, item 5): every benchmark deck with 1 and 2 threads while
# one competing CPU-bound process (`yes > /dev/null`, pinned to no core) runs, and the speed
# of 2 threads relative to 1. With a second binary (the build before a change) the runs of
# both alternate in the same minutes: round r runs OLD 1T, NEW 1T, OLD 2T, NEW 2T of each
# deck, so a slow stretch of a shared host hits both alike.
#
#   bash benchmarks/run_contention_benchmark.sh NEW/xpl [OLD/xpl] [ROUNDS]
#
# Decks: the hex block (46³ C3D8R, 100 increments), the S4R plate (316², pressure, 100
# increments), the contact block impact (2 × 40 × 40 × 30 C3D8R, 120 increments) and the
# 320-element contact example examples/contact/shell_block. Prints best and median of the
# element-cycle rate (and the wall time of the whole run for the small deck, where setup
# counts) per binary, deck and thread count, and 2T/1T of each; appends every run to
# benchmarks/results/contention.csv. OMP_WAIT_POLICY and GOMP_SPINCOUNT are unset, as a
# user's shell would have them. Environment: ROUNDS (5), DECKS (subset of "hex shell contact
# small"), NO_COMPETITOR=1 (the same runs on an otherwise idle machine), REDUCED=1 (meshes of
# about a quarter: 30³ hexes, a 160² plate, 2 × 25 × 25 × 18 contact blocks, for a machine
# so loaded that the full ones take minutes; the deck names get an "_r" suffix).
set -euo pipefail

new=$(realpath "$1")
old=${2:+$(realpath "$2")}
rounds=${3:-${ROUNDS:-5}}
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
decks_wanted=${DECKS:-"hex shell contact small"}
python=/usr/bin/python3
work=$(mktemp -d)
competitor=""
cleanup() {
  [[ -n $competitor ]] && kill "$competitor" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

reduced=${REDUCED:-0}
hex_n=46 plate_n=316 contact_n=40 contact_m=30
[[ $reduced == 1 ]] && hex_n=30 plate_n=160 contact_n=25 contact_m=18
declare -A deck
for d in $decks_wanted; do
  case $d in
    hex)
      "$python" "$repo/benchmarks/make_block.py" -n $hex_n --increments 100 --out "$work/hex.inp" >/dev/null
      deck[hex]=$work/hex.inp ;;
    shell)
      "$python" "$repo/benchmarks/make_plate_benchmark.py" -n $plate_n --increments 100 \
        --out "$work/shell.inp" >/dev/null
      deck[shell]=$work/shell.inp ;;
    contact)
      "$python" "$repo/benchmarks/make_contact_benchmark.py" --n $contact_n --m $contact_m \
        --increments 120 "$work/contact.inp" >/dev/null
      deck[contact]=$work/contact.inp ;;
    small)
      deck[small]=$repo/examples/contact/shell_block/shell_block.inp ;;
    *)
      echo "run_contention_benchmark: unknown deck '$d'" >&2
      exit 2 ;;
  esac
done

if [[ ${NO_COMPETITOR:-0} != 1 ]]; then
  yes >/dev/null &
  competitor=$!
fi

csv="$repo/benchmarks/results/contention.csv"
[[ -f $csv ]] || echo "date,binary,deck,threads,round,competitor,wall_s,mcycles_per_s,load1" >"$csv"
binaries=("$new")
[[ -n $old ]] && binaries=("$old" "$new")
label() { [[ $1 == "$new" ]] && echo new || echo old; }

# One run: appends "wall mcycles" to the results of (binary, deck, threads).
declare -A wall rate
run_one() {
  local xpl=$1 name=$2 threads=$3 r=$4
  local out=$work/out_$name t0 t1 w m
  t0=$(date +%s.%N)
  env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$xpl" run "${deck[$name]}" -o "$out" \
    --threads "$threads" >"$work/log" 2>&1 || {
    echo "run_contention_benchmark: $xpl failed on $name:" >&2
    tail -5 "$work/log" >&2
    exit 1
  }
  t1=$(date +%s.%N)
  w=$(echo "$t1 - $t0" | bc -l)
  m=$(sed -n 's/^xpl: element cycles per second: \([0-9.e+-]*\).*/\1/p' "$work/log")
  m=$(echo "$m" | awk '{printf "%.4f", $1 / 1e6}')
  local key
  key="$(label "$xpl") $name $threads"
  wall[$key]+="$w "
  rate[$key]+="$m "
  echo "$(date -u +%FT%TZ),$(label "$xpl"),$name$([[ $reduced == 1 && $name != small ]] && echo _r),$threads,$r,$([[ -n $competitor ]] && echo yes || echo no),$w,$m,$(cut -d' ' -f1 /proc/loadavg)" >>"$csv"
}

stats() {  # "best median" of the arguments after the first; best = largest if $1 is -r
  local order=$1
  shift
  printf '%s\n' "$@" | if [[ $order == -r ]]; then sort -gr; else sort -g; fi |
    awk '{v[NR]=$1} END {printf "%.3f %.3f", v[1], (NR % 2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'
}

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; competitor:" \
  "$([[ -n $competitor ]] && echo 'yes >/dev/null' || echo none); load at start $(cut -d' ' -f1-3 /proc/loadavg)"
for ((r = 1; r <= rounds; ++r)); do
  for name in $decks_wanted; do
    for threads in 1 2; do
      for xpl in "${binaries[@]}"; do run_one "$xpl" "$name" "$threads" "$r"; done
    done
  done
  echo "round $r of $rounds done (load $(cut -d' ' -f1 /proc/loadavg))"
done

echo
echo "| deck | binary | 1T M/s best / median | 2T M/s best / median | 2T/1T best / median | 1T wall s median | 2T wall s median |"
echo "|---|---|---:|---:|---:|---:|---:|"
for name in $decks_wanted; do
  for xpl in "${binaries[@]}"; do
    b=$(label "$xpl")
    read -r r1b r1m <<<"$(stats -r ${rate[$b $name 1]})"
    read -r r2b r2m <<<"$(stats -r ${rate[$b $name 2]})"
    read -r _ w1m <<<"$(stats +g ${wall[$b $name 1]})"
    read -r _ w2m <<<"$(stats +g ${wall[$b $name 2]})"
    printf '| %s | %s | %s / %s | %s / %s | %.2f / %.2f | %s | %s |\n' "$name" "$b" "$r1b" "$r1m" \
      "$r2b" "$r2m" "$(echo "$r2b / $r1b" | bc -l)" "$(echo "$r2m / $r1m" | bc -l)" "$w1m" "$w2m"
  done
done
echo "load at end $(cut -d' ' -f1-3 /proc/loadavg)"
