#!/usr/bin/python3
"""Contact does not lower the stable increment (C1, issue 4).

Usage: check_dt_contact.py XPL DECK WORK_DIR

Runs DECK as it is and a copy without its *CONTACT / *CONTACT INCLUSIONS lines, and checks
that the stable increment is the same before contact (to 1e-12) and at most 1 % smaller
during it, and that both runs take the same number of increments within 1 %. Contact in xpl
never enters the increment with the default penalty (k = 0.5 m_eff / dt^2 is tied to it); what
changes it is the physics: the impacted bars are compressed (strain sigma/E = 0.1 % for
bar_bar), which shortens their elements by as much. A penalty that limited the increment
would show up as a cut of tens of percent. The contact run must complete (stable; the energy
checks of check_contact.py cover its accuracy).
"""

import pathlib
import re
import shutil
import subprocess
import sys


def sta_increments(path):
    rows = []
    for line in path.read_text().splitlines():
        m = re.match(r"^\s+\d+\s+(\d+)\s+([-\d.E+]+)\s+[-\d.E+]+\s+([-\d.E+]+)", line)
        if m:
            rows.append((int(m.group(1)), float(m.group(2)), float(m.group(3))))
    return rows


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, deck, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    lines = deck.read_text().splitlines()
    kept = [l for l in lines if not re.match(r"^\*CONTACT(\s*,|\s*$|\s+INCLUSIONS)", l, re.I)]
    if len(kept) == len(lines):
        sys.exit("check_dt_contact.py: the deck has no *CONTACT")
    (work / "with.inp").write_text("\n".join(lines) + "\n")
    (work / "without.inp").write_text("\n".join(kept) + "\n")
    for name in ("with", "without"):
        r = subprocess.run([xpl, "run", f"{name}.inp", "-q"], cwd=work, capture_output=True,
                           text=True, timeout=300)
        if r.returncode != 0:
            sys.exit(f"check_dt_contact.py: FAILED: run {name} contact: {r.stderr}")
    a, b = sta_increments(work / "with.sta"), sta_increments(work / "without.sta")
    if not a or not b:
        sys.exit("check_dt_contact.py: FAILED: no status lines")
    n_a, n_b = a[-1][0], b[-1][0]
    if abs(n_a / n_b - 1) > 0.01:
        sys.exit(f"check_dt_contact.py: FAILED: {n_a} increments with contact, {n_b} without")
    print(f"check_dt_contact.py: ok: {n_a} increments with contact, {n_b} without (1 %)")
    dt_b = {inc: dt for inc, _, dt in b[:-1]}  # the last line is the increment landing on the end
    common = [(dt, dt_b[inc]) for inc, _, dt in a[:-1] if inc in dt_b]
    first = common[0]
    if abs(first[0] / first[1] - 1) > 1e-12:
        sys.exit(f"check_dt_contact.py: FAILED: first increments differ: {first}")
    worst = min(x / y for x, y in common)
    if worst < 0.99:
        sys.exit(f"check_dt_contact.py: FAILED: contact lowers the increment to {worst:.4f} of "
                 "the run without contact")
    print(f"check_dt_contact.py: ok: first increment identical; during contact the increment is "
          f"at least {worst:.4f} of the run without contact (>= 0.99) at {len(common)} status lines")

if __name__ == "__main__":
    main()
