#!/usr/bin/python3
"""Deck errors through the xpl command line.

Usage: check_bad_input.py XPL WORK_DIR

Writes small decks into WORK_DIR (emptied first): a one-element cube, or for the contact
clearance cases a cube under a two-shell sheet, each broken in a known way,
runs `XPL run DECK -o OUT` in the deck's directory and checks: exit code 1, every expected
`deck.inp:LINE: *KEYWORD:` message on stderr (LINE computed from the deck as written),
the closing "xpl: N error(s) in DECK; nothing was written" line, and that no result file
(.h5, .xdmf, .sta, .msg) was written, neither in OUT nor in the working directory. The
unbroken decks are checked first and must pass, so that every error comes from the change
made.
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

# Contact clearances (SPEC C7-C10): a cube under a two-shell sheet (z = 1.5, normals +z, SNEG
# facing the cube), a nodal distribution, both manual forms of the *CONTACT CLEARANCE lines
# (SEARCH ABOVE= on a data line; a trailing comma) and assignments in the first step.
CLEARANCE_BASE = """\
*HEADING
A steel cube under a steel sheet, with contact clearances
*NODE
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
11, 0, 0, 1.5
12, 0.5, 0, 1.5
13, 1, 0, 1.5
14, 0, 1, 1.5
15, 0.5, 1, 1.5
16, 1, 1, 1.5
*ELEMENT, TYPE=C3D8R, ELSET=CUBE
1, 1, 2, 3, 4, 5, 6, 7, 8
*ELEMENT, TYPE=S4R, ELSET=PLATE
11, 11, 12, 15, 14
12, 12, 13, 16, 15
*NSET, NSET=BOTTOM
1, 2, 3, 4
*MATERIAL, NAME=STEEL
*DENSITY
7850
*ELASTIC
2e11, 0.3
*SOLID SECTION, ELSET=CUBE, MATERIAL=STEEL
*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL
0.01
*SURFACE, NAME=BLOCK
CUBE
*SURFACE, NAME=SHEET
PLATE, SNEG
*DISTRIBUTION, NAME=GAPS, LOCATION=NODE
, 0.0
11, 0.001
*CONTACT CLEARANCE, NAME=C1, ADJUST=YES, SEARCH BELOW=0.2
SEARCH ABOVE=0.0
*CONTACT CLEARANCE, NAME=C2, ADJUST=NO, SEARCH BELOW=1.5,
SEARCH ABOVE=0.0, CLEARANCE=GAPS
*STEP, NAME=DROP
*DYNAMIC, EXPLICIT
, 1e-6
*BOUNDARY
BOTTOM, 1, 3
*CONTACT
*CONTACT INCLUSIONS, ALL EXTERIOR
*CONTACT CLEARANCE ASSIGNMENT
BLOCK, SHEET, C1
SHEET, BLOCK, C2, MASTER
*END STEP
*STEP, NAME=HOLD
*DYNAMIC, EXPLICIT
, 1e-6
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

