#!/usr/bin/python3
"""A deck's own penalty stiffness in the stable increment (issue 15, item 4).

Usage: check_penalty_increment.py XPL DECK WORK_DIR

DECK is examples/contact bar_bar_oneway (two equal steel bars, CalculiX-style *CONTACT PAIR).
Its HARD law is replaced by PRESSURE-OVERCLOSURE=LINEAR with a slope of 1e14 Pa/m, the stiff
slope a CalculiX deck carries (about E/h: the bars' 2.5 mm elements give E/h = 8e13 Pa/m).
Before the springs entered the increment this deck stopped at first contact with "energy
balance lost" at scale factor 1 (and ran only from 0.8 down); now it must
- run at scale factor 1 with the bar-on-bar answers of check_contact.py: interface stress
  rho c0 v/2 within 3 %, ETOTAL drift < 1 % of ALLKE(0), ALLPW back below 0.5 % of
  ALLKE(0) after separation (what is left is the springs' stepping error, also in the drift;
  the default penalty's 2 % of its peak does not apply: this spring stores a third as much), velocities exchanged within 0.3 m/s (check_contact.py's 0.2 m/s is for
  the default penalty: the stiff spring leaves 0.21 m/s of ringing in bar A at scale factors
  0.5, 0.8 and 1 alike, so it is the spring's, not the increment's);
- say so in the .msg (the interaction, the increment and the factor on the elements') and name
  the critical contact node in the .sta, with increments shorter than the elements' only while
  the bars touch (elsewhere the same as the HARD deck's, to 1e-12);
- be announced by `xpl check` as a warning;
and the same deck with a slope of 1e13 Pa/m (no stiffer than the default penalty) must leave
the increment alone: no message, the increments before contact as the HARD deck's.
"""

import math
import pathlib
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np


def fail(message):
    sys.exit(f"check_penalty_increment.py: FAILED: {message}")


def ok(message):
    print(f"check_penalty_increment.py: ok: {message}")


