#!/usr/bin/python3
"""Every example deck on one rank and on N ranks (an XPL_MPI=ON build), compared bitwise:
the check of the whole example set that the MPI tests (tests/mpi) make on a few decks.

Usage: mpi_examples.py XPL OUT_DIR [--ranks 2] [--threads 1] [--only SUBSTRING] [--decks DIR]
(--decks: the decks of DIR, e.g. tests/fuzz/generate_decks.py's, instead of examples/)
Prints one line per deck: bitwise, differs, refused under MPI (the deck's feature is not
distributed yet: a clear message, nothing run), or the two runs' exit codes when they end
differently. A run that fails on one rank must fail the same way on N (same exit code; its
file is then compared dataset by dataset with scripts/dev/h5_bitwise.py, as xpl compare
refuses a failed run). Exit 1 when a deck differs or ends differently.
"""

import argparse
import pathlib
import shutil
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(REPO / "tests" / "mpi"))
from mpi_bitwise import mpirun, run  # noqa: E402

REFUSED = 1  # xpl's exit code for a deck it will not run (here: a feature not distributed)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xpl")
    parser.add_argument("out")
    parser.add_argument("--ranks", default="2")
    parser.add_argument("--threads", default="1")
    parser.add_argument("--only", default="")
    parser.add_argument("--decks", type=lambda d: pathlib.Path(d).resolve(), default=REPO / "examples")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    decks = sorted(p for p in args.decks.rglob("*.inp") if args.only in str(p))
    bad = 0
    for deck in decks:
        name = deck.stem
        work = out / name
        shutil.rmtree(work, ignore_errors=True)
        work.mkdir(parents=True)
        one = work / "np1"
        code1, _ = run([args.xpl, "run", str(deck), "-o", str(one), "--quiet", "--threads",
                        args.threads], work)
        case = work / f"np{args.ranks}"
        code_n, text = run(mpirun(int(args.ranks)) + [args.xpl, "run", str(deck), "-o", str(case),
                                                      "--quiet", "--threads", args.threads], work)
        if code_n == REFUSED and code1 != REFUSED:
            line = "refused under MPI: " + (text.strip().splitlines() or [""])[-1][:160]
        elif code_n != code1:
            line = f"ENDS DIFFERENTLY: exit {code1} on one rank, {code_n} on {args.ranks}"
            bad += 1
        elif code1 == 0:
            c, t = run([args.xpl, "compare", str(one / f"{name}.h5"), str(case / f"{name}.h5"),
                        "--frames", "all"], work)
            line = "bitwise" if c == 0 else "DIFFERS: " + t.strip().splitlines()[-1][:160]
            bad += c != 0
        else:
            c = subprocess.run([sys.executable, str(HERE / "h5_bitwise.py"), str(one), str(case)],
                               capture_output=True, text=True).returncode
            line = f"fails on both (exit {code1}), " + ("bitwise" if c == 0 else "FILES DIFFER")
            bad += c != 0
        print(f"{deck.relative_to(args.decks)}: {line}", flush=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