# Broken forms of CLEARANCE_BASE, as CASES; an expected error may also give a text that the
# message must contain.
C1_LINE = "*CONTACT CLEARANCE, NAME=C1, ADJUST=YES, SEARCH BELOW=0.2"
ASSIGNMENT = "*CONTACT CLEARANCE ASSIGNMENT"
CLEARANCE_CASES = {
    "ca_negative_on_solid": (
        {C1_LINE: C1_LINE + ", CLEARANCE=-0.01"},
        [("BLOCK, SHEET, C1", ASSIGNMENT, "clearance C1 is negative (-0.01)")]),
    "cb_unknown_clearance": (
        {"BLOCK, SHEET, C1": "BLOCK, SHEET, C9"},
        [("BLOCK, SHEET, C9", ASSIGNMENT, "undefined contact clearance C9")]),
    "cc_unknown_surface": (
        {"BLOCK, SHEET, C1": "BLOCK, SHEETS, C1"},
        [("BLOCK, SHEETS, C1", ASSIGNMENT, "undefined surface SHEETS")]),
    "cd_self_contact": (
        {"BLOCK, SHEET, C1": "SHEET, SHEET, C1"},
        [("SHEET, SHEET, C1", ASSIGNMENT, "self contact of surface SHEET")]),
    # A fin (element 13) standing on the sheet's middle edge, nodes 12 and 15.
    "ce_edge_on_three_faces": (
        {"16, 1, 1, 1.5": "16, 1, 1, 1.5\n17, 0.5, 0, 2.5\n18, 0.5, 1, 2.5",
         "12, 12, 13, 16, 15": "12, 12, 13, 16, 15\n13, 12, 15, 18, 17"},
        [("BLOCK, SHEET, C1", ASSIGNMENT, "surface SHEET has the edge of nodes 12 and 15 on 3")]),
    "cf_flipped_normals": (
        {"PLATE, SNEG": "11, SNEG\n12, SPOS"},
        [("BLOCK, SHEET, C1", ASSIGNMENT,
          "surface SHEET has discontinuous normals: elements 11 and 12")]),
    "cg_double_sided": (
        {"PLATE, SNEG": "PLATE"},
        [("BLOCK, SHEET, C1", ASSIGNMENT, "surface SHEET is not single sided")]),
    # Contact of DROP carries over into HOLD: no clearance there, not even ADJUST=NO.
    "ch_contact_carried_over": (
        {"*STEP, NAME=HOLD": "*STEP, NAME=HOLD\n*CONTACT\n*CONTACT CLEARANCE ASSIGNMENT\n"
                             "BLOCK, SHEET, C2"},
        [("BLOCK, SHEET, C2", ASSIGNMENT,
          "clearances apply only when a step's contact domain is built new")]),
    # Contact only from HOLD on: a new domain, but ADJUST=YES moves nodes in the first step only.
    "ci_adjust_in_later_step": (
        {"*CONTACT": "", "*CONTACT INCLUSIONS, ALL EXTERIOR": "", ASSIGNMENT: "",
         "BLOCK, SHEET, C1": "", "SHEET, BLOCK, C2, MASTER": "",
         "*STEP, NAME=HOLD": "*STEP, NAME=HOLD\n*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
                             "*CONTACT CLEARANCE ASSIGNMENT\nSHEET, BLOCK, C2, MASTER\n"
                             "SHEET, BLOCK, C1, MASTER"},
        [("SHEET, BLOCK, C1, MASTER", ASSIGNMENT, "expected ADJUST=NO")]),
    "cj_bad_adjust": (
        {C1_LINE: "*CONTACT CLEARANCE, NAME=C1, ADJUST=SOMETIMES, SEARCH BELOW=0.2"},
        [("*CONTACT CLEARANCE, NAME=C1, ADJUST=SOMETIMES, SEARCH BELOW=0.2", "*CONTACT CLEARANCE",
          "bad ADJUST=SOMETIMES")]),
    "ck_element_distribution": (
        {"*DISTRIBUTION, NAME=GAPS, LOCATION=NODE": "*DISTRIBUTION, NAME=GAPS, LOCATION=ELEMENT"},
        [("*DISTRIBUTION, NAME=GAPS, LOCATION=ELEMENT", "*DISTRIBUTION",
          "LOCATION=ELEMENT is not supported")]),
    # The sheet on a rigid body, as the only slave surface (MASTER: surface 2 is the slave).
    "cl_rigid_slave": (
        {"*NSET, NSET=BOTTOM": "*NODE\n100, 5, 5, 5\n*RIGID BODY, REF NODE=100, ELSET=PLATE\n"
                               "*NSET, NSET=BOTTOM",
         "BLOCK, SHEET, C1": "BLOCK, SHEET, C1, MASTER"},
        [("BLOCK, SHEET, C1, MASTER", ASSIGNMENT, "slave surface SHEET lies wholly on rigid")]),
    "cm_stray_data_line": (
        {"SEARCH ABOVE=0.0": "0.0"},
        [("0.0", "*CONTACT CLEARANCE", "unexpected data line")]),
    # Several at once: all reported.
    "cn_three_errors": (
        {C1_LINE: "*CONTACT CLEARANCE, NAME=C1, ADJUST=SOMETIMES, SEARCH BELOW=0.2",
         "*DISTRIBUTION, NAME=GAPS, LOCATION=NODE": "*DISTRIBUTION, NAME=GAPS, LOCATION=ELEMENT",
         "SHEET, BLOCK, C2, MASTER": "SHEET, BLOCK, C2, MASTER, BOTH"},
        [("*CONTACT CLEARANCE, NAME=C1, ADJUST=SOMETIMES, SEARCH BELOW=0.2", "*CONTACT CLEARANCE",
          "bad ADJUST=SOMETIMES"),
         ("*DISTRIBUTION, NAME=GAPS, LOCATION=ELEMENT", "*DISTRIBUTION",
          "LOCATION=ELEMENT is not supported"),
         ("SHEET, BLOCK, C2, MASTER, BOTH", ASSIGNMENT, "too many values (5)")]),
}

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"check_bad_input.py: FAILED: {message}")
    return condition


def make_deck(base, replacements):
    lines = base.splitlines()
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

    # Control: the unbroken decks pass the data check (the clearance deck with its clearances).
    for name, base in (("base", BASE), ("clearance_base", CLEARANCE_BASE)):
        control = work / name
        control.mkdir()
        (control / f"{name}.inp").write_text(base)
        result = run(xpl, control, "check", f"{name}.inp", "-o", "out")
        if not check(result.returncode == 0,
                     f"the unbroken deck {name} fails: exit {result.returncode}\n{result.stderr}"):
            sys.exit(1)

    cases = [(BASE, name, case) for name, case in CASES.items()]
    cases += [(CLEARANCE_BASE, name, case) for name, case in CLEARANCE_CASES.items()]
    for base, name, (replacements, expected) in cases:
        case = work / name
        case.mkdir()
        deck = f"{name}.inp"
        text = make_deck(base, replacements)
        (case / deck).write_text(text)
        for command in ("run", "check"):
            out = case / f"out_{command}"
            result = run(xpl, case, command, deck, "-o", out.name)
            what = f"{command} {name}"
            check(result.returncode == 1,
                  f"{what}: exit code {result.returncode}, expected 1\nstderr:\n{result.stderr}")
            for line, keyword, *contains in expected:
                prefix = f"{deck}:{line_number(text, line)}: {keyword}:"
                words = contains[0] if contains else ""
                check(any(l.startswith(prefix) and words in l for l in result.stderr.splitlines()),
                      f"{what}: no message starting with '{prefix}' and containing '{words}' on "
                      f"stderr:\n{result.stderr}")
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
    print(f"check_bad_input.py: {len(cases)} broken decks rejected with exit code 1, "
          f"line-numbered messages and no result files")


if __name__ == "__main__":
    main()
