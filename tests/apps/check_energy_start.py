#!/usr/bin/python3
"""The health check from the first increment (issue 33, item 1; SPEC R3).

Usage: check_energy_start.py XPL WORK_DIR

A free 100 mm steel S4R, 5 mm thick, with random velocities of up to 1 m/s:
1. at SCALE FACTOR=2, 3 and 5 for 1 ms it explodes within a few increments while its own
   increment grows, so the step ended after 5-8 increments with ALLKE of 1e33-1e38 J,
   "completed", while the check waited for 10 increments; at SCALE FACTOR=2 for 0.1 ms (4
   increments, fewer than the old warm-up) it ended "completed" with ETOTAL 2e4 times its
   start. Each must now exit 3 (status failed, NaN/instability) before its 10th increment,
   with the same cause in stderr, .msg, .sta and the .h5, and the summary's status failed.
2. at SCALE FACTOR=1 (69 increments) it completes; the largest drift is the same in the
   terminal, the .msg, the .sta and JOB.summary.json (which computed its own from the .sta
   lines before), and below 0.01 % of the energy scale.
"""

import json
import pathlib
import random
import re
import subprocess
import sys

import h5py


def deck(scale_factor, period):
    rnd = random.Random(1)
    out = ["*HEADING", f"one S4R at scale factor {scale_factor}", "*NODE",
           "1, 0., 0., 0.", "2, 0.1, 0., 0.", "3, 0., 0.1, 0.", "4, 0.1, 0.1, 0.",
           "*ELEMENT, TYPE=S4R, ELSET=P", "1, 1, 2, 4, 3",
           "*MATERIAL, NAME=S", "*DENSITY", "7800.", "*ELASTIC", "2.1e11, 0.3",
           "*SHELL SECTION, ELSET=P, MATERIAL=S", "0.005, 5",
           "*INITIAL CONDITIONS, TYPE=VELOCITY"]
    for node in range(1, 5):
        for dof in (3, 1):
            out.append(f"{node}, {dof}, {rnd.uniform(-1, 1):.3f}")
    out += ["*STEP", f"*DYNAMIC, EXPLICIT, SCALE FACTOR={scale_factor}", f", {period}",
            "*OUTPUT, HISTORY, TIME INTERVAL=1e-6", "*ENERGY OUTPUT", "*END STEP"]
    return "\n".join(out) + "\n"


def run(xpl, name, text, work):
    path = work / f"{name}.inp"
    path.write_text(text)
    out = work / name
    out.mkdir(parents=True, exist_ok=True)
    r = subprocess.run([xpl, "run", str(path), "-o", str(out), "--threads", "1"],
                       capture_output=True, text=True, timeout=60,
                       env={"OMP_WAIT_POLICY": "PASSIVE"})
    return r, out


def exploding(xpl, work, failures):
    for factor, period in ((2, 1e-3), (3, 1e-3), (5, 1e-3), (2, 1e-4)):
        name = f"s4r_sf{factor}_{period:g}"
        r, out = run(xpl, name, deck(factor, period), work)
        msg = (out / f"{name}.msg").read_text()
        sta = (out / f"{name}.sta").read_text()
        summary = json.loads((out / f"{name}.summary.json").read_text())
        with h5py.File(out / f"{name}.h5") as f:
            status, error = f.attrs["status"], f.attrs["error"]
        m = re.search(r"NaN/instability at increment (\d+)", error)
        print(f"{name}: exit {r.returncode}, {status}: {error[:160]}")
        if r.returncode != 3 or status != "failed" or summary["status"] != "failed" or m is None:
            failures.append(f"{name}: exit {r.returncode}, status {status}/{summary['status']}, "
                            f"cause {error!r}: expected a failed run")
            continue
        if int(m.group(1)) >= 10:
            failures.append(f"{name}: stopped at increment {m.group(1)}, after the old warm-up")
        for where, text in (("stderr", r.stderr), (".msg", msg), (".sta", sta)):
            if error not in text:
                failures.append(f"{name}: {where} lacks the cause")


def reported(r, out, name):
    """The largest drift (per cent) as the terminal, .msg, .sta and summary report it."""
    terminal = re.search(r"largest energy balance drift: (\S+) % of the largest energy",
                         r.stdout)
    texts = {"terminal": float(terminal.group(1)) if terminal else None}
    for suffix in ("msg", "sta"):
        m = re.search(r"largest energy balance drift: ETOTAL drift \S+ J, (\S+) % of the largest",
                      (out / f"{name}.{suffix}").read_text())
        texts[suffix] = float(m.group(1)) if m else None
    summary = json.loads((out / f"{name}.summary.json").read_text())
    texts["summary"] = 100.0 * summary["energy_balance"]["relative_error"]
    return texts, summary


def stable(xpl, work, failures):
    name = "s4r_sf1"
    r, out = run(xpl, name, deck(1, 1e-3), work)
    if r.returncode != 0:
        failures.append(f"{name}: exit {r.returncode}: {r.stderr.strip()[-300:]}")
        return
    texts, summary = reported(r, out, name)
    print(f"{name}: completed, {summary['increments']} increments, largest drift (%) {texts}")
    if summary["status"] != "completed":
        failures.append(f"{name}: summary status {summary['status']}")
    if any(v is None for v in texts.values()):
        failures.append(f"{name}: a report lacks the largest drift: {texts}")
        return
    # The texts print four significant digits (format_real; the terminal %.3g).
    for where in ("msg", "sta", "terminal"):
        if abs(texts[where] - texts["summary"]) > 1e-3 * texts["summary"] + 1e-12:
            failures.append(f"{name}: {where} says {texts[where]} %, the summary "
                            f"{texts['summary']} %")
    if texts["summary"] > 0.01:
        failures.append(f"{name}: drift {texts['summary']} % above 0.01 %")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    xpl, work = sys.argv[1], pathlib.Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    failures = []
    exploding(xpl, work, failures)
    stable(xpl, work, failures)
    for f in failures:
        print(f"FAIL: {f}")
    if failures:
        sys.exit(1)
    print("check_energy_start: all passed")


if __name__ == "__main__":
    main()
