#!/usr/bin/python3
"""Deck errors through the xpl command line.

Usage: check_bad_input.py XPL WORK_DIR

Writes small one-element decks into WORK_DIR (emptied first), each broken in a known way,
runs `XPL run DECK -o OUT` in the deck's directory and checks: exit code 1, every expected
`deck.inp:LINE: *KEYWORD:` message on stderr (LINE computed from the deck as written),
the closing "xpl: N error(s) in DECK; nothing was written" line, and that no result file
(.h5, .xdmf, .sta, .msg) was written, neither in OUT nor in the working directory. The
unbroken deck is run first and must pass, so that every error comes from the change made.
"""

import pathlib
import re
import shutil
import subprocess
import sys

BASE = """\
*HEADING
One steel cube on the floor
*NODE
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
*ELEMENT, TYPE=C3D8R, ELSET=CUBE
1, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=BOTTOM
1, 2, 3, 4
*MATERIAL, NAME=STEEL
*DENSITY
7850
*ELASTIC
2e11, 0.3
*SOLID SECTION, ELSET=CUBE, MATERIAL=STEEL
*STEP, NAME=DROP
*DYNAMIC, EXPLICIT
, 1e-6
*BOUNDARY
BOTTOM, 1, 3
*END STEP
"""

RESULT_SUFFIXES = (".h5", ".xdmf", ".sta", ".msg")

# name: (replacements (old line -> new line(s)), expected errors (new line text, keyword)).
# Each expected error is reported on the (first) line of the deck that equals the given text.
CASES = {
    "a_unknown_keyword": (
        {"2e11, 0.3": "2e11, 0.3\n*CONDUCTIVITY\n50.0"},
        [("*CONDUCTIVITY", "*CONDUCTIVITY")]),
    "b_bad_node_number": (
        {"2, 1, 0, 0": "2, 1.0x, 0, 0"},
        [("2, 1.0x, 0, 0", "*NODE")]),
    "c_missing_material": (
        {"*SOLID SECTION, ELSET=CUBE, MATERIAL=STEEL": "*SOLID SECTION, ELSET=CUBE, MATERIAL=IRON"},
        [("*SOLID SECTION, ELSET=CUBE, MATERIAL=IRON", "*SOLID SECTION")]),
    "d_undefined_nset": (
        {"BOTTOM, 1, 3": "TOP, 1, 3"},
        [("TOP, 1, 3", "*BOUNDARY")]),
    "e_missing_node": (
        {"1, 1, 2, 3, 4, 5, 6, 7, 8": "1, 1, 2, 3, 4, 5, 6, 7, 9"},
        [("1, 1, 2, 3, 4, 5, 6, 7, 9", "*ELEMENT")]),
    # Top face first, bottom face second: negative Jacobian everywhere.
    "f_inverted_element": (
        {"1, 1, 2, 3, 4, 5, 6, 7, 8": "1, 5, 6, 7, 8, 1, 2, 3, 4"},
        [("1, 5, 6, 7, 8, 1, 2, 3, 4", "*ELEMENT")]),
    "g_three_errors": (
        {"2, 1, 0, 0": "2, 1.0x, 0, 0",
         "*SOLID SECTION, ELSET=CUBE, MATERIAL=STEEL": "*SOLID SECTION, ELSET=CUBE, MATERIAL=IRON",
         "BOTTOM, 1, 3": "TOP, 1, 3"},
        [("2, 1.0x, 0, 0", "*NODE"),
         ("*SOLID SECTION, ELSET=CUBE, MATERIAL=IRON", "*SOLID SECTION"),
         ("TOP, 1, 3", "*BOUNDARY")]),
    # *DIAGNOSTICS (issue 5): a bad level, a bad switch and an unknown parameter, all reported.
    "h_bad_diagnostics": (
        {"BOTTOM, 1, 3": "BOTTOM, 1, 3\n*DIAGNOSTICS, CONTACT INITIAL OVERCLOSURE=FULL\n"
                         "*DIAGNOSTICS, DETECT CROSSED SURFACES=MAYBE\n*DIAGNOSTICS, WARNING POINT=3"},
        [("*DIAGNOSTICS, CONTACT INITIAL OVERCLOSURE=FULL", "*DIAGNOSTICS"),
         ("*DIAGNOSTICS, DETECT CROSSED SURFACES=MAYBE", "*DIAGNOSTICS"),
         ("*DIAGNOSTICS, WARNING POINT=3", "*DIAGNOSTICS")]),
}

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"check_bad_input.py: FAILED: {message}")
    return condition


