#!/usr/bin/python3
"""MPI output test (issue 37 item 5, docs/dev/mpi.md): a deck run on one rank and on N ranks,
where every rank writes its rows of each frame into JOB.h5 (parallel HDF5), and on 2 ranks with
--gather-frames (rank 0 gathers and writes alone). Each N-rank file must be bitwise the one-rank
result (`xpl compare --frames all`, tolerance 0) and have its layout: the same groups and
datasets (shape, type, chunks, compression, fill value), the same attributes with the same
values (the root's xpl_version and /summary, which hold times, aside). The N-rank summary must
validate against apps/summary.schema.json and its `mpi` block hold the partition and every
rank's times (elements adding up to the model's, time_loop = compute + exchange + wait +
output).

Usage: mpi_output.py XPL DECK OUT_DIR [--ranks 2,3]
OUT_DIR is removed when every check passed and kept otherwise.
"""

import argparse
import json
import math
import pathlib
import shutil
import sys

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "apps"))
from mpi_bitwise import mpirun, run  # noqa: E402
from summary_check import check_summary  # noqa: E402

SCHEMA = HERE.parents[1] / "apps" / "summary.schema.json"


def layout(path):
    """Every group and dataset of the file with its attributes, as comparable lines."""
    lines = []

    def attributes(name, obj):
        for key in sorted(obj.attrs):
            if name == "/" and key == "xpl_version":
                continue
            value = obj.attrs[key]
            lines.append(f"{name} @{key} = {np.asarray(value).tolist()!r}")

    with h5py.File(path, "r") as f:
        attributes("/", f)

        def visit(name, obj):
            if name == "summary" or name.startswith("summary/"):
                return
            if isinstance(obj, h5py.Dataset):
                fill = obj.fillvalue
                lines.append(f"/{name} dataset {obj.shape} {obj.dtype} chunks={obj.chunks} "
                             f"compression={obj.compression} fill={fill!r}")
            else:
                lines.append(f"/{name} group")
            attributes(f"/{name}", obj)

        f.visititems(visit)
    return lines


def check_mpi_summary(summary, ranks, frames):
    """The summary's mpi block: every rank's share and times."""
    problems = []
    mpi = summary.get("mpi")
    if mpi is None:
        return ["no mpi block in the summary"]
    if mpi["ranks"] != ranks or len(mpi["rank"]) != ranks:
        problems.append(f"mpi.ranks {mpi['ranks']}, {len(mpi['rank'])} rank entries; expected {ranks}")
    if mpi["frames"] != frames:
        problems.append(f"mpi.frames {mpi['frames']!r}; expected {frames!r}")
    if mpi["times"] != "gathered":
        problems.append(f"mpi.times {mpi['times']!r}; expected 'gathered'")
    elements = sum(r["elements"] for r in mpi["rank"].values())
    if elements != summary["model"]["elements"]:
        problems.append(f"the ranks' elements add up to {elements}, the model has "
                        f"{summary['model']['elements']}")
    owned = sum(r["owned_nodes"] for r in mpi["rank"].values())
    if owned > summary["model"]["nodes"] or owned == 0:
        problems.append(f"the ranks own {owned} nodes of {summary['model']['nodes']}")
    if not mpi["imbalance"] >= 1.0 or mpi["interface_nodes"] <= 0:
        problems.append(f"imbalance {mpi['imbalance']}, interface nodes {mpi['interface_nodes']}")
    for name, r in mpi["rank"].items():
        parts = r["compute"] + r["exchange"] + r["wait"] + r["output"]
        if min(r["compute"], r["exchange"], r["wait"], r["output"]) < 0 or r["time_loop"] <= 0:
            problems.append(f"rank {name}: a negative or empty time: {r}")
        # compute is the rest of the loop (clamped at 0): the parts add up to the loop.
        if not math.isclose(parts, r["time_loop"], rel_tol=1e-9, abs_tol=1e-9):
            problems.append(f"rank {name}: compute + exchange + wait + output = {parts} s, "
                            f"time_loop {r['time_loop']} s")
        if r["interface_nodes"] <= 0 or r["neighbours"] <= 0:
            problems.append(f"rank {name}: no interface: {r}")
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
    job = pathlib.Path(args.deck).stem

    reference = out / "np1"
    code, text = run([args.xpl, "run", args.deck, "-o", str(reference), "--quiet", "--threads", "1"],
                     out)
    if code != 0:
        print(f"one-rank run failed ({code}):\n{text}")
        return 1
    check_summary(SCHEMA, reference, job, "completed")
    expected = layout(reference / f"{job}.h5")
    failures = 0
    cases = [(int(r), []) for r in args.ranks.split(",")] + [(2, ["--gather-frames"])]
    for ranks, extra in cases:
        name = f"np{ranks}" + ("_gather" if extra else "")
        case = out / name
        code, text = run(mpirun(ranks) + [args.xpl, "run", args.deck, "-o", str(case), "--quiet",
                                          "--threads", "1"] + extra, out)
        if code != 0:
            print(f"{name}: run failed ({code}):\n{text}")
            failures += 1
            continue
        problems = []
        code, text = run([args.xpl, "compare", str(reference / f"{job}.h5"),
                          str(case / f"{job}.h5"), "--frames", "all"], out)
        if code != 0:
            problems.append("\n".join(line for line in text.splitlines()
                                      if not line.startswith("pass")))
        got = layout(case / f"{job}.h5")
        if got != expected:
            differ = [f"- {line}" for line in expected if line not in got]
            differ += [f"+ {line}" for line in got if line not in expected]
            problems.append(f"layout differs from the one-rank file ({len(expected)} lines):\n  "
                            + "\n  ".join(differ[:20]))
        try:
            summary = check_summary(SCHEMA, case, job, "completed")
            problems += check_mpi_summary(
                summary, ranks, "gathered to rank 0" if extra else "every rank its rows")
        except AssertionError as error:
            problems.append(str(error))
        print(f"{name}: " + ("bitwise, same layout "
                             f"({len(got)} groups, datasets and attributes), summary valid"
                             if not problems else "FAILED"))
        for p in problems:
            print(f"  {p}")
        failures += bool(problems)
    if failures:
        return 1
    shutil.rmtree(out, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
