#!/usr/bin/python3
"""An exception inside an OpenMP region ends the run with its message and a failed status,
never std::terminate (issue 15, item 3).

Usage: check_parallel_error.py XPL SOURCE_DIR OUT_DIR

No region body throws on any deck today, so the failure is injected: XPL_TEST_FAULT=SITE:0
makes iteration 0 of the guarded region SITE throw std::runtime_error (common/
parallel_error.hpp). For each site, on an example deck that runs it, with two threads:
`xpl run` exits 4 (an internal error, not a signal) naming the fault, JOB.h5 and
JOB.summary.json record status "failed" with it, and JOB.msg gives it as the error.
"""

import json
import os
import pathlib
import shutil
import subprocess
import sys

import h5py

LIMIT = 60
CASES = [
    ("element-forces", "examples/bar_impact/bar_impact.inp"),
    ("element-forces", "examples/plate_pressure/plate_pressure.inp"),
    ("element-boundary", "examples/plate_pressure/plate_pressure.inp"),
    ("contact-search", "examples/contact/friction_block/friction_block.inp"),
    ("contact-forces", "examples/contact/friction_block/friction_block.inp"),
    ("broad-phase", "examples/contact/friction_block/friction_block.inp"),
    ("overclosure", "examples/overclosure/blocks_adjust/blocks_adjust.inp"),
    ("clearance", "examples/clearance/deep_blocks/deep_blocks.inp"),
]


def fail(message):
    sys.exit(f"FAIL: {message}")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, source, out = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(out, ignore_errors=True)
    for site, deck_name in CASES:
        deck = source / deck_name
        job = deck.stem
        results = out / f"{site}_{job}"
        env = dict(os.environ, XPL_TEST_FAULT=f"{site}:0", OMP_WAIT_POLICY="PASSIVE")
        try:
            r = subprocess.run([xpl, "run", str(deck), "-o", str(results), "--threads", "2",
                                "--quiet"], capture_output=True, text=True, errors="replace",
                               env=env, timeout=LIMIT)
        except subprocess.TimeoutExpired:
            fail(f"{site}: the run did not end within {LIMIT} s")
        fault = f"injected fault at {site}:0"
        if r.returncode != 4 or fault not in r.stderr or "terminate" in r.stderr:
            fail(f"{site}: exit {r.returncode} (expected 4 and {fault!r}):\n{r.stderr}")
        with h5py.File(results / f"{job}.h5", "r") as f:
            status, error = f.attrs["status"], f.attrs["error"]
        if status != "failed" or fault not in error:
            fail(f"{site}: {job}.h5 status {status!r}, error {error!r}")
        summary = json.loads((results / f"{job}.summary.json").read_text())
        if summary["status"] != "failed" or fault not in summary["exit_reason"]:
            fail(f"{site}: {job}.summary.json status {summary['status']!r}, "
                 f"exit_reason {summary['exit_reason']!r}")
        msg = (results / f"{job}.msg").read_text(errors="replace")
        if f"***ERROR: {fault}" not in msg:
            fail(f"{site}: {job}.msg does not give the fault as the error")
        print(f"ok: {site}: exit 4, status failed: {error}")
    # Unset or not understood, nothing is injected: the first case runs its data check.
    env = dict(os.environ, XPL_TEST_FAULT="no-such-site:0", OMP_WAIT_POLICY="PASSIVE")
    r = subprocess.run([xpl, "check", str(source / CASES[0][1]), "-o", str(out / "none")],
                       capture_output=True, text=True, env=env, timeout=LIMIT)
    if r.returncode != 0:
        fail(f"XPL_TEST_FAULT=no-such-site:0: exit {r.returncode}\n{r.stderr}")


if __name__ == "__main__":
    main()
