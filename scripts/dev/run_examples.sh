#!/usr/bin/env bash
# Run every example deck with one xpl binary at 1 and 2 threads, for a bitwise comparison of
# two builds (a refactoring must not change a bit):
#   bash scripts/dev/run_examples.sh OLD/xpl /tmp/old
#   bash scripts/dev/run_examples.sh NEW/xpl /tmp/new
#   /usr/bin/python3 scripts/dev/h5_bitwise.py /tmp/old /tmp/new
# Each line of OUT/rc.txt is "exit-code threads deck".
set -uo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: $0 XPL OUT_DIR [REPO]" >&2
  exit 2
fi
xpl=$1
out=$2
repo=${3:-"$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"}
export OMP_WAIT_POLICY=PASSIVE
rm -f "$out/rc.txt"
mkdir -p "$out"
for threads in 1 2; do
  for deck in $(cd "$repo" && find examples -name '*.inp' | sort); do
    name=$(basename "$deck" .inp)
    dir=$out/t$threads/$name
    mkdir -p "$dir"
    extra=()
    # import_target continues from import_source's last frame (examples/overclosure).
    if [[ $name == import_target ]]; then
      extra=(--import "$out/t$threads/import_source/import_source.h5")
    fi
    "$xpl" run "$repo/$deck" -o "$dir" --threads "$threads" --quiet "${extra[@]}" >"$dir/stdout" 2>&1
    echo "$? $threads $name" >>"$out/rc.txt"
  done
done
