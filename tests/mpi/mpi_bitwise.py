#!/usr/bin/env python3
"""MPI test (issue 37 item 3, docs/dev/mpi.md): a deck run on one rank and under mpirun on
2 and 3 ranks with 1 and 2 threads each must give bitwise equal results (`xpl compare
--frames all` at tolerance 0: every field of every frame and every history series, the
energies included). Only in the XPL_MPI=ON build (ctest label mpi).

Usage: mpi_bitwise.py XPL DECK OUT_DIR [--ranks 2,3] [--threads 1,2] [--time-period T]
       mpi_bitwise.py XPL DECK OUT_DIR --refused TEXT   (the deck must be refused on 2 ranks
                                                          with TEXT in the message)
--time-period T runs a copy of the deck (in OUT_DIR) whose steps last T s each, to keep a long
example short.
Standard library only.
"""

import argparse
import os
import pathlib
import shutil
import subprocess
import sys


def mpirun(ranks):
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)]
    if os.geteuid() == 0:
        cmd.insert(1, "--allow-run-as-root")
    return cmd


def run(cmd):
    result = subprocess.run(cmd, capture_output=True, text=True, check=False)
    return result.returncode, result.stdout + result.stderr


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xpl")
    parser.add_argument("deck")
    parser.add_argument("out")
    parser.add_argument("--ranks", default="2,3")
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--refused", default=None)
    parser.add_argument("--time-period", default=None)
    parser.add_argument("--import-state", default=None,
                        help="with --refused: run with --import of this result file")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    if args.time_period is not None:
        # The line after each *DYNAMIC, EXPLICIT holds (initial increment, time period).
        lines = pathlib.Path(args.deck).read_text().splitlines()
        for k in range(len(lines) - 1):
            if lines[k].upper().replace(" ", "").startswith("*DYNAMIC,EXPLICIT"):
                lines[k + 1] = f", {args.time_period}"
        short = out / pathlib.Path(args.deck).name
        short.write_text("\n".join(lines) + "\n")
        args.deck = str(short)
    job = pathlib.Path(args.deck).stem

    if args.refused is not None:
        extra = ["--import", args.import_state] if args.import_state else []
        code, text = run(mpirun(2) + [args.xpl, "run", args.deck, "-o", str(out), "--quiet",
                                      "--threads", "1"] + extra)
        if code != 1 or args.refused not in text or "not distributed yet" not in text:
            print(f"expected exit 1 and '{args.refused} ... not distributed yet', got {code}:\n{text}")
            return 1
        if (out / f"{job}.h5").exists():
            print("a refused run wrote results")
            return 1
        print(f"refused on 2 ranks as expected: {text.strip().splitlines()[0]}")
        return 0

    reference = out / "np1"
    code, text = run([args.xpl, "run", args.deck, "-o", str(reference), "--quiet", "--threads", "1"])
    if code != 0:
        print(f"one-rank run failed ({code}):\n{text}")
        return 1
    failures = 0
    for ranks in [int(r) for r in args.ranks.split(",")]:
        for threads in [int(t) for t in args.threads.split(",")]:
            case = out / f"np{ranks}_t{threads}"
            code, text = run(mpirun(ranks) + [args.xpl, "run", args.deck, "-o", str(case),
                                              "--quiet", "--threads", str(threads)])
            if code != 0:
                print(f"{ranks} ranks x {threads} threads: run failed ({code}):\n{text}")
                failures += 1
                continue
            msg = (case / f"{job}.msg").read_text()
            if f"mpi: {ranks} ranks, distributed time loop" not in msg:
                print(f"{ranks} ranks x {threads} threads: the .msg does not report a distributed run")
                failures += 1
            code, text = run([args.xpl, "compare", str(reference / f"{job}.h5"),
                              str(case / f"{job}.h5"), "--frames", "all"])
            verdict = text.strip().splitlines()[-1] if text.strip() else ""
            print(f"{ranks} ranks x {threads} threads: {verdict}")
            if code != 0:
                print("\n".join(line for line in text.splitlines() if not line.startswith("pass")))
                failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