def run(xpl, deck, command="run"):
    r = subprocess.run([xpl, command, deck.name, "--threads", "1", "-q"], cwd=deck.parent,
                       capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        fail(f"xpl {command} {deck}: exit code {r.returncode}: {r.stderr.strip()[-400:]}")


def sta_rows(path):
    """(increment, total time, increment length, critical column) of every status line."""
    rows = []
    for line in path.read_text().splitlines():
        m = re.match(r"^\s+\d+\s+(\d+)\s+([-\d.E+]+)\s+[-\d.E+]+\s+([-\d.E+]+)\s+(node \d+|\d+)\s",
                     line)
        if m:
            rows.append((int(m.group(1)), float(m.group(2)), float(m.group(3)), m.group(4)))
    return rows


def linear_deck(source, target, slope):
    text = source.read_text()
    hard = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n"
    if hard not in text:
        fail(f"{source} has no HARD surface behaviour to replace")
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(text.replace(hard, f"*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                                         f"{slope:g}\n"))


def bar_answers(path):
    """The bar-on-bar answers (docstring) on the results file `path`."""
    rho, c0 = 7850.0, math.sqrt(200e9 / 7850.0)
    with h5py.File(path, "r") as f:
        h = f["history/step_1"]
        force = h["contact/A_END-B_END/CFN"][:]
        stress = np.median(force[force > 0.5 * force.max()]) / 1e-4
        expected = rho * c0 * 10.0 / 2.0
        if abs(stress / expected - 1) > 0.03:
            fail(f"interface stress {stress / 1e6:.1f} MPa, not {expected / 1e6:.1f} MPa (3 %)")
        e = h["energy"]
        drift = np.abs(e["ETOTAL"][:] - e["ETOTAL"][0]).max() / e["ALLKE"][0]
        if drift > 0.01:
            fail(f"ETOTAL drift {100 * drift:.2f} % of ALLKE(0) (limit 1 %)")
        pw = e["ALLPW"][:]
        if not (pw.max() > 0 and abs(pw[-1]) < 0.005 * e["ALLKE"][0]):
            fail(f"ALLPW {pw[-1]:.3g} J at the end, ALLKE(0) {e['ALLKE'][0]:.3g} J (0.5 %)")
        frame = f["frames"][sorted(f["frames"].keys())[-1]]
        x0 = f["mesh/coordinates"][:, 0]
        v = frame["V"][:, 0]
        v_a, v_b = v[x0 < 0.1005].mean(), v[x0 > 0.1005].mean()
        if abs(v_a) > 0.3 or abs(v_b - 10.0) > 0.3:
            fail(f"after contact v_A = {v_a:.3f} m/s, v_B = {v_b:.3f} m/s (0 and 10, 0.3 m/s)")
    ok(f"LINEAR 1e14 Pa/m at scale factor 1: interface stress {stress / 1e6:.1f} MPa "
       f"({expected / 1e6:.1f}), ETOTAL drift {100 * drift:.2f} % of ALLKE(0), ALLPW at the end "
       f"{pw[-1]:.3g} J of a {pw.max():.3g} J peak, v_A {v_a:.3f} m/s, v_B {v_b:.3f} m/s")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl = str(pathlib.Path(sys.argv[1]).resolve())
    source, work = pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    hard = work / "hard" / source.name
    hard.parent.mkdir(parents=True)
    shutil.copy(source, hard)
    run(xpl, hard)
    reference = {inc: dt for inc, _, dt, _ in sta_rows(hard.with_suffix(".sta"))}

    # The stiff slope: runs, balanced, reported.
    stiff = work / "stiff" / source.name
    linear_deck(source, stiff, 1e14)
    run(xpl, stiff)
    bar_answers(stiff.with_suffix(".h5"))
    msg = stiff.with_suffix(".msg").read_text()
    m = re.search(r"interaction STEEL \(PRESSURE-OVERCLOSURE=LINEAR, slope 1e\+14 Pa/m\) governs "
                  r"the stable increment from t = ([-\d.e+]+) s .*contact node (\d+): "
                  r"([-\d.e+]+) s instead of the elements' ([-\d.e+]+) s \(x([\d.]+)\)", msg)
    if not m:
        fail("the .msg does not say that interaction STEEL governs the increment")
    start, factor = float(m.group(1)), float(m.group(5))
    # The bars touch at gap/v = 100 us; the springs count from two increments before.
    if not 99e-6 < start < 100.5e-6:
        fail(f"contact governs from t = {start:.4g} s, not at first contact (100 us)")
    if not 0.5 < factor < 0.95:
        fail(f"the increment factor {factor} is not the expected cut (0.5 to 0.95)")
    ok(f"the .msg: STEEL governs from t = {start:.4g} s at x{factor} of the elements' increment")
    if "governed the stable increment for" not in msg:
        fail("the .msg has no summary of the span in which contact governed")
    rows = sta_rows(stiff.with_suffix(".sta"))
    governed = [(inc, t, dt) for inc, t, dt, crit in rows if crit.startswith("node ")]
    if not governed:
        fail("no .sta line names a critical contact node")
    # Contact lasts 2L/c0 = 39.6 us from 100 us; the limit is held for 50 short increments after.
    first, last = governed[0][1], governed[-1][1]
    if not (99e-6 < first < 101e-6 and 139e-6 < last < 160e-6):
        fail(f"contact nodes are critical from {first:.4g} s to {last:.4g} s, not while the "
             "bars touch (100 to 139.6 us and the hold after)")
    before = [(inc, dt) for inc, t, dt, crit in rows if t < 99e-6 and inc in reference]
    if any(abs(dt / reference[inc] - 1) > 1e-12 for inc, dt in before):
        fail("the increments before contact differ from the HARD deck's")
    ok(f"{len(governed)} .sta lines name a contact node ({first * 1e6:.2f} to {last * 1e6:.2f} "
       f"us); the {len(before)} lines before contact match the HARD deck's increments")
    # 153 us to the end of the step (160 us), the last increment landing on it left out.
    window = lambda rows: [dt for _, t, dt, crit in rows[:-1] if t > 153e-6 and
                           not crit.startswith("node ")]
    late, late_hard = window(rows), window(sta_rows(hard.with_suffix(".sta")))
    if not late or not late_hard or min(late) < 0.99 * min(late_hard):
        fail("the increment does not return to the elements' after contact")
    ok("after contact the increment returns to the elements' value")

    # xpl check warns of it.
    run(xpl, stiff, "check")
    msg = stiff.with_suffix(".msg").read_text()
    if not re.search(r"WARNING: .*penalty of interaction STEEL .* will govern the stable "
                     r"increment while in contact", msg):
        fail("xpl check does not warn that the penalty will govern the increment")
    ok("xpl check warns that STEEL's penalty will govern the increment")

    # A slope no stiffer than the default penalty leaves every increment alone.
    soft = work / "soft" / source.name
    linear_deck(source, soft, 1e13)
    run(xpl, soft)
    if "governs the stable increment" in soft.with_suffix(".msg").read_text():
        fail("a 1e13 Pa/m slope (softer than the default penalty) governs the increment")
    rows = sta_rows(soft.with_suffix(".sta"))
    same = [abs(dt / reference[inc] - 1) <= 1e-12 for inc, t, dt, _ in rows[:-1]
            if inc in reference and t < 99e-6]
    if not same or not all(same):
        fail("a 1e13 Pa/m slope changes the increments before contact")
    ok("a 1e13 Pa/m slope leaves the increment to the elements")
    return 0


if __name__ == "__main__":
    sys.exit(main())
