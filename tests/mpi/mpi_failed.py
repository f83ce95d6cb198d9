#!/usr/bin/python3
"""A run that fails on every rank (issue 37, docs/dev/mpi.md): the bar wave of
examples/bar_impact with an initial velocity of 20 km/s, whose stable increment collapses at
the same increment on one rank and on N. Each N-rank run must exit as the one-rank run does
(code 3), end "failed" with the same cause, write a JOB.h5 bitwise the one-rank one (every
dataset and attribute but the summary's times: scripts/dev/h5_bitwise.py), and its summary
must validate against apps/summary.schema.json with an `mpi` block that holds the partition
(the ranks' elements adding up to the model's) and says that the ranks' times were not
gathered.

Then a stop on one rank alone, which the solver never makes (its stops come from reduced
values) but a bug could: the stop injected on rank 1, then on rank 0 (XPL_TEST_FAULT=
solver-stop:20 in that rank's environment). The job must end on every rank within the wait
for the others (apps/job.cpp), exit 4 with the rank's reason, and no MPI error (before, the
rank went on to the end-of-run collective while the others waited in the time loop's, and
the job died in MPI_ERR_TRUNCATE without saying why); with rank 0 alone, JOB.h5 says failed.

Usage: mpi_failed.py XPL BAR_IMPACT_DECK OUT_DIR [--ranks 2,3]
OUT_DIR is removed when every check passed and kept otherwise.
"""

import argparse
import json
import pathlib
import shutil
import sys

import h5py

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "apps"))
from mpi_bitwise import mpirun, run  # noqa: E402
from summary_check import check_summary  # noqa: E402

SCHEMA = HERE.parents[1] / "apps" / "summary.schema.json"
BITWISE = HERE.parents[1] / "scripts" / "dev" / "h5_bitwise.py"
VELOCITY_LINE = "MOVING, 1, -10"
FAILED_CODE = 3  # xpl's exit code of a run that stopped on an error
ALONE_CODE = 4  # a failure of one rank alone: every rank ended (MPI_Abort)


def check_mpi_block(summary, ranks):
    """The failed run's mpi block: the partition of every rank, no times."""
    mpi = summary.get("mpi")
    if mpi is None:
        return ["no mpi block in the summary"]
    problems = []
    if mpi["ranks"] != ranks or len(mpi["rank"]) != ranks:
        problems.append(f"mpi.ranks {mpi['ranks']}, {len(mpi['rank'])} entries; expected {ranks}")
    if mpi["times"] != "not gathered: the run failed":
        problems.append(f"mpi.times {mpi['times']!r}")
    elements = sum(r["elements"] for r in mpi["rank"].values())
    if elements != summary["model"]["elements"]:
        problems.append(f"the ranks' elements add up to {elements}, the model has "
                        f"{summary['model']['elements']}")
    for name, r in mpi["rank"].items():
        if "time_loop" in r or r["owned_nodes"] <= 0:
            problems.append(f"rank {name}: {r}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xpl")
    parser.add_argument("deck")
    parser.add_argument("out")
    parser.add_argument("--ranks", default="2,3")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    text = pathlib.Path(args.deck).read_text()
    if text.count(VELOCITY_LINE) != 1:
        print(f"{args.deck}: expected one line {VELOCITY_LINE!r}")
        return 1
    job = "bar_fast"
    deck = out / f"{job}.inp"
    deck.write_text(text.replace(VELOCITY_LINE, "MOVING, 1, -20000"))

    reference = out / "np1"
    code, output = run([args.xpl, "run", str(deck), "-o", str(reference), "--quiet",
                        "--threads", "1"], out)
    if code != FAILED_CODE:
        print(f"one-rank run: exit {code}, expected {FAILED_CODE}:\n{output}")
        return 1
    expected = check_summary(SCHEMA, reference, job, "failed")
    if "mpi" in expected:
        print("one-rank run: an mpi block in its summary")
        return 1
    failures = 0
    for ranks in (int(r) for r in args.ranks.split(",")):
        case = out / f"np{ranks}"
        code, output = run(mpirun(ranks) + [args.xpl, "run", str(deck), "-o", str(case),
                                            "--quiet", "--threads", "1"], out)
        problems = []
        if code != FAILED_CODE:
            problems.append(f"exit {code}, expected {FAILED_CODE}:\n{output}")
        else:
            try:
                summary = check_summary(SCHEMA, case, job, "failed")
                if summary.get("cause") != expected.get("cause"):
                    problems.append(f"cause {summary.get('cause')!r}, one rank "
                                    f"{expected.get('cause')!r}")
                problems += check_mpi_block(summary, ranks)
            except AssertionError as error:
                problems.append(str(error))
            # xpl compare refuses a failed run's file: every dataset and attribute instead.
            code, output = run([sys.executable, str(BITWISE), str(reference), str(case)], out)
            if code != 0:
                problems.append(output)
        print(f"np{ranks}: " + ("failed as on one rank, frames bitwise, summary valid"
                                if not problems else "FAILED"))
        for p in problems:
            print(f"  {p}")
        failures += bool(problems)
    failures += stops_alone(args.xpl, pathlib.Path(args.deck), out)
    if failures:
        return 1
    shutil.rmtree(out, ignore_errors=True)
    return 0


def stops_alone(xpl, deck, out):
    """A stop of one rank alone ends the job with its reason; returns the failures."""
    failures = 0
    for alone in (1, 0):
        case = out / f"alone{alone}"
        command = []
        for rank in (0, 1):
            env = ["env", "XPL_TEST_FAULT=solver-stop:20"] if rank == alone else []
            command += (["-np", "1"] + env + [xpl, "run", str(deck), "-o", str(case), "--quiet",
                                             "--threads", "1"] + ([":"] if rank == 0 else []))
        code, output = run(mpirun(1)[:-2] + command, out)
        problems = []
        if code != ALONE_CODE:
            problems.append(f"exit {code}, expected {ALONE_CODE}")
        reason = f"error on rank {alone}: injected stop at increment 20"
        if reason not in output or "this rank alone" not in output:
            problems.append(f"no {reason!r} in the output")
        if "MPI_ERR" in output:
            problems.append("an MPI error")
        if alone == 0:
            with h5py.File(case / f"{deck.stem}.h5", "r") as f:
                if f.attrs["status"] != "failed":
                    problems.append(f"JOB.h5 status {f.attrs['status']!r}")
        print(f"stop on rank {alone} alone: " + ("the job ended with its reason"
                                                 if not problems else "FAILED"))
        for p in problems:
            print(f"  {p}\n{output}" if p.startswith("exit") else f"  {p}")
        failures += bool(problems)
    return failures


if __name__ == "__main__":
    sys.exit(main())
