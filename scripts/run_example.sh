#!/usr/bin/env bash
# Build xpl (release) and run the default example, a steel bar hitting a rigid wall.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

# Only the program: the test suite is built by scripts/run_tests.sh.
bash scripts/build.sh release xpl

job=bar_impact
out_dir=build/examples/$job
build/release/apps/xpl run "examples/$job/$job.inp" -o "$out_dir"

echo
echo "Results of job '$job' in $repo_root/$out_dir:"
for ext in h5 xdmf sta msg; do
  file="$out_dir/$job.$ext"
  if [[ -f $file ]]; then
    printf '  %-5s %s\n' "$ext" "$repo_root/$file"
  else
    printf '  %-5s %s (missing)\n' "$ext" "$repo_root/$file"
  fi
done
echo "ParaView: open $out_dir/$job.xdmf, then Filters > Warp By Vector (U)."
echo "h5py:     /usr/bin/python3 -c \"import h5py; f = h5py.File('$out_dir/$job.h5', 'r'); print(f['/history/step_1/energy/ALLKE'][:])\""