def make_deck(replacements):
    lines = BASE.splitlines()
    for old, new in replacements.items():
        if lines.count(old) != 1:
            sys.exit(f"check_bad_input.py: test bug: '{old}' is not exactly once in the base deck")
        lines[lines.index(old)] = new
    return "\n".join(lines) + "\n"


def line_number(text, line):
    lines = text.splitlines()
    if line not in lines:
        sys.exit(f"check_bad_input.py: test bug: '{line}' not in the deck")
    return lines.index(line) + 1


def result_files(*directories):
    found = []
    for directory in directories:
        if directory.exists():
            found += [p.name for p in directory.iterdir() if p.suffix in RESULT_SUFFIXES]
    return found


def run(xpl, directory, *args):
    return subprocess.run([xpl, *args], cwd=directory, capture_output=True, text=True,
                          timeout=60)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    xpl, work = sys.argv[1], pathlib.Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)

    # Control: the unbroken deck passes the data check.
    control = work / "base"
    control.mkdir()
    (control / "base.inp").write_text(BASE)
    result = run(xpl, control, "check", "base.inp", "-o", "out")
    if not check(result.returncode == 0,
                 f"the unbroken deck fails: exit {result.returncode}\n{result.stderr}"):
        sys.exit(1)

    for name, (replacements, expected) in CASES.items():
        case = work / name
        case.mkdir()
        deck = f"{name}.inp"
        text = make_deck(replacements)
        (case / deck).write_text(text)
        for command in ("run", "check"):
            out = case / f"out_{command}"
            result = run(xpl, case, command, deck, "-o", out.name)
            what = f"{command} {name}"
            check(result.returncode == 1,
                  f"{what}: exit code {result.returncode}, expected 1\nstderr:\n{result.stderr}")
            for line, keyword in expected:
                prefix = f"{deck}:{line_number(text, line)}: {keyword}:"
                check(any(l.startswith(prefix) for l in result.stderr.splitlines()),
                      f"{what}: no message starting with '{prefix}' on stderr:\n{result.stderr}")
            messages = [l for l in result.stderr.splitlines() if l.startswith(f"{deck}:")]
            summary = re.search(r"^xpl: (\d+) error\(s\) in (.+); nothing was written$",
                                result.stderr, re.MULTILINE)
            if check(summary is not None, f"{what}: no 'xpl: N error(s) in' line:\n{result.stderr}"):
                check(int(summary.group(1)) == len(messages),
                      f"{what}: summary counts {summary.group(1)} errors, {len(messages)} printed")
                check(int(summary.group(1)) >= len(expected),
                      f"{what}: {summary.group(1)} errors reported, expected {len(expected)}")
                check(summary.group(2) == deck, f"{what}: summary names {summary.group(2)}")
            written = result_files(out, case)
            check(not written, f"{what}: result files written: {written}")
            check(not out.exists(), f"{what}: output directory {out} was created")
            check(result.stdout == "", f"{what}: stdout is not empty:\n{result.stdout}")

    if failures:
        sys.exit(f"check_bad_input.py: {len(failures)} check(s) failed")
    print(f"check_bad_input.py: {len(CASES)} broken decks rejected with exit code 1, "
          f"line-numbered messages and no result files")


if __name__ == "__main__":
    main()
