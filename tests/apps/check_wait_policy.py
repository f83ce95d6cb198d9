#!/usr/bin/python3
"""xpl's default OpenMP wait policy (issue 15, item 10): threads sleep at barriers
(OMP_WAIT_POLICY=PASSIVE) unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT.

Usage: check_wait_policy.py XPL

libgomp prints the settings it runs with under OMP_DISPLAY_ENV=VERBOSE, when it is loaded: a
spin count of 0 is the passive policy; its default (nothing set) is 300,000 spins. The last
block printed is that of the process that runs. Skipped (exit 77) with another OpenMP runtime.
"""

import os
import re
import subprocess
import sys


def spin_count(xpl, **env):
    environment = {k: v for k, v in os.environ.items()
                   if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    environment.update(env, OMP_DISPLAY_ENV="VERBOSE")
    r = subprocess.run([xpl, "--version"], capture_output=True, text=True, env=environment,
                       timeout=30)
    if r.returncode != 0 or not r.stdout.startswith("xpl "):
        sys.exit(f"FAIL: xpl --version: exit {r.returncode}\n{r.stdout}{r.stderr}")
    counts = re.findall(r"GOMP_SPINCOUNT = '(\d+)'", r.stderr)
    if not counts:
        print("skipped: the OpenMP runtime is not libgomp")
        sys.exit(77)
    return int(counts[-1])


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    xpl = sys.argv[1]
    checks = [({}, 0, "nothing set: passive"),
              ({"OMP_WAIT_POLICY": "ACTIVE"}, None, "OMP_WAIT_POLICY=ACTIVE kept"),
              ({"GOMP_SPINCOUNT": "1000"}, 1000, "GOMP_SPINCOUNT=1000 kept")]
    for env, expected, what in checks:
        count = spin_count(xpl, **env)
        ok = count > 300000 if expected is None else count == expected
        if not ok:
            sys.exit(f"FAIL: {what}: libgomp runs with GOMP_SPINCOUNT {count}")
        print(f"ok: {what} (spin count {count})")
    if "OMP_WAIT_POLICY" not in subprocess.run([xpl, "--help"], capture_output=True,
                                               text=True).stdout:
        sys.exit("FAIL: --help does not say how to change the wait policy")


if __name__ == "__main__":
    main()
