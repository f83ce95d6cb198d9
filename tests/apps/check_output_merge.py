#!/usr/bin/python3
"""A variable requested twice in a step is written once (issue 15, item 2).

Usage: check_output_merge.py XPL BAR_DECK OUT_DIR

The bar_impact example gains Abaqus' usual `*OUTPUT, HISTORY, VARIABLE=PRESELECT` with its own
`*ENERGY OUTPUT` (the whole-model energies a second time), the node set FIXED's RF1 in a second
history request, and U in a second `*OUTPUT, FIELD` at a finer interval. `xpl run` and
`xpl check` must both end normally (no HDF5 "name already exists"), each history series
exists once, U is written at the finer interval and S at its own, and the .msg notes the
merges.
"""

import pathlib
import subprocess
import sys

import h5py
import numpy as np


def fail(message):
    sys.exit(f"FAIL: {message}")


EXTRA = """*OUTPUT, HISTORY, VARIABLE=PRESELECT
*NODE OUTPUT, NSET=FIXED
RF1, RF2
*ENERGY OUTPUT
*OUTPUT, FIELD, TIME INTERVAL=2e-6
*NODE OUTPUT
U
*END STEP"""


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, bar, out = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    out.mkdir(parents=True, exist_ok=True)
    text = bar.read_text()
    if text.count("*END STEP") != 1:
        fail("the example changed: expected one *END STEP")
    deck = out / "merged.inp"
    deck.write_text(text.replace("*END STEP", EXTRA))

    for command, status in (("run", "completed"), ("check", "checked")):
        results = out / command
        run = subprocess.run([xpl, command, str(deck), "-o", str(results), "--threads", "1",
                              "--quiet"], capture_output=True, text=True, timeout=60)
        if run.returncode != 0:
            fail(f"xpl {command} exited {run.returncode}: {run.stderr}")
        with h5py.File(results / "merged.h5", "r") as f:
            if f.attrs["status"] != status or f.attrs["error"] != "":
                fail(f"{command}: status {f.attrs['status']!r}, error {f.attrs['error']!r}")
            history = f["history/step_1"]
            names = []
            history.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset)
                               else None)
            for expected in ("energy/ALLKE", "energy/ETOTAL", "node/FIXED/RF1",
                             "node/FIXED/RF2", "node/FREE_END/U1"):
                if expected not in names:
                    fail(f"{command}: history {expected} missing (have {names})")
            if command == "run":
                # Rows at the finer history interval (2e-7 s requested, so every increment of
                # ~4.2e-7 s): far more than the 200 rows of the PRESELECT default.
                time = np.asarray(history["time"])
                if len(time) < 200 or np.max(np.diff(time)) > 5e-7:
                    fail(f"history rows: {len(time)}, largest gap {np.max(np.diff(time))} s")
                frames = f["frames"]
                with_u = [k for k in frames if "U" in frames[k]]
                with_s = [k for k in frames if "S" in frames[k]]
                # 1e-4 s step: U every 2e-6 s (50 + frame 0), S every 1e-5 s (10 + frame 0).
                if len(with_u) != 51 or len(with_s) != 11:
                    fail(f"frames with U: {len(with_u)} (expected 51), with S: {len(with_s)} "
                         "(expected 11)")
        msg = (results / "merged.msg").read_text()
        for note in ("asks again for ALLKE, ALLKD, ALLSE, ALLAE, ALLIE, ALLVD, ALLWK, ETOTAL, "
                     "FIXED/RF1",
                     "asks again for U (also requested at",
                     "written once, at the finer interval 2e-06 s"):
            if note not in msg:
                fail(f"{command}: .msg lacks the note '{note}'")
    print("ok: PRESELECT + *ENERGY OUTPUT, a node set twice and U twice merged in run and check")


if __name__ == "__main__":
    main()
