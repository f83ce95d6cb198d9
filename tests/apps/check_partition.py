#!/usr/bin/python3
"""`xpl run|check --partition N` (issue 37 item 2, docs/dev/mpi.md): the partition into N parts
reported in JOB.msg, the run itself unchanged.

- a run with --partition 3 gives results bitwise equal to one without (xpl compare at tolerance
  0, every frame), and its .msg has the report: one summary line and one line per part whose
  element counts add up to the model's, imbalance >= 1;
- without --partition the .msg has no partition line;
- a data check of a contact deck with a rigid body reports it too;
- --partition 0 and --partition x are usage errors (exit 2).

Usage: check_partition.py XPL BAR_DECK CONTACT_DECK WORK_DIR
"""

import pathlib
import re
import shutil
import subprocess
import sys

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"check_partition.py: FAILED: {message}")
    return condition


SUMMARY = re.compile(r"partition: (\d+) parts by (\w+) in [0-9.]+ s: imbalance ([0-9.]+) .*?"
                     r"(\d+) interface nodes")
PART = re.compile(r"partition: part (\d+): (\d+) elements \(weight [0-9.]+\), (\d+) owned nodes")


def report(msg_file):
    text = pathlib.Path(msg_file).read_text()
    return SUMMARY.findall(text), PART.findall(text)


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    xpl, bar, contact, work = sys.argv[1], sys.argv[2], sys.argv[3], pathlib.Path(sys.argv[4])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)

    def run(*args):
        return subprocess.run([xpl, *args], capture_output=True, text=True, timeout=240)

    plain = run("run", bar, "-o", str(work / "plain"), "--quiet", "--threads", "1")
    parted = run("run", bar, "-o", str(work / "parted"), "--quiet", "--threads", "1",
                 "--partition", "3")
    check(plain.returncode == 0 and parted.returncode == 0,
          f"runs exit 0 (got {plain.returncode}, {parted.returncode}: {parted.stderr})")
    compared = subprocess.run([xpl, "compare", str(work / "plain/bar_impact.h5"),
                               str(work / "parted/bar_impact.h5"), "--frames", "all"],
                              capture_output=True, text=True, timeout=120)
    check(compared.returncode == 0, "--partition leaves the results bitwise unchanged: "
          + compared.stdout[-400:])
    summary, parts = report(work / "parted/bar_impact.msg")
    check(len(summary) == 1 and summary[0][0] == "3", f"one summary line of 3 parts: {summary}")
    check(len(parts) == 3, f"one line per part: {parts}")
    # The bar example has 640 C3D8R.
    check(sum(int(p[1]) for p in parts) == 640, f"the parts hold the 640 elements: {parts}")
    if summary:
        check(float(summary[0][2]) >= 1.0, f"imbalance >= 1: {summary[0][2]}")
    none, _ = report(work / "plain/bar_impact.msg")
    check(not none and "partition" not in (work / "plain/bar_impact.msg").read_text(),
          "no partition line without --partition")

    checked = run("check", contact, "-o", str(work / "contact"), "--quiet", "--partition", "2")
    check(checked.returncode == 0, f"check exits 0: {checked.stderr}")
    job = pathlib.Path(contact).stem
    summary, parts = report(work / f"contact/{job}.msg")
    check(len(summary) == 1 and len(parts) == 2, f"data check reports 2 parts: {summary} {parts}")

    for bad in ("0", "x", "-2"):
        r = run("run", bar, "-o", str(work / "bad"), "--partition", bad)
        check(r.returncode == 2 and "--partition" in r.stderr,
              f"--partition {bad}: exit 2 naming the option (got {r.returncode}: {r.stderr})")
    check(not (work / "bad").exists(), "a usage error writes nothing")

    if failures:
        sys.exit(f"check_partition.py: {len(failures)} check(s) failed")
    print("check_partition.py: all checks passed")


if __name__ == "__main__":
    main()
