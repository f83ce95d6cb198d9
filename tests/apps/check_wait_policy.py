#!/usr/bin/python3
"""xpl's default OpenMP wait policy (issue 15, item 10): threads sleep at barriers
(OMP_WAIT_POLICY=PASSIVE) unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT.

Usage: check_wait_policy.py XPL [DECK]   (DECK: also check `xpl check DECK`)

libgomp prints the settings it runs with under OMP_DISPLAY_ENV=VERBOSE, when it starts: a
spin count of 0 is the passive policy; its default (nothing set) is 300,000 spins. The last
block printed is that of the process that runs. With libgomp linked statically (the default
build, CMakeLists.txt XPL_STATIC_OPENMP) xpl sets the policy before the runtime starts, which
then starts once: one block, no re-exec (issue 38 item 5); with a shared libgomp xpl executes
itself again and the first process prints a block too. Skipped (exit 77) with another OpenMP
runtime.
"""

import os
import re
import subprocess
import sys
import tempfile


def links_shared_libgomp(xpl):
    """Whether the program needs libgomp.so (readelf -d), None if readelf is not there."""
    try:
        r = subprocess.run(["readelf", "-d", xpl], capture_output=True, text=True, timeout=30)
    except FileNotFoundError:
        return None
    return "libgomp" in r.stdout


def spin_counts(xpl, command, **env):
    """The spin count of each runtime start, in order."""
    environment = {k: v for k, v in os.environ.items()
                   if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    environment.update(env, OMP_DISPLAY_ENV="VERBOSE")
    r = subprocess.run([xpl] + command, capture_output=True, text=True, env=environment,
                       timeout=60)
    if r.returncode != 0:
        sys.exit(f"FAIL: xpl {' '.join(command)}: exit {r.returncode}\n{r.stdout}{r.stderr}")
    counts = re.findall(r"GOMP_SPINCOUNT = '(\d+)'", r.stderr)
    if not counts:
        print("skipped: the OpenMP runtime is not libgomp")
        sys.exit(77)
    return [int(c) for c in counts]


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    xpl = sys.argv[1]
    shared = links_shared_libgomp(xpl)
    checks = [({}, 0, "nothing set: passive"),
              ({"OMP_WAIT_POLICY": "ACTIVE"}, None, "OMP_WAIT_POLICY=ACTIVE kept"),
              ({"GOMP_SPINCOUNT": "1000"}, 1000, "GOMP_SPINCOUNT=1000 kept")]
    commands = [["--version"]]
    if len(sys.argv) == 3:  # a run: the process that starts the threads
        commands.append(["check", sys.argv[2], "-o", tempfile.mkdtemp(), "--quiet"])
    for command in commands:
        for env, expected, what in checks:
            counts = spin_counts(xpl, command, **env)
            count = counts[-1]
            ok = count > 300000 if expected is None else count == expected
            if not ok:
                sys.exit(f"FAIL: xpl {command[0]}: {what}: libgomp runs with GOMP_SPINCOUNT {count}")
            if shared is False and len(counts) != 1:
                sys.exit(f"FAIL: xpl {command[0]}: {what}: libgomp is linked statically but "
                         f"started {len(counts)} times (spin counts {counts}): a re-exec")
            print(f"ok: xpl {command[0]}: {what} (spin count {count}, "
                  f"{len(counts)} runtime start(s))")
    if "OMP_WAIT_POLICY" not in subprocess.run([xpl, "--help"], capture_output=True,
                                               text=True).stdout:
        sys.exit("FAIL: --help does not say how to change the wait policy")


if __name__ == "__main__":
    main()
