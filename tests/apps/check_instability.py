#!/usr/bin/python3
"""A run that goes unstable: exit code 3, and the results file records the failure.

Usage: check_instability.py XPL MAKE_BAR WORK_DIR

Writes the default bar deck with examples/make_bar.py (MAKE_BAR) into WORK_DIR (emptied
first), with a short period, and switches its step to
`*DYNAMIC, EXPLICIT, DIRECT USER CONTROL` with a fixed increment of 1.5e-6 s, about 3.6 times
the stable increment of the mesh (0.9 * 0.94 * 2.5e-3 m / 5047 m/s = 4.19e-7 s). Then
`XPL run` must exit with 3 and "NaN/instability at increment" on stderr; JOB.h5 must open in
h5py with status "failed" and the error text in its error attribute; JOB.msg and JOB.sta
must record the error.
"""

import pathlib
import shutil
import subprocess
import sys

import h5py

from summary_check import check_summary

SCHEMA = pathlib.Path(__file__).resolve().parents[2] / "apps" / "summary.schema.json"

JOB = "cli_unstable_bar"
PERIOD = "3e-05"
FIXED_INCREMENT = "1.5e-06"
STABLE_INCREMENT = 0.9 * 0.94 * 2.5e-3 / 5047.5


def check(condition, message):
    if not condition:
        sys.exit(f"check_instability.py: FAILED: {message}")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, make_bar, work = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    deck = work / f"{JOB}.inp"
    subprocess.run([sys.executable, make_bar, "--period", PERIOD, "--out", str(deck)],
                   check=True, capture_output=True)
    text = deck.read_text()
    old = f"*DYNAMIC, EXPLICIT\n, {PERIOD}\n"
    new = f"*DYNAMIC, EXPLICIT, DIRECT USER CONTROL\n{FIXED_INCREMENT}, {PERIOD}\n"
    if text.count(old) != 1:
        sys.exit(f"check_instability.py: test bug: make_bar.py output lacks {old!r}")
    deck.write_text(text.replace(old, new))
    check(float(FIXED_INCREMENT) > 3.0 * STABLE_INCREMENT, "the increment is not unstable enough")

    out = work / "out"
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out)], capture_output=True,
                            text=True, timeout=120)
    check(result.returncode == 3, f"exit code {result.returncode}, expected 3\n"
                                  f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}")
    check("NaN/instability at increment" in result.stderr,
          f"stderr lacks 'NaN/instability at increment':\n{result.stderr}")

    h5_path = out / f"{JOB}.h5"
    check(h5_path.is_file(), f"{h5_path} missing")
    with h5py.File(h5_path, "r") as f:
        check(f.attrs["status"] == "failed", f"status is {f.attrs['status']!r}, not 'failed'")
        error = f.attrs["error"]
        check(isinstance(error, str) and error != "", f"error attribute is {error!r}")
        check(error.startswith("NaN/instability at increment"), f"error attribute is {error!r}")
        check(error in result.stderr, f"stderr does not carry the error {error!r}")
        check(len(f["frames"]) >= 1, "no frames in the failed run's file")
        check(f["history/step_1/time"].shape[0] >= 1, "no history rows in the failed run's file")
    msg = out / f"{JOB}.msg"
    check(msg.is_file(), f"{msg} missing")
    check(error in msg.read_text(), f".msg does not contain the error {error!r}")
    sta = out / f"{JOB}.sta"
    check(sta.is_file(), f"{sta} missing")
    sta_text = sta.read_text()
    check("THE ANALYSIS HAS NOT BEEN COMPLETED" in sta_text, ".sta does not say NOT BEEN COMPLETED")
    check("COMPLETED SUCCESSFULLY" not in sta_text, ".sta claims success")
    # The summary of a failed run: valid, status failed, the error as its exit reason.
    try:
        summary = check_summary(SCHEMA, out, JOB, "failed")
    except AssertionError as e:
        sys.exit(f"check_instability.py: FAILED: {e}")
    check(summary["exit_reason"] == error, f"summary exit_reason {summary['exit_reason']!r}")
    check(summary["increments"] > 0, "the failed run's summary counts no increments")
    print(f"check_instability.py: exit code 3, status failed, error recorded: {error}")


if __name__ == "__main__":
    main()
