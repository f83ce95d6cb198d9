#!/usr/bin/python3
"""The pinched sheet released and pinched again (issue 32, item 2; SPEC C3, R5).

Usage: check_pinch_reclose.py XPL PINCHED_DECK WORK_DIR

PINCHED_DECK is examples/overclosure's pinched deck: an S4R sheet (t = 0.2 mm) between two rigid
dies 0.1 mm apart, every sheet node stored as a pinched offset of 0.05 mm, held for one step.
Its step is followed here by two more: OPEN, the dies driven apart at 1 m/s (ramped over 10 us,
100 us long: 0.1 mm each), and CLOSE, driven back the same way. The sheet's offsets are spent
as the dies leave; when they come back, the sheet is pressed from both sides at once by
springs that start from zero (the touch is new) and hold it: a node held by two faces must be
stable with the sum of its springs. Checked: the run completes (the contact-energy check on,
as always), ETOTAL stays balanced to 1e-3 of the largest energy, the dies press the sheet at
the end (CFN > 0 in the last rows of CLOSE), no sheet node leaves the gap between the dies.
"""

import pathlib
import subprocess
import sys

import h5py
import numpy as np

TAIL = """*NSET, NSET=LOWREF
190001
*NSET, NSET=HIGHREF
290001
*AMPLITUDE, NAME=RAMP
0., 0., 1e-5, 1.
{held_step}*STEP, NAME=OPEN
*DYNAMIC, EXPLICIT
, 0.0001
*BOUNDARY, TYPE=VELOCITY, AMPLITUDE=RAMP
LOWREF, 3, 3, -1.0
HIGHREF, 3, 3, 1.0
*BOUNDARY
LOWREF, 1, 2
LOWREF, 4, 6
HIGHREF, 1, 2
HIGHREF, 4, 6
*OUTPUT, HISTORY, TIME INTERVAL=2e-06
*ENERGY OUTPUT
*END STEP
*STEP, NAME=CLOSE
*DYNAMIC, EXPLICIT
, 0.0001
*BOUNDARY, TYPE=VELOCITY, AMPLITUDE=RAMP
LOWREF, 3, 3, 1.0
HIGHREF, 3, 3, -1.0
*OUTPUT, HISTORY, TIME INTERVAL=2e-06
*ENERGY OUTPUT
*END STEP
"""


def fail(message):
    sys.exit(f"check_pinch_reclose.py: FAILED: {message}")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    text = source.read_text()
    at = text.index("*STEP")
    held = text[at:]
    if held.count("*STEP") != 1 or "*END STEP" not in held:
        fail(f"{source} does not end with its one step")
    work.mkdir(parents=True, exist_ok=True)
    deck = work / "pinch_reclose.inp"
    deck.write_text(text[:at] + TAIL.format(held_step=held))
    run = subprocess.run([xpl, "run", str(deck), "-o", str(work), "--quiet"], capture_output=True,
                         text=True, timeout=300)
    with h5py.File(work / "pinch_reclose.h5", "r") as f:
        status = f.attrs["status"]
        if status != "completed":
            fail(f"status {status}: {f.attrs.get('error', '')} (exit {run.returncode})")
        steps = sorted(f["history"].keys())
        if len(steps) != 3:
            fail(f"history of {len(steps)} steps, expected 3")
        etotal = np.concatenate([f[f"history/{s}/energy/ETOTAL"][:] for s in steps])
        scale = max(np.abs(f[f"history/{s}/energy/{e}"][:]).max() for s in steps
                    for e in ("ALLKE", "ALLIE", "ALLWK"))
        drift = np.abs(etotal - etotal[0]).max()
        if not drift <= 1e-3 * scale:
            fail(f"ETOTAL drift {drift:.3e} J above 1e-3 of the largest energy {scale:.3e} J")
        cfn = f[f"history/{steps[2]}/contact/ALL_EXTERIOR/CFN"][:]
        if not np.all(np.abs(cfn[-5:]) > 0.0):
            fail(f"the dies do not press the sheet at the end of CLOSE (CFN {cfn[-5:]})")
        ids = f["mesh/node_ids"][:]
        x = f["mesh/coordinates"][:] + f["frames"][sorted(f["frames"])[-1]]["U"][:]
        sheet = ids // 100000 == 3
        low = x[ids // 100000 == 1, 2].max()
        high = x[ids // 100000 == 2, 2].min()
        z = x[sheet, 2]
        if not (z.min() > low - 0.1e-3 and z.max() < high + 0.1e-3):
            fail(f"sheet nodes at z {z.min():.3e}..{z.max():.3e} m outside the dies' faces "
                 f"{low:.3e}..{high:.3e} m by more than half the sheet")
    msg = (work / "pinch_reclose.msg").read_text()
    if "contact created energy" in msg:
        fail("the .msg warns of energy created by contact")
    print(f"check_pinch_reclose.py: ok: completed, ETOTAL drift {drift:.2e} J of {scale:.3e} J, "
          f"CFN at the end {abs(cfn[-1]):.4g} N, the sheet between the dies")


if __name__ == "__main__":
    main()
