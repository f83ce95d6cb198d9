#!/usr/bin/python3
"""Energy created by contact stops the run early (issue 20, item 4).

Usage: check_contact_energy.py XPL DECK WORK_DIR

DECK is examples/contact bar_bar_oneway (two steel bars, *CONTACT PAIR). Its HARD law becomes
PRESSURE-OVERCLOSURE=LINEAR with 1.2e14 Pa/m and the step a fixed increment of 4e-7 s
(*DYNAMIC, EXPLICIT, DIRECT USER CONTROL), so the penalty-increment rule cannot shorten it:
the spring is too stiff for the increment (the rule would take x0.74) and pumps energy into
the bars. ETOTAL stays balanced because ALLPW (inside it) goes negative as the kinetic
energy grows; before the contact check the run went on until the kinetic-energy artefact
tripped the ETOTAL check, with 1.5 J (38 % of ALLKE(0)) created. Now it must
- stop with "contact created energy" (springs' stored energy minus ALLPW above 10 % of the
  energy scale), after a warning in the .msg, and exit non-zero;
- be caught early: the energy scale at the stop (the largest of ALLKE, ALLIE, ...) is still
  within 10 % of ALLKE(0) = rho A L v^2 / 2 = 3.925 J, and the created energy is below 20 %
  of it (one or two increments past the 10 % limit).
"""

import pathlib
import re
import subprocess
import sys

KE0 = 0.5 * 7850.0 * 1e-4 * 0.100 * 10.0**2  # bar A: rho A L v^2 / 2, J


def fail(message):
    sys.exit(f"check_contact_energy.py: FAILED: {message}")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    text = source.read_text()
    hard = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n"
    step = "*DYNAMIC, EXPLICIT\n, "
    if hard not in text or step not in text:
        fail(f"{source} has no HARD surface behaviour or *DYNAMIC, EXPLICIT line to replace")
    text = text.replace(hard, "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.2e14\n")
    text = text.replace(step, "*DYNAMIC, EXPLICIT, DIRECT USER CONTROL\n4e-7, ")
    # The bars keep the stiffness hourglass form this test was calibrated with (the default
    # before issue 32): the pumped energy's growth per increment near the stop depends on the
    # bars' modes (with the enhanced default the same increments go 8.4 % -> 24 % in the
    # increment that passes 10 %, against 8.8 % -> 11 %), and the test is about the check.
    sections = re.findall(r"^\*SOLID SECTION, ELSET=\w+, MATERIAL=\w+$", text, flags=re.M)
    if not sections:
        fail(f"{source} has no *SOLID SECTION line to give section controls")
    for line in sections:
        text = text.replace(line, line + ", CONTROLS=CALIBRATED")
    text = text.replace("*MATERIAL", "*SECTION CONTROLS, NAME=CALIBRATED, HOURGLASS=STIFFNESS\n"
                        "*MATERIAL", 1)
    deck = work / "creates.inp"
    deck.write_text(text)
    # This tests the contact check alone: the ETOTAL watchdog (default 10 %, issue 15 item 5)
    # stops this run too, at 14 % drift in the same increments; its old bound of 50 % keeps it
    # out of the way.
    r = subprocess.run([xpl, "run", deck.name, "--threads", "1", "--quiet", "--energy-limit",
                        "50"], cwd=work,
                       capture_output=True, text=True, timeout=120)
    if r.returncode == 0:
        fail("the run completed: the energy created by contact was not caught")
    m = re.search(r"contact created energy: .* so (\S+) J came from contact \((\S+) % of the "
                  r"largest energy (\S+) J\)", r.stderr)
    if not m:
        fail(f"no 'contact created energy' error; stderr: {r.stderr.strip()[-300:]}")
    created, share, scale = float(m.group(1)), float(m.group(2)), float(m.group(3))
    if not 10.0 < share < 20.0:
        fail(f"stopped with {share} % created (expected just past the 10 % limit)")
    if scale > 1.1 * KE0:
        fail(f"caught late: the energy scale had grown to {scale} J (ALLKE(0) = {KE0:.4g} J)")
    msg = (work / "creates.msg").read_text()
    if "WARNING" not in msg or "contact created energy" not in msg:
        fail("no contact-energy warning in the .msg before the stop")
    print(f"check_contact_energy.py: ok: stopped with {created:.3g} J created by contact "
          f"({share} % of {scale:.4g} J; ALLKE(0) = {KE0:.4g} J), warned first")
    return 0


if __name__ == "__main__":
    sys.exit(main())
