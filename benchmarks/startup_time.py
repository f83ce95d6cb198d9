#!/usr/bin/python3
"""Start-up and small-deck times of one or more xpl builds (issue 38, item 5): `xpl --version`
and a run of the 640-element example, whole processes, alternated build by build, with the
median and the best wall and CPU (user + system) time of each. OMP_WAIT_POLICY and
GOMP_SPINCOUNT are removed from the environment, as a user's shell has them, so that a build
that re-executes itself to set the wait policy pays for it. CPU time is the steadier figure on
a shared machine; the load average is printed before and after.

Usage: startup_time.py [--runs N] [--deck DECK] XPL [XPL ...]
Default: 20 runs, examples/bar_impact/bar_impact.inp (written to a temporary directory).
"""

import argparse
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parent.parent


def timed(command, env):
    """Wall and CPU seconds of one process."""
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               env=env)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    if status != 0:
        raise SystemExit(f"{' '.join(command)}: exit status {status}")
    return wall, usage.ru_utime + usage.ru_stime


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("--deck", type=pathlib.Path,
                        default=REPO / "examples" / "bar_impact" / "bar_impact.inp")
    parser.add_argument("xpl", nargs="+")
    args = parser.parse_args()
    env = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    out = tempfile.mkdtemp(prefix="xpl_startup_")
    cases = {"--version": ["--version"],
             args.deck.name: ["run", str(args.deck), "-o", out, "--quiet"]}
    times = {(x, c): [] for x in args.xpl for c in cases}
    print(f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    for _ in range(args.runs):
        for name, words in cases.items():
            for xpl in args.xpl:
                times[(xpl, name)].append(timed([xpl, *words], env))
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print(f"{'build':40s} {'case':18s} {'wall median':>12s} {'best':>8s} {'CPU median':>11s} "
          f"{'best':>8s}  (ms, {args.runs} runs)")
    for (xpl, name), values in times.items():
        wall = [1e3 * w for w, _ in values]
        cpu = [1e3 * c for _, c in values]
        print(f"{xpl[-40:]:40s} {name:18s} {statistics.median(wall):12.1f} {min(wall):8.1f} "
              f"{statistics.median(cpu):11.1f} {min(cpu):8.1f}")


if __name__ == "__main__":
    main()
