#!/usr/bin/env bash
# Partition quality (issue 37 item 2, docs/dev/mpi.md): `xpl check --partition N` on decks, one
# CSV row per deck, part count and build: imbalance, interface nodes, cut edges, seconds.
# Usage: benchmarks/run_partition_quality.sh XPL [DECK.inp...]
#   XPL: a default build (bisection) or an XPL_MPI=ON build (METIS) of xpl
#   PARTS: part counts (default "2 3 4 8")
set -euo pipefail
xpl="$1"
shift
parts="${PARTS:-2 3 4 8}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
echo "deck,elements,parts,method,imbalance,interface_nodes,cut_edges,graph_edges,cut_pairs,pairs,seconds"
for deck in "$@"; do
  job="$(basename "$deck" .inp)"
  for n in $parts; do
    rm -rf "${out:?}/$job"
    "$xpl" check "$deck" -o "$out/$job" --quiet --partition "$n" > /dev/null 2>&1 || true
    line="$(grep -h ' partition: [0-9]* parts' "$out/$job/$job.msg" || true)"
    elements="$(grep -h ' partition: part ' "$out/$job/$job.msg" |
      awk '{ s += $4 } END { print s }')"
    echo "$line" | sed -E "s/^ *partition: ([0-9]+) parts by ([A-Za-z]+) in ([0-9.]+) s: imbalance ([0-9.]+) .*, ([0-9]+) interface nodes, ([0-9]+) of ([0-9]+) graph edges cut, ([0-9]+) of ([0-9]+) contact.*/$job,$elements,\1,\2,\4,\5,\6,\7,\8,\9,\3/"
  done
done
